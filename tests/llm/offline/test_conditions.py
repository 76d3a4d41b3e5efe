"""Conditions read by the offline translator: if, whenever, responses (if you ever ... afterwards), only if,
several rules, several actions, bare when.

Each sentence of ``corpus/conditions.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

from tests.llm.offline.corpus import corpus_test

test_conditions_read_or_refused = corpus_test("conditions")
