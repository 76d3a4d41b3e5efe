"""The offline translator on the styles people write to robots in, each a corpus of our own phrasings
(``corpus/style_<style>.jsonl``): every sentence means its gold formula or gets its refusal."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_shorthand = corpus_test("style_shorthand")
