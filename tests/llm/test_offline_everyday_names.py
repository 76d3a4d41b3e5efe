"""Everyday room names the scene decides (``everyday.py``): *loo*, *kids' room*, *nursery* ..."""

from __future__ import annotations

import dataclasses

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.grounding import Discourse
from sgplan.llm.offline.meaning.mission import mission_formula
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.llm.offline.syntax import split_mission
from sgplan.scene.demo import demo_building
from sgplan.scene.model import Building
from tests.llm.offline_reading import means

# demo: room_5 bathroom floor 0, room_14 bathroom floor 1, room_11 bedroom with the teddy bear (object_32),
# room_13 bedroom with the book, room_4 kitchen.


@pytest.fixture(scope="module")
def demo() -> Building:
    return demo_building()


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Head to the loo upstairs.", "F r14"),
        ("I'd like you to visit one of the loos.", "F(r5 | r14)"),
        ("Go to the lavatory on the ground floor, then the kitchen.", "F(r5 & F r4)"),
        ("Pop into the kids' room and then the kitchen.", "F(r11 & F r4)"),
        ("Look at the clock in the kid's room.", "F o33"),
        ("Go to the nursery.", "F r11"),
        ("Never enter the children's room.", "G !r11"),
    ],
)
def test_everyday_names_the_scene_decides(demo, text, gold):
    means(text, gold, demo)


def test_the_loo_is_a_bathroom_so_which_one_is_asked(demo):
    with pytest.raises(MissionError, match="'the loo' matches 2 rooms"):
        PatternTranslator().translate("Go to the loo.", demo)


def _with_teddy_bears_in(vocabulary: SceneVocabulary, rooms: list[str]) -> SceneVocabulary:
    """The demo's vocabulary with its teddy bears moved to ``rooms`` (none when empty)."""
    others = [e for e in vocabulary.entities if e.category != "teddy bear"]
    bear = next(e for e in vocabulary.entities if e.category == "teddy bear")
    bears = [dataclasses.replace(bear, key=f"object_{900 + k}", room_key=r) for k, r in enumerate(rooms)]
    vocabulary.entities = tuple(others + bears)
    return vocabulary


@pytest.mark.parametrize(
    ("rooms", "fragment"),
    [
        (["room_11", "room_13"], "several rooms hold a teddy bear; candidates: room_11 (bedroom, floor 1), "
                                 "room_13 (bedroom, floor 1)"),
        ([], "no room of this scene holds a teddy bear; candidates: room_11"),
    ],
)
def test_a_kids_room_the_scene_does_not_single_out_is_refused(demo, rooms, fragment):
    vocabulary = _with_teddy_bears_in(SceneVocabulary(demo), rooms)
    text = "Go to the kids' room."
    with pytest.raises(MissionError) as info:
        mission_formula(split_mission(text, vocabulary.nouns), Discourse(vocabulary, text, None))
    assert "'kids room' is not a room category of this scene" in str(info.value)
    assert fragment in str(info.value)
