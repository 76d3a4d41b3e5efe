"""The refusal of an ambiguous reference suggests a wording that tells its candidates apart, and every
suggestion, followed as printed, is read as one of the candidates (never refused again): over the ambiguous
references of the four scenes (each category said alone, in a room, on a floor)."""

from __future__ import annotations

import re

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.logic import atoms
from sgplan.scene.model import Building
from tests.shared_data import scene_building

SCENES = ["demo", *(pytest.param(s, marks=pytest.mark.gibson) for s in ("Allensville", "Benevolence",
                                                                         "Collierville"))]
SUGGESTION = re.compile(r"\(e\.g\. '([^']+)'\)")


def references(building: Building) -> list[str]:
    """Phrases that may be ambiguous in ``building``: each category alone, each object category in each room
    category holding it, each category on each floor."""
    vocab = SceneVocabulary(building)
    categories = sorted({e.category for e in vocab.entities})
    rooms_of = {(o.category, vocab.by_key[o.room_key].category) for o in vocab.entities if o.kind == "object"}
    floors = sorted({(e.category, e.floor) for e in vocab.entities})
    return ([f"the {c}" for c in categories] + [f"the {o} in the {r}" for o, r in sorted(rooms_of)]
            + [f"the {c} on floor {f}" for c, f in floors])


def refusal(text: str, building: Building) -> str | None:
    """The refusal of ``text``, or ``None`` when it is read."""
    try:
        PatternTranslator().translate(text, building)
    except MissionError as error:
        return str(error)
    return None


@pytest.mark.parametrize("scene", SCENES)
def test_every_suggestion_is_read_as_one_of_the_candidates(scene: str) -> None:
    building = scene_building(scene)
    followed = 0
    for phrase in references(building):
        said = refusal(f"Go to {phrase}.", building)
        if said is None or "matches" not in said:
            continue
        candidates = set(re.findall(r"(?:room|object)_\d+", said.split(";")[0]))
        suggestion = SUGGESTION.search(said)
        if suggestion is None:
            continue  # "say 'any X' or 'every X', or name it by its ID": a choice, not a wording
        formula = PatternTranslator().translate(f"Go to {suggestion.group(1)}.", building).formula
        named = {re.sub(r"^(enter|reach)\((.*)\)$", r"\2", a) for a in atoms(formula)}
        assert named & candidates, f"{phrase!r} -> {suggestion.group(1)!r} names {named}, not {candidates}"
        followed += 1
    assert followed > 0


@pytest.mark.gibson
def test_the_book_in_benevolence_is_told_apart_by_what_its_bedroom_holds(gibson_root: object) -> None:
    building = scene_building("Benevolence")
    for phrase in ("the book", "the book in the bedroom on floor 2"):
        said = refusal(f"Go to {phrase}.", building)
        assert said is not None and "say which room it is in (e.g. 'the book in the bedroom with the" in said
        suggestion = SUGGESTION.search(said)
        assert suggestion is not None and refusal(f"Go to {suggestion.group(1)}.", building) is None
