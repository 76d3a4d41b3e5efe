"""Refusal classes seen on blind set 5, generalised (own phrasings, not the set's sentences): leading
chit-chat, a stated start floor, *in whatever order is quickest*, *X in the house*, *after all three / after
all of them / once you've done those*, *The whole time, keep out of X*."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.scene.demo import demo_building
from sgplan.scene.model import Building
from tests.llm.offline_reading import means
from tests.shared_data import scene_building

# demo: room_4 kitchen (object_15 refrigerator), room_5 bathroom floor 0, room_6 living room (object_23
# tv), room_7 dining room, room_11 / room_13 bedrooms floor 1, room_12 home office floor 1, room_14
# bathroom floor 1.


@pytest.fixture(scope="module")
def demo() -> Building:
    return demo_building()


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        # chit-chat sentences and a leading chit-chat clause carry nothing: skipped
        ("Hello! Please visit the office.", "F r12"),
        ("Hey there! Head to the kitchen, then the dining room.", "F(r4 & F r7)"),
        ("Okay, quick request. Go to the living room.", "F r6"),
        ("I need a favour. Look at the TV and never enter the kitchen.", "F o23 & G !r4"),
        ("I'm thirsty, grab something from the fridge.", "F o15"),
        ("Good morning, visit the dining room.", "F r7"),
        # 'in whatever order is quickest': the default (the planner picks the best order)
        ("Go to the kitchen and the dining room in whatever order is fastest.", "F r4 & F r7"),
        ("Visit the office, the kitchen, in whichever order is best, then the living room.",
         "F(r12 & F r6) & F(r4 & F r6)"),
        # the whole building restricts nothing
        ("Look at any TV in the house.", "F o23"),
        ("Go to a bathroom anywhere in the building, then the kitchen.", "F((r5 | r14) & F r4)"),
        ("Visit the home office in this house.", "F r12"),
        # after every goal of the sentence
        ("Visit the kitchen, the office and the dining room, and after all three go to the living room.",
         "F(r4 & F r6) & F(r12 & F r6) & F(r7 & F r6)"),
        ("Check the kitchen and the dining room, and once you've done those, the office.",
         "F(r4 & F r12) & F(r7 & F r12)"),
        ("See the kitchen and the office in any order, after both of them go to the dining room.",
         "F(r4 & F r7) & F(r12 & F r7)"),
        # a whole-mission opener before what to avoid
        ("Visit the office. The entire time, stay out of the kitchen.", "F r12 & G !r4"),
        ("Go to the dining room. At all times, avoid the office and the living room.",
         "F r7 & G !r12 & G !r6"),
        # not a waypoint opener
        ("Go to the kitchen. On the way, look at the TV.", "F(o23 & F r4)"),
    ],
)
def test_set5_classes_read(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "start", "gold"),
    [
        # a stated start floor is used by upstairs / this floor
        ("I'm downstairs right now. Go to the bathroom upstairs.", None, "F r14"),
        ("We are on the ground floor. Use the bathroom on this floor.", None, "F r5"),
        ("You're upstairs at the moment. Go to the bathroom downstairs.", None, "F r5"),
        ("I am on floor 1. Go to the bathroom on this floor.", 1, "F r14"),
    ],
)
def test_stated_start_floor(demo, text, start, gold):
    means(text, gold, demo, start)


@pytest.mark.parametrize(
    ("text", "start", "fragment"),
    [
        # a stated start floor contradicting the known one
        ("I'm upstairs. Go to the bathroom downstairs.", 0, "but it starts on floor 0"),
        ("We're on floor 0 now. Go to the kitchen.", 1, "but it starts on floor 1"),
        # chit-chat that names a place, a verb or a grammar word is not skipped
        ("Hi! The kitchen is a mess. Go to the office.", None, "kitchen"),
        ("If you're hungry, go to the fridge.", None, "hungry"),
        ("Let's get going, go to the kitchen.", None, ""),
        # an order about something the scene lacks is never taken for chit-chat
        ("Feed the cat. Then go to the kitchen.", None, "'cat'"),
        ("I want you to feed the dog, then go to the kitchen.", None, "'dog'"),
        ("Feed pets, then go to the kitchen.", None, "feed pets"),
        # chit-chat after the mission is not skipped (only leading words are)
        ("Go to the kitchen. Thanks a lot!", None, "lot"),
        # after all of them: of this sentence, or of the whole mission?
        ("Visit the kitchen. Go to the office and the dining room, and after all of them go to the living "
         "room.", None, "or of the whole mission"),
        ("Visit the kitchen and the office, and after all three go to the dining room.", None,
         "names 2 goals before it, not 3"),
        # a whole-mission opener before goals
        ("At all times, go to the kitchen.", None, "only before what to avoid"),
        ("Go to the office. The whole time, stay off the couch and visit the kitchen.", None,
         "only before what to avoid"),
        # 'in whatever order' with a reason that is not about speed is not skipped
        ("Visit the kitchen and the office in any order that makes sense.", None, "makes"),
    ],
)
def test_set5_classes_refused(demo, text, start, fragment):
    with pytest.raises(MissionError) as info:
        PatternTranslator(start).translate(text, demo)
    assert fragment in str(info.value).lower()


def test_stated_floor_needs_one_floor():
    """*downstairs* names a floor only in a two-floor building (or as the known start floor)."""
    building = scene_building("Benevolence")  # floors 0 to 2
    with pytest.raises(MissionError, match="say which floor the robot is on"):
        PatternTranslator().translate("I'm downstairs. Go to the bathroom upstairs.", building)
    means("I'm downstairs. Go to the kitchen upstairs.", "F r15", building, start_floor=0)
