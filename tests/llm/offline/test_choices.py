"""Conjunction and choice read by the offline translator: and, or, either, any, one of, choice remarks, a
phrase named twice.

Each sentence of ``corpus/choices.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.llm.offline.evaluation import EvalMission
from tests.llm.offline.corpus import cases, check


@pytest.mark.parametrize("mission", cases("choices"))
def test_choices_read_or_refused(mission: EvalMission) -> None:
    check(mission)
