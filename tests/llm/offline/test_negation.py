"""Negation read by the offline translator: always avoid, never, don't, neither / nor, off limits, until,
trailing avoidance, partial prohibitions.

Each sentence of ``corpus/negation.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_negation_read_or_refused = corpus_test("negation")

test_negated_verbs_read_or_refused = corpus_test("negated_verbs")
"""corpus/negated_verbs.jsonl: a negation is read with the verbs it knows (a place to avoid, or a goal not to
miss), and refused with any other verb."""
