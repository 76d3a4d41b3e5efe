"""Order read by the offline translator: then, first, before that, last, after / before X, once done, on the
way, via, comma lists, order remarks, only after.

Each sentence of ``corpus/order.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_order_read_or_refused = corpus_test("order")
