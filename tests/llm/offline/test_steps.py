"""The clauses and the order of steps as people write them (branch `steps`): a closing *when you're
done*, *once you've done that / both*, *after all that* opening a sentence, learners' order words.

Each sentence of ``corpus/steps.jsonl`` must mean its gold formula or be refused with its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_steps_read_or_refused = corpus_test("steps")
