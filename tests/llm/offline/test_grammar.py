"""The grammar of the instruction as people word it (``corpus/grammar.jsonl``): non-native word orders and
slips, quantities over a category, references and clause forms, each read or refused as its case says."""

from __future__ import annotations

from sgplan.explain import explain_mission
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.translation import mission_of
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_grammar_read_or_refused = corpus_test("grammar")


def test_a_goal_not_needed_is_said_back_as_set_aside(demo: Building) -> None:
    translation = PatternTranslator().translate(
        "Check the fridge, you don't have to open it, then the couch. No need to go upstairs.", demo)
    assert translation.set_aside == ("you don't have to open it", "No need to go upstairs")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert said[-2:] == ["Not part of the mission: 'you don't have to open it'",
                         "Not part of the mission: 'No need to go upstairs'"]
