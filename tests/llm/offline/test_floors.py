"""Floors read by the offline translator: on floor k, upstairs, the floor above, stay on this floor, floor
moves, the same floor, up there.

Each sentence of ``corpus/floors.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.llm.offline.evaluation import EvalMission
from tests.llm.offline.corpus import cases, check


@pytest.mark.parametrize("mission", cases("floors"))
def test_floors_read_or_refused(mission: EvalMission) -> None:
    check(mission)
