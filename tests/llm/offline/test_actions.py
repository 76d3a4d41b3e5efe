"""Actions read by the offline translator: verbs, idioms, polite wrappers, carrying (X to Y), purpose clauses,
refused verbs.

Each sentence of ``corpus/actions.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.llm.offline.evaluation import EvalMission
from tests.llm.offline.corpus import cases, check


@pytest.mark.parametrize("mission", cases("actions"))
def test_actions_read_or_refused(mission: EvalMission) -> None:
    check(mission)
