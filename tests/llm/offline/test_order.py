"""Order read by the offline translator: then, first, before that, last, after / before X, once done, on the
way, via, comma lists, order remarks, only after.

Each sentence of ``corpus/order.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.llm.offline.evaluation import EvalMission
from tests.llm.offline.corpus import cases, check


@pytest.mark.parametrize("mission", cases("order"))
def test_order_read_or_refused(mission: EvalMission) -> None:
    check(mission)
