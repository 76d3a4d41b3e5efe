"""Back-references read by the offline translator: it, them, its, there, in there, that X, the same X, the
other X, the one.

Each sentence of ``corpus/back_references.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_back_references_read_or_refused = corpus_test("back_references")
