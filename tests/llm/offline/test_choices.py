"""Conjunction and choice read by the offline translator: and, or, either, any, one of, choice remarks, a
phrase named twice.

Each sentence of ``corpus/choices.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_choices_read_or_refused = corpus_test("choices")
