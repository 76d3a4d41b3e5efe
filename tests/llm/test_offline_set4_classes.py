"""Refusal classes seen on blind set 4, generalised (own phrasings, not the set's sentences): *in
whichever order you like*, *X again* after an object in X, *keep / stay off X*, *either to A or to B*,
*a X, any X*, *take the stairs down to ...*."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.scene.demo import demo_building
from sgplan.scene.model import Building
from tests.llm.offline_reading import means

# demo: room_4 kitchen (object_15 refrigerator, object_16 oven, object_18 microwave), room_5 bathroom
# floor 0, room_6 living room (object_22 couch, object_23 tv, object_26 clock), room_7 dining room
# (object_27 dining table), room_8 staircase, room_11 bedroom (object_33 clock), room_12 home office,
# room_14 bathroom floor 1.


@pytest.fixture(scope="module")
def demo() -> Building:
    return demo_building()


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        # order left to the robot, with a liking
        ("Check the oven and the couch in whichever order you like, then go to the office.",
         "F(o16 & F r12) & F(o22 & F r12)"),
        ("Visit the office and the dining room in any order you want.", "F r12 & F r7"),
        ("Go to the fridge, the TV, in whatever order you prefer.", "F o15 & F o23"),
        # an object in X was a visit of X
        ("Look at the clock in the living room, then the office, and then the living room again.",
         "F(o26 & F(r12 & F(!r6 & F r6)))"),
        ("Open the fridge, go to the dining room, then to the kitchen again.",
         "F(o15 & F(r7 & F(!r4 & F r4)))"),
        # keep / stay off
        ("Keep off the stairs and go to the office.", "F r12 & G !r8"),
        ("Stay off the couch while you check the TV.", "F o23 & G !o22"),
        # the preposition repeated after 'either' / 'or'
        ("Head either to the office or to the dining room, then the kitchen.", "F((r12 | r7) & F r4)"),
        ("Walk either into the kitchen or into the dining room.", "F(r4 | r7)"),
        # 'any X' restating a choice of the same Xs
        ("Look at a clock, any clock.", "F(o26 | o33)"),
        ("Visit a bathroom, any bathroom, then the kitchen.", "F((r5 | r14) & F r4)"),
        # the stairs as the way, not a goal
        ("Take the stairs up to the top floor and visit the office there.", "F r12"),
        ("Go down the stairs to the kitchen.", "F r4"),
    ],
)
def test_set4_classes_read(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("Look at a clock, then the office, then the living room again.", "was not a goal before"),
        ("Check the clock in the bedroom, any clock.", "named twice"),
        ("Visit the bathroom upstairs, any bathroom.", "named twice"),
    ],
)
def test_set4_classes_still_refused_when_unclear(demo, text, fragment):
    with pytest.raises(MissionError, match=fragment):
        PatternTranslator().translate(text, demo)
