"""No clause of a mission is ever dropped silently: several condition rules in one sentence are each
kept, and a sentence the grammar did not read to its end, or a named place that did not make it into the
formula, is refused with the words named (set 4's f063 / f123 lost a second *whenever* rule)."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.grounding import Discourse, Grounded
from sgplan.llm.offline.meaning.mission import check_all_used, mission_formula
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.llm.offline.syntax import split_mission
from sgplan.logic.formula import Atom, Eventually
from sgplan.scene.demo import demo_building
from sgplan.scene.model import Building
from tests.llm.offline_reading import means

# demo building: room_4 kitchen (object_15 refrigerator), room_6 living room (object_22 couch), room_7
# dining room (object_27 dining table), room_12 home office, room_13 bedroom with the book.


@pytest.fixture(scope="module")
def demo() -> Building:
    return demo_building()


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Open the fridge. Whenever you visit the kitchen, head to the living room afterwards, and whenever "
         "you're in the living room, go to the dining room afterwards.",
         "F o15 & G(r4 -> F r6) & G(r6 -> F r7)"),
        ("Whenever you enter the kitchen, open the fridge, whenever you enter the office, visit the dining "
         "room, and every time you are in the dining room, go to the couch.",
         "G(r4 -> F o15) & G(r12 -> F r7) & G(r7 -> F o22)"),
        ("Whenever you enter the kitchen, open the fridge, but whenever you enter the office, go to the "
         "couch afterwards.", "G(r4 -> F o15) & G(r12 -> F o22)"),
        ("Go to the office, and whenever you enter the kitchen, open the fridge, and whenever you reach the "
         "couch, go to the dining room.", "F r12 & G(r4 -> F o15) & G(o22 -> F r7)"),
        ("Go to the couch whenever you enter the living room, and whenever you are in the kitchen, go to "
         "the dining room.", "G(r6 -> F o22) & G(r4 -> F r7)"),
        ("If you go to the kitchen, open the fridge, and if you go to the office, visit the dining room.",
         "(F r4 -> F o15) & (F r12 -> F r7)"),
        ("Open the fridge if you enter the kitchen, and whenever you go to the office, visit the couch.",
         "(F r4 -> F o15) & G(r12 -> F o22)"),
        ("Whenever you are in the office, go to the couch. And whenever you are at the couch, visit the "
         "kitchen, and whenever you are in the kitchen, open the fridge.",
         "G(r12 -> F o22) & G(o22 -> F r4) & G(r4 -> F o15)"),
        ("Every time you enter the kitchen, open the fridge; any time you enter the office, visit the "
         "dining room.", "G(r4 -> F o15) & G(r12 -> F r7)"),
        # the second rule used to be dropped
        ("Whenever you are in the dining room, look at the table, and if you ever go to the kitchen, open "
         "the fridge afterwards.", "G(r7 -> F o27) & G(r4 -> F o15)"),
        ("Only after visiting the kitchen, go to the office, and whenever you are in the office, open the "
         "laptop.", "F r12 & (!r12 U r4) & G(r12 -> F o35)"),
    ],
)
def test_every_condition_rule_is_kept(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "left_over"),
    [
        # used to be read as the first condition only
        ("If you go to the kitchen, open the fridge if you enter the office.", "'if you enter the office'"),
        ("Until you reach the kitchen, avoid the office, and whenever you are in the kitchen, open the "
         "fridge.", "'whenever you are in the kitchen, open the fridge' was not understood"),
        ("Whenever you enter the kitchen, open the fridge, and whenever you enter the office.",
         "nothing to do"),
    ],
)
def test_words_left_over_are_refused(demo, text, left_over):
    with pytest.raises(MissionError) as info:
        PatternTranslator().translate(text, demo)
    assert left_over in str(info.value)


def test_a_named_place_missing_from_the_formula_is_refused(demo):
    """The second safeguard, on its own: a goal phrase whose entities are absent from the formula."""
    vocabulary = SceneVocabulary(demo)
    text = "Go to the kitchen and the office."
    disc = Discourse(vocabulary, text, None)
    formula = mission_formula(split_mission(text, vocabulary.nouns), disc)
    check_all_used(formula, disc.references)  # the whole reading: accepted
    office = next(g for g in disc.references if "office" in g.phrase)
    kitchen_only = Eventually(Atom("enter(room_4)"))
    with pytest.raises(MissionError, match="'the office' was read but is not part of the mission"):
        check_all_used(kitchen_only, disc.references)
    qualifier = Grounded(office.phrase, office.start, office.end, office.entities, "the", False, "qualifier")
    check_all_used(kitchen_only, [qualifier])  # a qualifier only narrows another phrase
