"""Actions read by the offline translator: verbs, idioms, polite wrappers, carrying (X to Y), purpose clauses,
refused verbs.

Each sentence of ``corpus/actions.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_actions_read_or_refused = corpus_test("actions")
