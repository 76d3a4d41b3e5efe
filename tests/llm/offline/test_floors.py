"""Floors read by the offline translator: on floor k, upstairs, the floor above, stay on this floor, floor
moves, the same floor, up there.

Each sentence of ``corpus/floors.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_floors_read_or_refused = corpus_test("floors")
