"""The noun phrase and what it refers to (``corpus/references.jsonl``): objects placed by other objects,
where a carried thing goes, a room's contents in any form of *have*, *the <room> one*, each read or refused
as its case says."""

from __future__ import annotations

from sgplan.explain import explain_mission
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.translation import mission_of
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_references_read_or_refused = corpus_test("references")


def test_a_thing_the_scene_does_not_hold_is_said_back_as_set_aside(demo: Building) -> None:
    translation = PatternTranslator().translate(
        "Water the plant in the office, then rinse the watering can out at the kitchen sink.", demo)
    assert translation.set_aside == ("the watering can",)
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert said[-1] == "Not part of the mission: 'the watering can'"


def test_a_place_the_scene_does_not_hold_is_said_back_as_set_aside(demo: Building) -> None:
    translation = PatternTranslator().translate("Look at the laptop on the desk and then the couch.", demo)
    assert translation.set_aside == ("on the desk",)
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert said[-1] == "Not part of the mission: 'on the desk'"
