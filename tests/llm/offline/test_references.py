"""The noun phrase and what it refers to (``corpus/references.jsonl``): objects placed by other objects,
where a carried thing goes, a room's contents in any form of *have*, *the <room> one*, each read or refused
as its case says."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_references_read_or_refused = corpus_test("references")
