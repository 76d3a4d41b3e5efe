"""Sentences read by the offline translator: how sentences join, leading chit-chat, where the robot is said to
start, statements, and no word left over.

Each sentence of ``corpus/sentences.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline.grounding import Discourse, Grounded
from sgplan.llm.offline.meaning.mission import check_all_used, mission_formula
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.llm.offline.syntax import split_mission
from sgplan.logic.formula import Atom, Eventually
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_sentences_read_or_refused = corpus_test("sentences")


def test_a_named_place_missing_from_the_formula_is_refused(demo: Building) -> None:
    """The second safeguard against a dropped clause, on its own: a goal phrase whose entities are absent
    from the formula is refused, named (a qualifier only narrows another phrase)."""
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
    check_all_used(kitchen_only, [qualifier])
