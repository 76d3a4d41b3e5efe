"""The offline pattern translator on the demo building: typical sentences, qualifiers, errors, output."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import MissionError
from sgplan.llm.offline import PATTERN_BACKEND, PatternTranslator
from sgplan.llm.offline.evaluation import expand_shorthand, same_language
from sgplan.llm.offline.lexicon import word_set
from sgplan.logic import parse_infix, parse_tokens, to_tokens
from sgplan.scene.demo import demo_building

# demo building: room_4 kitchen (object_15 refrigerator, object_19 bowl), room_5 bathroom floor 0
# (object_20 toilet, object_21 sink), room_6 living room (object_22 couch, object_23 tv),
# room_7 dining room (object_28, object_29 chairs), room_8 staircase, room_11 bedroom (teddy bear),
# room_12 home office, room_13 bedroom (book), room_14 bathroom floor 1 (object_41 sink).


@pytest.fixture(scope="module")
def demo():
    return demo_building()


@pytest.fixture(scope="module")
def translate(demo):
    translator = PatternTranslator()
    return lambda text: translator.translate(text, demo)


def assert_means(translation, gold: str) -> None:
    same, why = same_language(translation.formula, parse_infix(expand_shorthand(gold)))
    assert same, f"{translation.formula} vs {gold}: {why}"


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Visit the kitchen.", "F r4"),
        ("Go to the kitchen, then walk to the living room.", "F(r4 & F r6)"),
        ("Visit the kitchen and the living room.", "F r4 & F r6"),
        ("Visit the kitchen or the living room.", "F(r4 | r6)"),
        ("Visit either the kitchen or the dining room.", "F(r4 | r7)"),
        ("Visit the living room after the kitchen.", "F(r4 & F r6)"),
        ("After visiting the kitchen, go to the living room.", "F(r4 & F r6)"),
        ("Before going to the living room, visit the kitchen.", "F(r4 & F r6)"),
        ("Visit the kitchen. Then visit the living room. Finally open the fridge.", "F(r4 & F(r6 & F o15))"),
        ("Always avoid the kitchen.", "G !r4"),
        ("Never enter the kitchen and visit the living room.", "G !r4 & F r6"),
        ("Visit the living room and don't enter the kitchen.", "F r6 & G !r4"),
        ("Visit the bathroom on floor 0 and avoid the sink.", "F(r5 & !o21)"),
        ("Stay away from the kitchen until you have visited the living room.", "!r4 U r6"),
        ("If you visit the kitchen, then take the bowl.", "F r4 -> F o19"),
        ("Take the bowl only if you visit the kitchen.", "F o19 -> F r4"),
        ("Sit on the sofa, then watch the television.", "F(o22 & F o23)"),
        ("Visit the kitchen, the living room and the dining room in that order.", "F(r4 & F(r6 & F r7))"),
        ("Sit on a chair in the dining room.", "F((o28 | o29) & r7)"),
        ("Visit room_11, then reach object_41.", "F(r11 & F o41)"),
    ],
)
def test_typical_sentences(translate, text, gold):
    assert_means(translate(text), gold)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Visit the bathroom on floor 1.", "F r14"),
        ("Visit the bathroom in floor 0.", "F r5"),
        ("Visit the bathroom on the ground floor.", "F r5"),
        ("Visit the bathroom on the first floor.", "F r5"),
        ("Visit the bathroom on the second floor.", "F r14"),
        ("Visit the bathroom on the top floor.", "F r14"),
        ("Touch the sink in the kitchen.", "F(o17 & r4)"),
        ("Touch the kitchen's sink.", "F(o17 & r4)"),
        ("Touch the sink on floor 1.", "F o41"),
        ("Visit the bedroom with the teddy bear.", "F r11"),
        ("Visit the bedroom that has a book.", "F r13"),
        ("Visit the room with two chairs.", "F r7"),
        ("Visit the kitchen next to the bathroom.", "F r4"),
        ("Visit every room on floor 1 except the bedrooms.", "F r9 & F r12 & F r14"),
        ("Go to the kitchen and take the sink.", "F r4 & F(o17 & r4)"),
    ],
)
def test_grounding_qualifiers(translate, text, gold):
    assert_means(translate(text), gold)


def test_output_is_the_llm_token_format_with_grounded_text_and_references(translate, demo):
    t = translate("Take the bowl in the kitchen, then always avoid the bathroom on floor 1.")
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


def test_deterministic(translate):
    text = "Visit any bathroom, then sit on a chair. Never touch the tv."
    assert translate(text) == translate(text)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("Go to the bathroom.",
         "'the bathroom' matches 2 rooms: room_5 (floor 0), room_14 (floor 1); say which floor (e.g. 'the "
         "bathroom on floor 0')"),
        ("Visit the bedroom.",
         "'the bedroom' matches 2 rooms: room_11 (floor 1), room_13 (floor 1); say what it contains"),
        ("Sit on the chair in the dining room.",
         "'the chair in the dining room' matches 2 objects: object_28 (in room_7, floor 0), object_29 (in "
         "room_7, floor 0)"),
        ("Touch the sink.", "'the sink' matches 3 objects"),
        ("Visit the garage.", "no room or object of this scene is called 'garage'"),
        ("Visit the bathroom on floor 4.", "has floors 0 to 1"),
        ("Visit the kitchen with the bed.", "'the kitchen with the bed' matches no room"),
        ("Take both clocks in the living room.",
         "'both clocks in the living room' should be 2 objects but matches 1"),
        ("Leave the kitchen.", "cannot understand 'leave'"),
        ("Visit the kitchen and put it in the fridge.", "'it' does not refer to any room or object"),
        ("Visit the kitchen and the bathroom on floor 0 or the living room.", "mixes 'and' and 'or'"),
        ("Visit two bedrooms.", "choosing a number of them is not understood"),
        ("Whenever you visit the kitchen, never open the fridge.",
         "'whenever X, ...' is understood with goals only"),
        ("Go to the first bathroom.", "ordinals like 'first' are only understood for floors"),
        ("Please.", "names no room or object"),
        ("Visit the kitchen, then the.", "expected a room or object"),
    ],
)
def test_unresolved_ambiguous_and_unknown_are_errors(translate, text, message):
    with pytest.raises(MissionError) as info:
        translate(text)
    assert message in str(info.value)


def test_room_context_resolves_objects_of_the_step(translate):
    # "the sink" alone is ambiguous; after "go to the bathroom on floor 1" it is that bathroom's sink.
    assert_means(translate("Go to the bathroom on floor 1 and wash the sink."), "F r14 & F(o41 & r14)")
    # ... but only within the step: after "then" the context is gone.
    with pytest.raises(MissionError, match="'the sink' matches 3 objects"):
        translate("Go to the bathroom on floor 1, then wash the sink.")


def test_pronouns_agree_in_number(translate):
    assert_means(translate("Go to the bedroom with the teddy bear and touch it."), "F r11 & F o32")
    assert_means(translate("Take the bowl in the kitchen and put it on the dining table."),
                 "F(o19 & r4 & F o27)")
    # "them" is both clocks: touch both, then each of them anew (in any order).
    assert_means(translate("Touch the clocks, then touch them again."),
                 "F(o26 & F(!o26 & F o26) & F(!o33 & F o33)) & F(o33 & F(!o26 & F o26) & F(!o33 & F o33))")


_WORDS = sorted(word_set(
    "visit the a any all every both either kitchen bathroom bathrooms bedroom chair chairs sink tv it them "
    "then and or , . if when until before after only avoid never don't always without in on with next to "
    "floor 0 1 first second top except one of couch put bring that order after other room rooms 's not "
    "stay away from take water go room_4 object_19 two again twice times upstairs downstairs whenever "
    "there first secondly that whole time my ground middle no doesn't have once done you're way your via "
    "through ( ) whichever fine maybe ever afterwards are is make sure could"))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(_WORDS), min_size=1, max_size=12))
def test_any_text_gives_a_checked_formula_or_a_mission_error(demo, words):
    text = " ".join(words)
    try:
        t = PatternTranslator().translate(text, demo)
    except MissionError as exc:
        assert str(exc)
        return
    assert to_tokens(parse_tokens(list(t.tokens))) == list(t.tokens) == to_tokens(t.formula)
