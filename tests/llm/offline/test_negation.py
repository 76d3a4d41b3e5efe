"""Negation read by the offline translator: always avoid, never, don't, neither / nor, off limits, until,
trailing avoidance, partial prohibitions.

Each sentence of ``corpus/negation.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_negation_read_or_refused = corpus_test("negation")
