"""Noun phrases of everyday speech read by the offline translator: *the bathroom next door*, *the plant
bedroom*, *out of the fridge*, *1 of the chairs*, *it* after a choice carried to a place.

Each sentence of ``corpus/everyday_nouns.jsonl`` must mean its gold formula or be refused with its
fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_everyday_nouns_read_or_refused = corpus_test("everyday_nouns")
