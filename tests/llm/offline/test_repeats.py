"""Repeated visits read by the offline translator: again, back to, twice, N times, with Y in between.

Each sentence of ``corpus/repeats.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_repeats_read_or_refused = corpus_test("repeats")
