"""The offline translator on what people put around and between the instructions (sign-offs, greetings,
contractions, headings, context, self-corrections, shorthand): ``corpus/surroundings.jsonl`` holds our own
phrasings, each read to its gold formula or refused with its reason."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_surroundings = corpus_test("surroundings")
