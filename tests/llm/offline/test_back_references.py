"""Back-references read by the offline translator: it, them, its, there, in there, that X, the same X, the
other X, the one.

Each sentence of ``corpus/back_references.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.llm.offline.evaluation import EvalMission
from tests.llm.offline.corpus import cases, check


@pytest.mark.parametrize("mission", cases("back_references"))
def test_back_references_read_or_refused(mission: EvalMission) -> None:
    check(mission)
