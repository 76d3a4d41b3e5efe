"""What the offline translator returns: the LLM's prefix token list, the grounded text and the references;
the same output for the same text; a checked formula or a refusal for any words at all."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import MissionError
from sgplan.llm.offline import PATTERN_BACKEND, PatternTranslator
from sgplan.llm.offline.phrases import word_set
from sgplan.logic import parse_tokens, to_tokens
from sgplan.scene.model import Building


def test_output_is_the_llm_token_format_with_grounded_text_and_references(demo: Building) -> None:
    t = PatternTranslator().translate(
        "Take the bowl in the kitchen, then always avoid the bathroom on floor 1.", demo)
    assert t.backend == PATTERN_BACKEND == "offline-pattern"
    assert t.tokens == ("AND", "EVENTUALLY", "AND", "reach(object_19)", "enter(room_4)", "ALWAYS", "NOT",
                        "enter(room_14)")
    keys = {e.key for e in demo.rooms()} | {o.key for o in demo.objects()}
    assert to_tokens(parse_tokens(list(t.tokens), known=keys)) == list(t.tokens)
    assert t.grounded_text == "Take object_19 in room_4, then always avoid room_14."
    refs = {r.phrase: r for r in t.references}
    assert refs["the bowl in the kitchen"].keys == ("object_19",)
    assert refs["the kitchen"].role == "qualifier" and refs["the kitchen"].keys == ("room_4",)
    avoided = refs["the bathroom on floor 1"]
    assert avoided.keys == ("room_14",) and avoided.role == "avoid"
    assert refs["the bathroom on floor 1"].descriptions == ("room_14 (bathroom, floor 1)",)


def test_grounded_text_of_floor_stays(demo: Building) -> None:
    # the grounded text names what the words name: the rooms kept, or the others for 'any other floor'
    kept = "room_9, room_11, room_12, room_13 and room_14"
    t = PatternTranslator(1).translate("Stay on this floor and go to the toilet.", demo)
    assert t.grounded_text == f"Stay on {kept} and go to object_40."
    t = PatternTranslator(1).translate("Don't go to any other floor; check the laptop.", demo)
    others = "room_2, room_4, room_5, room_6, room_7 and room_8"
    assert t.grounded_text == f"Don't go to {others}; check object_35."


def test_deterministic(demo: Building) -> None:
    text = "Visit any bathroom, then sit on a chair. Never touch the tv."
    assert PatternTranslator().translate(text, demo) == PatternTranslator().translate(text, demo)


_WORDS = sorted(word_set(
    "visit the a any all every both either kitchen bathroom bathrooms bedroom chair chairs sink tv it them "
    "then and or , . if when until before after only avoid never don't always without in on with next to "
    "floor 0 1 first second top except one of couch put bring that order after other room rooms 's not "
    "stay away from take water go room_4 object_19 two again twice times upstairs downstairs whenever "
    "there first secondly that whole time my ground middle no doesn't have once done you're way your via "
    "through ( ) whichever fine maybe ever afterwards are is make sure could"))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(_WORDS), min_size=1, max_size=12))
def test_any_text_gives_a_checked_formula_or_a_mission_error(demo: Building, words: list[str]) -> None:
    text = " ".join(words)
    try:
        t = PatternTranslator().translate(text, demo)
    except MissionError as exc:
        assert str(exc)
        return
    assert to_tokens(parse_tokens(list(t.tokens))) == list(t.tokens) == to_tokens(t.formula)


@pytest.mark.parametrize("start", [None, 0, 1])
def test_the_start_floor_is_a_capability_of_the_translator(demo: Building, start: int | None) -> None:
    """Every translator has ``starting_on`` (:class:`~sgplan.llm.backends.MissionTranslator`); this one reads
    *this floor* from it."""
    translator = PatternTranslator().starting_on(start)
    if start is None:
        with pytest.raises(MissionError, match="depends on where the robot starts"):
            translator.translate("Go to the bathroom on this floor.", demo)
    else:
        assert translator.translate("Go to the bathroom on this floor.", demo).tokens == (
            "EVENTUALLY", "enter(room_5)" if start == 0 else "enter(room_14)")
