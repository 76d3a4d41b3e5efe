"""The grammar of the instruction as people word it (``corpus/grammar.jsonl``): non-native word orders and
slips, quantities over a category, references and clause forms, each read or refused as its case says."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.explain import explain_mission
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.translation import mission_of
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_grammar_read_or_refused = corpus_test("grammar")


def test_a_goal_not_needed_is_said_back_as_set_aside(demo: Building) -> None:
    translation = PatternTranslator().translate(
        "Check the fridge, you don't have to open it, then the couch. No need to rush.", demo)
    assert translation.set_aside == ("you don't have to open it", "No need to rush")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert said[-2:] == ["Not part of the mission: 'you don't have to open it'",
                         "Not part of the mission: 'No need to rush'"]
    # Naming a place, it may mean "keep out of it": refused, saying how to say either
    with pytest.raises(MissionError, match="'No need to go upstairs' says a goal is not needed"):
        PatternTranslator().translate("Check the fridge. No need to go upstairs.", demo)
