"""Noun phrases and their grounding read by the offline translator: heads, synonyms, everyday names,
qualifiers, relative clauses, asides, room context, ambiguity.

Each sentence of ``corpus/noun_phrases.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import dataclasses

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.grounding import Discourse
from sgplan.llm.offline.meaning.mission import mission_formula
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.llm.offline.syntax import split_mission
from sgplan.logic import to_infix
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_noun_phrases_read_or_refused = corpus_test("noun_phrases")


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
def test_a_kids_room_the_scene_does_not_single_out_is_refused(demo: Building, rooms: list[str],
                                                               fragment: str) -> None:
    vocabulary = _with_teddy_bears_in(SceneVocabulary(demo), rooms)
    text = "Go to the kids' room."
    with pytest.raises(MissionError) as info:
        mission_formula(split_mission(text, vocabulary.nouns), Discourse(vocabulary, text, None))
    assert "'kids room' is not a room category of this scene" in str(info.value)
    assert fragment in str(info.value)


def test_a_persons_possessive_is_said_back_as_set_aside(demo: Building) -> None:
    """*the baby's teddy bear* is the teddy bear: whose it is, the scene does not say, so the owner is said
    back as set aside (never dropped silently)."""
    translation = PatternTranslator().translate("Check the baby's teddy bear, then Grandma's laptop.", demo)
    assert to_infix(translation.formula) == 'F("reach(object_32)" & F "reach(object_35)")'
    assert translation.set_aside == ("the baby's", "Grandma's")
