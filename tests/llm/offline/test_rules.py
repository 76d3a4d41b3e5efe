"""The grammar's rules are small, named and each exercised: every registered syntax rule reads at least one
sentence of the corpus, and every kind of phrase, qualifier, body item and sentence has a grounder or a
reader that some sentence uses (a construct added without a corpus entry fails here)."""

from __future__ import annotations

import contextlib
import inspect
from collections import Counter
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.grounding.described import APPLIERS
from sgplan.llm.offline.grounding.phrases import GROUNDERS
from sgplan.llm.offline.meaning.body import READERS
from sgplan.llm.offline.meaning.sentences import SENTENCES
from sgplan.llm.offline.registry import Registry
from sgplan.llm.offline.syntax.body import ITEMS
from sgplan.llm.offline.syntax.noun_slot import NOUN_PHRASES
from sgplan.llm.offline.syntax.qualifiers import QUALIFIERS
from sgplan.llm.offline.syntax.rules import RuleSet
from sgplan.llm.offline.syntax.sentences import OPENINGS
from tests.llm.offline.corpus import constructs, corpus
from tests.shared_data import scene_building

RULE_SETS: list[RuleSet[Any]] = [NOUN_PHRASES, QUALIFIERS, ITEMS, OPENINGS]
REGISTRIES: list[Registry[Any]] = [GROUNDERS, APPLIERS, READERS, SENTENCES]
MAX_RULE_LINES = 40
"""A rule is a small function: its pattern and its production (docstring included)."""


@contextmanager
def counting(hits: Counter[str]) -> Iterator[None]:
    """Count, while open, each rule that matched and each registered function that was called."""
    saved = [list(rules.rules) for rules in RULE_SETS]
    saved_maps = [dict(registry.functions) for registry in REGISTRIES]

    def counted(key: str, fn: Callable[..., Any], matched_only: bool) -> Callable[..., Any]:
        def wrapper(*args: Any) -> Any:
            result = fn(*args)
            if result is not None or not matched_only:
                hits[key] += 1
            return result
        return wrapper

    for rules in RULE_SETS:
        rules.rules = [(n, counted(f"{rules.slot}: {n}", fn, True)) for n, fn in rules.rules]
    for registry in REGISTRIES:
        for kind, fn in list(registry.functions.items()):
            registry.functions[kind] = counted(f"{registry.job}: {kind.__name__}", fn, False)
    try:
        yield
    finally:
        for rules, kept in zip(RULE_SETS, saved):
            rules.rules = kept
        for registry, kept_map in zip(REGISTRIES, saved_maps):
            registry.functions = kept_map


@pytest.mark.gibson
def test_every_rule_reads_some_sentence_of_the_corpus(gibson_root: object) -> None:
    hits: Counter[str] = Counter()
    with counting(hits):
        for construct in constructs():
            for mission in corpus(construct):
                translator = PatternTranslator(mission.start_floor)
                with contextlib.suppress(MissionError):
                    translator.translate(mission.text, scene_building(mission.scene))
    names = [f"{rules.slot}: {n}" for rules in RULE_SETS for n in rules.names()]
    names += [f"{registry.job}: {kind.__name__}" for registry in REGISTRIES for kind in registry]
    assert [n for n in names if not hits[n]] == []


def test_rules_are_small_and_named() -> None:
    for rules in RULE_SETS:
        assert len(set(rules.names())) == len(rules.names())
        for name, fn in rules.rules:
            lines = len(inspect.getsource(fn).splitlines())
            assert lines <= MAX_RULE_LINES, f"{rules.slot} rule {name!r} has {lines} lines"
            assert fn.__doc__, f"{rules.slot} rule {name!r} says nothing of what it reads"
