"""Repeated visits read by the offline translator: again, back to, twice, N times, with Y in between.

Each sentence of ``corpus/repeats.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.llm.offline.evaluation import EvalMission
from tests.llm.offline.corpus import cases, check


@pytest.mark.parametrize("mission", cases("repeats"))
def test_repeats_read_or_refused(mission: EvalMission) -> None:
    check(mission)
