"""Negation read by the offline translator: always avoid, never, don't, neither / nor, off limits, until,
trailing avoidance, partial prohibitions.

Each sentence of ``corpus/negation.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.llm.offline.evaluation import EvalMission
from tests.llm.offline.corpus import cases, check


@pytest.mark.parametrize("mission", cases("negation"))
def test_negation_read_or_refused(mission: EvalMission) -> None:
    check(mission)
