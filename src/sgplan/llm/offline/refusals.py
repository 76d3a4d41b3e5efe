"""Every refusal of the offline translator, worded in one place.

A refusal names the words it could not read and says what would be read instead; most end with
:data:`REPHRASE`. The syntax returns them as :class:`.syntax.reader.Refusal` values, grounding raises them as
:class:`~sgplan.errors.MissionError` (:func:`refuse`); nothing else in the translator words a refusal.
Sections follow the pipeline: tokens and sentences, noun phrases, actions, order, negation, conditions,
grounding (what a phrase matches), back-references, floors.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NoReturn

from sgplan.errors import MissionError
from sgplan.llm.offline.lexicon import TIME_UNITS, plural
from sgplan.llm.offline.names import Entity, head_word

REPHRASE = "; rephrase the mission (see docs/offline.md for the understood English)"


def rephrase(message: str) -> str:
    """``message`` followed by the pointer to the understood English."""
    return message + REPHRASE


def with_suggestions(message: str, did_you_mean: str) -> str:
    """``message`` with the suggestions for the mission's unknown words (*did you mean ...?*) before its
    pointer to the understood English."""
    if not did_you_mean:
        return message
    if message.endswith(REPHRASE):
        return f"{message[: -len(REPHRASE)]}; {did_you_mean}{REPHRASE}"
    return f"{message}; {did_you_mean}"


def refuse(message: str) -> NoReturn:
    """Raise the refusal ``message`` (one of this module's) as a :class:`~sgplan.errors.MissionError`."""
    raise MissionError(message)


# ------------------------------------------------------------------------------ sentences and leftovers
def left_over(words: str) -> str:
    if set(words.lower().split()) & TIME_UNITS:
        return rephrase(f"'{words}': a delay or a duration cannot be required (a plan has no clock); "
                        "leave it out")
    return rephrase(f"'{words}' was not understood (the sentence was read only up to there), and no part of "
                    "a mission is ever dropped")


def cannot_understand(what: str) -> str:
    return rephrase(f"cannot understand {what}")


def not_a_verb(words: str) -> str:
    return rephrase(f"cannot understand '{words}': it is no verb or room or object the translator knows")


def cannot_understand_word(word: str, rest: str) -> str:
    return rephrase(f"cannot understand '{word}' in {rest}")


def no_goal_at_all(set_aside: list[str]) -> str:
    aside = "; ".join(f"'{s}'" for s in set_aside)
    return rephrase("the mission names no room or object to visit or avoid" + (
        f" (set aside as asking nothing: {aside})" if set_aside else ""))


def dropped(phrase: str) -> str:
    return rephrase(f"'{phrase}' was read but is not part of the mission that would be planned, and no part "
                    "of a mission is ever dropped")


def whole_mission_opener(opener: str) -> str:
    return rephrase(f"'{opener}, ...' is understood only before what to avoid for the whole mission ('"
                    f"{opener}, keep out of the kitchen')")


def scope_unused(room: str) -> str:
    return rephrase(f"'in {room}, ...': nothing said after it is in {room}; say 'go to {room}, then ...' if "
                    "it is a place to go")


def order_after_ordered_goals() -> str:
    return rephrase("'the order does not matter' after goals given in order; say which it is")


def apology_about_place(words: str) -> str:
    return rephrase(f"'{words}': an apology about a room or object says nothing of what to do there (it is "
                    "no goal); say what to do ('go to X'), or 'avoid X' to keep away")


def reason_before_pronoun(reason: str, pronoun: str) -> str:
    return rephrase(f"'{reason}' names a place before '{pronoun}': is '{pronoun}' that place, or what the "
                    "order before it named? Name the place again")


def event_of_people_at_place(said: str) -> str:
    return rephrase(f"'{said}' says when by what people do at a place of the scene, which the robot can "
                    "neither sense nor wait for (the place is not a goal of the robot's); leave the event "
                    "out, or say the goals in order with 'then'")


# ------------------------------------------------------------------------------------------ noun phrases
def expected_phrase_at_end() -> str:
    return rephrase("expected a room or object at the end of the sentence")


def expected_phrase_after(word: str) -> str:
    return rephrase(f"expected a room or object after '{word}' at the end of the sentence")


def state_condition(said: str) -> str:
    return rephrase(f"'{said}' is a condition on the state of something, which the robot cannot check; only "
                    "where the robot goes can be a condition ('if you go into X, ...')")


def optional_condition(said: str) -> str:
    return rephrase(f"'{said}' makes a goal optional, which cannot be expressed; leave the goal out or make "
                    "it a goal")


def self_correction(said: str) -> str:
    return rephrase(f"'{said}' takes back something said before it, and the translator does not read which "
                    "part stands; say the mission again as it should be done")


def where_you_find(said: str) -> str:
    return rephrase(f"'{said}' may only say what is there, or ask for it; say 'and check the ...' if it is a "
                    "goal, or leave it out")


def where_after_no_room(said: str) -> str:
    return rephrase(f"'{said}' follows no single room, so it is not clear where it is done; say 'in the "
                    "<room>, ...' or name the room of the object")


def caution_not_goal(said: str) -> str:
    return rephrase(f"'{said}' says how to behave near a place (or to disregard it), which neither asks to "
                    "go there nor forbids it; say 'go to X' for a goal, or 'avoid X' / 'never enter X' to "
                    "keep away")


def not_needed(said: str) -> str:
    return rephrase(f"'{said}' says a goal is not needed, which neither asks for it nor forbids it; leave "
                    "it out, or say 'never enter X' to forbid it")


def before_bare_verb(said: str) -> str:
    return rephrase(f"'{said}' can mean 'before you go there' or 'before that, go there'; say 'then' or "
                    "'before that'")


def before_pronoun(said: str) -> str:
    return rephrase(f"'{said}': before which goal, or before all of them? Say 'before that' (before "
                    "everything said so far) or name the goal")


def times_in_order(times: list[str]) -> str:
    said = " and ".join(f"'{t}'" for t in times)
    return rephrase(f"{said} may put the goals in an order of times, and a plan has no clock; leave the "
                    "times out and say the order in words ('A, then B')")


def restated_first(said: str) -> str:
    return rephrase(f"'{said}' names again a goal said before: is it to be done first only, or twice? Say "
                    "the goals once, in the order they must be done")


def trailing_after(said: str) -> str:
    return rephrase(f"in '{said}' it is not clear which goals come after which; say 'then' before the goal "
                    "that comes after ('A, then B')")


def strict_closing(said: str, words: str) -> str:
    return rephrase(f"'{said}': '{words}' closing the clause is not understood (which goal must wait, "
                    f"and for which?); put it before the goal that waits ('A, and {words} B')")


def first_mid_sentence(said: str) -> str:
    return rephrase(f"'{said}': 'first' after a comma could put what follows before everything said so far, "
                    "or only before what comes next; say 'but first, X' or 'X, then ...'")


def before_floor_move(said: str) -> str:
    return rephrase(f"'{said}' orders the goals by a move between floors, not by a goal (on which floor is "
                    "what follows?); say the goals in order with their floors ('check the oven, then go "
                    "upstairs to the office')")


def order_without_goal(said: str) -> str:
    return rephrase(f"'{said}' says where in the order but names no goal; say the goal in the same sentence "
                    "('Last, the office.', 'Then the kitchen.')")


def carried_nothing(said: str) -> str:
    return rephrase(f"'{said}' carries something, but no object is named before it; say what to carry "
                    "('bring the <object> to ...')")


def give_without_look(said: str) -> str:
    return rephrase(f"'{said}' is read only as 'give X a look' (or a check, a clean); say what to do with X")


def expected_phrase(verbs: str, rest: str) -> str:
    what = f"after '{verbs}'" if verbs else "here"
    return rephrase(f"expected a room or object {what}, found {rest}")


def symbol(sym: str, rest: str) -> str:
    return rephrase(f"cannot read '{sym}' in {rest}; say what it means in words ('and', 'or', 'then')")


def clock_time(said: str) -> str:
    return rephrase(f"'{said}': the time of day something is done cannot be required (a plan has no clock); "
                    "leave the time out, or plan it when it is time")


def unknown_noun(word: str, rooms: Sequence[str], objects: Sequence[str]) -> str:
    return rephrase(f"no room or object of this scene is called '{word}' (rooms: {', '.join(rooms)}; "
                    f"objects: {', '.join(objects)})")


def unknown_key(key: str) -> str:
    return rephrase(f"'{key}' is not a room or object of this scene")


def one_without_kind(word: str) -> str:
    return rephrase(f"'{word}' does not refer to a kind of room or object named just before")


def ordinal_not_of_a_floor(word: str) -> str:
    return rephrase(f"ordinals like '{word}' are only understood for floors ('the bathroom on the {word} "
                    f"floor') and for what was named before ('back to the {word} one')")


def demonstrative_not_before_noun(word: str, after: str) -> str:
    return rephrase(f"'{word} {after}' refers back to something named before, and is understood only "
                    f"directly before a room or object ('{word} bathroom'); name it instead")


def choosing_a_number(number: str) -> str:
    return rephrase(f"'{number} ...': choosing a number of them is not understood; say 'any of the ...' or "
                    "'all the ...'")


def nor_outside_negation(said: str) -> str:
    return rephrase(f"'nor' in '{said}' is understood only in 'never enter / neither A nor B' (each of them "
                    "forbidden)")


def dash_between_goals(said: str) -> str:
    return rephrase(f"'{said}': a dash between goals could mean 'then' or 'and'; write '->' or 'then' for an "
                    "order, 'and' for a set")


def mixes_and_or(said: str) -> str:
    return rephrase(f"'{said}' mixes 'and' and 'or'; split it into two sentences")


def group_in_a_choice(said: str) -> str:
    return rephrase(f"'{said}' joins a group with 'or'; say 'any of ...'")


def announced_count(said: str, count: int, items: int) -> str:
    follow = "follows" if items == 1 else "follow"
    return rephrase(f"'{said}' announces {count}, but {items} {follow} after the colon; name them all, or "
                    f"leave the number out")


def not_announced(phrase: str, said: str) -> str:
    return rephrase(f"'{phrase}' is not one of '{said}' announced before the colon; name the list again")


def named_twice(phrase: str) -> str:
    return rephrase(f"'{phrase}' is named twice in one list")


def contact_clause(said: str) -> str:
    return rephrase(f"'{said} ...': a clause about the thing inside the phrase is not understood (what "
                    "follows could say where it is, or be another goal); say which one by its room or "
                    "contents")


def remark_after_each(remark: str, said: str) -> str:
    return rephrase(f"'{remark}' after '{said}', which means each of them: say 'any of ...' or 'A or B' for "
                    "a choice")


def only_a_room_holds(said: str) -> str:
    return rephrase(f"'{said}': only a room can hold an object ('the teddy bear's room')")


def only_objects_belong(said: str) -> str:
    return rephrase(f"'{said}': only objects belong to a room")


def object_in_room(said: str) -> str:
    return rephrase(f"'{said}': say 'the <object> in the <room>' (rooms are not inside rooms, objects not "
                    "inside objects)")


def room_holds_none(said: str, room: str, thing: str) -> str:
    return rephrase(f"'{said}': '{room}' has no {thing}; to go there as well, name it apart (e.g. '..., then "
                    f"{room}')")


def room_without(said: str) -> str:
    return rephrase(f"'{said}': say 'the <room> without any <object>'")


def room_with(said: str) -> str:
    return rephrase(f"'{said}': say 'the <room> with the <object>'")


def room_by_contents(phrase: str) -> str:
    return rephrase(f"'{phrase}': a room is described by an object it holds ('the room where the book is')")


def where_after_a_room(rest: str) -> str:
    return rephrase("'where ...' after a room is understood as 'the room where the <object> is'; found "
                    f"{rest}")


def next_to_rooms_only(said: str) -> str:
    return rephrase(f"'{said}': 'next to' is understood for rooms only (distances between objects are not "
                    "known); name the room the object is in")


def placed_or_where_it_is(said: str, anchor: str) -> str:
    return rephrase(f"'{said}': is '{anchor}' where it is, or where it goes? Say 'put ... {anchor}' for "
                    "where it goes, or name the room it is in")


def carried_in_purpose(said: str) -> str:
    return rephrase(f"{said}: what is carried after 'to' is not read in its order (the thing, then where it "
                    "goes); say it as a step of its own ('go to X, then put ...')")


def thing_to_find(thing: str, said: str) -> str:
    return rephrase(f"'{said}': the scene has no '{thing}', and the robot would have to find it itself; "
                    "name a room or object of the scene")


def negated_count(said: str) -> str:
    return rephrase(f"'{said}': a room that does not have a number of things (none, or another number?) is "
                    "not understood; say 'the ... with no X' or 'the ... with two X'")


def anchor_in_several_rooms(said: str, anchor: str, rooms: Sequence[Entity]) -> str:
    listing = ", ".join(r.describe() for r in rooms)
    return rephrase(f"'{said}': an object by another is read as one in that object's room, and '{anchor}' "
                    f"is in {len(rooms)} rooms ({listing}); name the room the object is in")


def not_an_exception(said: str, stray: str, restricted: str) -> str:
    return rephrase(f"'{said} {stray}': {stray!r} is not one of {restricted!r}; to forbid it, say 'never "
                    f"enter {stray}'")


def both_contents_or_goal(said: str, thing: str) -> str:
    return rephrase(f"'{said}': a room with both, or '{thing}' as another goal? Say 'the ... that has both "
                    f"...', or 'then' before '{thing}'")


def same_room_unclear(word: str, keys: Sequence[str]) -> str:
    return rephrase(f"'the same {word}': the place named before it is {' or '.join(keys)}; name the room")


def undecided_description(words: Sequence[str], said: str, entities: Sequence[Entity],
                          singular: bool) -> str:
    listing = ", ".join(e.describe() for e in entities[:8]) + (", ..." if len(entities) > 8 else "")
    things, word = plural(head_word(list(entities))), " ".join(words)
    return rephrase(f"'{word}' in '{said}': the scene does not say which of its {len(entities)} {things} "
                    f"{'is' if singular else 'are'} {' and '.join(words)} ({listing}); name the one meant "
                    f"another way (its room or floor), or leave '{word}' out")


def kids_room(said: str, why: str, named: str) -> str:
    return (f"'{said}' is not a room category of this scene and {why}; candidates: {named}; name the room "
            "(e.g. by its ID or its contents: 'the bedroom with the ...')")


# -------------------------------------------------------------------------------------- what a phrase is
def matches_nothing(phrase: str, kind: str, kept: str, existing: str) -> str:
    return rephrase(f"'{phrase}' matches no {kind}{kept}{existing}")


def qualifier_matches_nothing(phrase: str, kind: str, existing: str) -> str:
    return rephrase(f"'{phrase}' matches no {kind} of this scene{existing}")


def wrong_count(phrase: str, count: int, kind: str, n: int, listing: str) -> str:
    return rephrase(f"'{phrase}' should be {count} {kind}s but matches {n}: {listing}")


def ambiguous(phrase: str, n: int, kind: str, listing: str, hint: str) -> str:
    return f"'{phrase}' matches {n} {kind}s: {listing}; {hint}"


def not_in_this_step(said: str, where: str, listing: str, noun: str) -> str:
    return rephrase(f"'{said}' is not in {where} named in the same step; it is at {listing}; say 'then' "
                    f"between the two, or name its room ('the {noun} in the ...')")


def step_room_or_anywhere(said: str, where: str, noun: str, room: str, single: str) -> str:
    return rephrase(f"'{said}' right after a step in {where}: one of the ones there, or any in the building? "
                    f"Say 'one of the {noun} in the {room}', or name the room of the {single} meant")


def listed_room_or_anywhere(said: str, where: str, room: str) -> str:
    return rephrase(f"'{said}' after {where} among tasks in any order: the ones there, or any in the "
                    f"building? Name the room ('{said} in the {room}', or another)")


def there_or_anywhere(said: str, where: str, noun: str, room: str, single: str) -> str:
    return rephrase(f"'{said}' after a condition on {where}: the ones there, or any in the building? Say "
                    f"'the {noun} in the {room}' or 'any {single}'")


# --------------------------------------------------------------------------------------------- actions
def expected_action_after_floor() -> str:
    return rephrase("expected an action after the floor to go to")


def path_start_or_end(verb: str, particle: str) -> str:
    return rephrase(f"'{verb} {particle} ...': where the path starts or ends cannot be required; put the "
                    "goals in order with 'then'")


def did_is_not_a_place(verb: str, what: str) -> str:
    return rephrase(f"'{verb} {what}' refers to what was done, not to a place; name the rooms or objects "
                    "again")


def too_many_repeats(number: str) -> str:
    return rephrase(f"'{number} times': at most 5 repeated visits are understood")


def again_not_a_goal(said: str) -> str:
    return rephrase(f"'{said} again': it was not a goal before")


def again_after_choice(said: str) -> str:
    return rephrase(f"'{said} again' after a choice among them: each of them, or the one chosen before? Say "
                    "'each of the ... again' to visit every one, or name the one to visit again")


def revisit_without_first_visit() -> str:
    return rephrase("'again' / 'back to' needs the first visit earlier in the same sequence (e.g. 'go to "
                    "the kitchen, then the bedroom, then back to the kitchen')")


def or_between_actions(rest: str) -> str:
    return rephrase(f"'or' between actions is not understood at {rest} (say 'visit A or B' with one verb)")


# ----------------------------------------------------------------------------------------------- order
def order_word_in_list(item: str, word: str, place: str) -> str:
    return rephrase(f"'{item}': '{word}' opens an item that is not the {place} of its list, or a list in no "
                    "order: which items it comes before or after is not clear; number the items in the order "
                    "meant ('1. ..., 2. ...')")


def choice_narrowed_aside(remark: str) -> str:
    return rephrase(f"'{remark}' says where the choice is made, in a remark not read; say it with the goal "
                    "('a vase in the dining room or the living room')")


def choice_of_no_goal(remark: str, kind: str) -> str:
    return rephrase(f"'{remark}' leaves a choice of {kind}, but no {kind} is a goal of the mission; name the "
                    "one meant as the goal")


def purpose_of_several(said: str, things: str) -> str:
    return rephrase(f"'{said}': each of {things}, or only the place as the goal? Say 'go to X and check each "
                    "of ...', or leave the purpose out")


def obliged_before_that(said: str) -> str:
    return rephrase(f"{said}: X first and then the goal said before, or that goal not before X? Say 'X, then "
                    "Y', or 'do not go to Y until X'")


def room_or_fixture(said: str, room: str, fixture: str) -> str:
    return rephrase(f"'{said}' could be the {room} or the {fixture} in it; say 'the {room}' or "
                    f"'the {fixture}'")


def which_visit_of_scope(rooms: str) -> str:
    return rephrase(f"the sentence's room ({rooms}) is visited more than once in the order said before "
                    "it: on which visit? Put the sentence's goals in that order ('..., then X in the "
                    "kitchen, then ...')")


def after_before_or_then(said: str) -> str:
    return rephrase(f"'{said}': after what was said before it, or before it? Say 'then' (what follows comes "
                    "after) or put 'after ...' first ('after you ..., go to ...')")


def out_of_text_order(later: str, earlier: str) -> str:
    return rephrase(f"'{later.split(',')[0]}' is said before '{earlier.split(',')[0]}' but would be done "
                    "after it, and no word says so; put the goals in the order they must be done (with "
                    "'then'), or say 'first' / 'before' / 'in any order'")


def before_which(rest: str) -> str:
    return rephrase(f"'before that' at {rest}: it is not clear which of the earlier goals this comes before; "
                    "put the goals in the order they must be done (with 'then')")


def before_which_trailing(rest: str) -> str:
    return rephrase(f"'before that' at {rest}: it is not clear which of the earlier goals this comes before; "
                    "put the goals in the order they must be done")


def precedes_which(said: str) -> str:
    return rephrase(f"'{said}': it is not clear which of the earlier goals this comes before; put the goals "
                    "in the order they must be done (with 'then')")


def follows_nothing(said: str) -> str:
    return rephrase(f"'{said}' says it comes after the sentence before, which has no goals to follow (only "
                    "conditions or prohibitions); say the order within one sentence ('A, then B')")


def precedes_needs_goals() -> str:
    return rephrase("'before that' / 'first' in a later sentence needs a plain list of goals in this "
                    "sentence and the one before it")


def after_first_sentence(first: str) -> str:
    return rephrase(f"'{first.strip()}' says what comes first, and a later sentence of goals in an order of "
                    "their own does not say where they go in its sequence: put the goals in the order they "
                    "must be done (with 'then')")


def trailing_first_later(word: str = "first") -> str:
    return rephrase(f"a trailing '{word}' in a later sentence: start the sentence with 'Before that' or put "
                    "the goals in the order they must be done")


def before_that_of_nothing(said: str) -> str:
    return rephrase(f"'{said}': no goal is named before it")


def last_followed_by(rest: str) -> str:
    return rephrase(f"'last' followed by {rest}: put the goals in the order they must be done (with 'then'), "
                    "or say 'finally'")


def on_the_way_to_which() -> str:
    return rephrase("'on the way' after several goals: it is not clear on the way to which; put the goals "
                    "in the order they must be done (with 'then')")


def on_the_way_to_several(count: int) -> str:
    return rephrase(f"'on your way to' a destination of {count} places: is it a goal to visit each of "
                    "them, or only the direction you are heading? Name the place to go to last ('then go to "
                    "X'), or leave the destination out")


def floor_said_twice(said: str) -> str:
    return rephrase(f"'{said}' names a floor twice in a row: the same floor said again, or a correction? "
                    "Name the floor once")


def floor_left_at_once(said: str) -> str:
    return rephrase(f"'{said}' names a floor and the next step leaves it: no place on that floor is a goal; "
                    "say where to go there ('go upstairs to the office, then ...')")


def starting_place(said: str) -> str:
    return rephrase(f"'{said}' says where to start from, which is no goal; leave it out, or say where to go "
                    "(the start is where the robot is)")


def way_back_from_mid(said: str) -> str:
    return rephrase(f"'{said} ...' after what it is said with: done after that place, or before it? Open the "
                    "sentence with it ('On your way back from X, check Y': X, then Y) or say 'then'")


def on_the_way_to_nothing() -> str:
    return rephrase("'on the way' needs the goal it is on the way to, named before it")


def strict_after_several() -> str:
    return rephrase("'only after that' after steps that each hold several goals: after which of them? Put "
                    "the goal that must wait in a sentence of its own ('Do not enter X until ...')")


def either_of_more(said: str, described: list[str]) -> str:
    return rephrase(f"'{said}' is one of two, but it matches {len(described)}: {', '.join(described)}; say "
                    "'any ...' for one of them all, or name the room")


def avoided_goal(pronoun: str, goal: str) -> str:
    return rephrase(f"'{pronoun}' to keep away from would be '{goal}', which is also a goal; say "
                    "'never enter X' with the place named")


def way_back_to(said: str) -> str:
    return rephrase(f"'{said} ...' puts what follows before that place and after what came before, which is "
                    "not read; say 'then Y, then go to X'")


def on_your_way_there() -> str:
    return rephrase("'on your way there': say 'before going to X, ...' or put the goals in order")


def carried_through(said: str) -> str:
    return rephrase(f"'{said} ...': the way it is carried, after it is picked up, is not read; say where it "
                    "goes ('take it to X') and, if it matters, 'then go through Y'")


def waypoint_of_which(rest: str) -> str:
    return rephrase(f"it is not clear which of the goals {rest} is on the way to; say 'go to X, then Y'")


def after_all_of_which(said: str) -> str:
    return rephrase(f"'{said}': after the goals of this sentence only, or of the whole mission? Say 'then' "
                    "and name what comes after what")


def after_all_count(said: str, goals: int, number: int, sentence: bool = True) -> str:
    where = "this sentence names {} goals before it" if sentence else "the sentence before it names {} goals"
    return rephrase(f"'{said}': {where.format(goals)}, not {number}")


def after_all_of_nothing(said: str, sentence: bool = True) -> str:
    return rephrase(f"'{said}': no goal is named before it" + (" in this sentence" if sentence else ""))


def bulleted_among_numbered(said: str) -> str:
    return rephrase(f"'{said}': a bulleted item among numbered ones is in no order the numbers give "
                    "(before, after or with the numbered item above it?); number every step, or say the "
                    "order in words")


def prohibition_in_between(said: str) -> str:
    return rephrase(f"'{said}': a prohibition between two goals only (not before the first, nor after the "
                    "last) cannot be expressed here; say 'never enter X' for the whole mission")


def back_to_start(said: str) -> str:
    return rephrase(f"'{said}' names no place: coming back to where the robot started cannot be required (a "
                    "plan ends at its last goal); leave it out, or name the place to come back to")


def order_remark_in_numbered(said: str) -> str:
    return rephrase(f"'{said}': the numbers put the items in order and the remark leaves the order free; "
                    "which holds? Use bullets for any order, or leave the remark out")


def order_remark_after_then(said: str) -> str:
    return rephrase(f"'{said}': 'then' puts the goals in order and the remark leaves the order free; which "
                    "holds? Say 'A and B, in any order' or 'A, then B'")


def aside_after_prefix(prefix: str, aside: str) -> str:
    return rephrase(f"'({aside})' after '{prefix}': is it what is done there (before what follows) or a step "
                    "of its own? Say it without the parentheses, in order with 'then'")


def work_after_prefix(prefix: str, work: str) -> str:
    return rephrase(f"'{work}' after '{prefix}' is part of what is done first, and is not read there; say it "
                    "as one step ('once you have checked the oven in the kitchen, ...')")


def after_a_middle_step(said: str) -> str:
    return rephrase(f"'{said}' goes on after a step in the middle of the sequence before it: before or after "
                    "the steps that follow that one? Say the whole order with 'then'")


def line_of_sentences(heading: str, said: str) -> str:
    return rephrase(f"'{said}' shares a line with a sentence, or stands without a list marker among marked "
                    f"items, under '{heading}': which of them are steps of that order is not known; put each "
                    "step on a line of its own, or number them")


def after_clause_between(said: str, before: str) -> str:
    return rephrase(f"'{said}' between two clauses: is it done after '{before}', or only before what "
                    "follows it, or before both? Say it in order with 'then' ('A, then X, then B'), or give "
                    "it its own sentence ('After X, B.')")


def prefix_took_the_goals(said: str) -> str:
    return rephrase(f"'{said}': are the goals after the comma part of what comes {said.split()[0].lower()} "
                    "them, or the steps to do? Give them a verb ('Before X, go to Y.') or say the order with "
                    "'then'")


def before_clause_between(said: str, before: str) -> str:
    return rephrase(f"'{said}' between two clauses: does '{before}' come before it too, or only what "
                    "follows it? Say it in order with 'then' ('A, then B, then X'), or give it its own "
                    "sentence ('Before X, B.')")


def after_all_of_sentences(said: str) -> str:
    return rephrase(f"'{said}': after the goals of the sentence before it, or of every sentence before it? "
                    "Say it in one sentence ('A and B, and after both, C') or name what comes after what")


def done_that_of_nothing() -> str:
    return rephrase("'done that' does not refer to any goal named before it")


def only_after_needs(what: str = "'only after X, ...'") -> str:
    return rephrase(f"{what} needs one condition and one step after the comma")


def only_after_two_readings(said: str, room: str, thing: str) -> str:
    return rephrase(f"'only after' about '{said}': it can mean not entering {room} before that, or not "
                    f"reaching {thing} before that; say 'only enter {room} after ...' or 'reach {thing} only "
                    "after ...'")


def only_before_a_verb(rest: str) -> str:
    return rephrase(f"'only' before a verb is understood as 'only <do X> after Y'; found {rest}")


# -------------------------------------------------------------------------------------------- negation
def never_go_back() -> str:
    return rephrase("'never go back / return to X' (after a first visit) is not understood; say 'never "
                    "enter X' for the whole mission")


def unknown_negated_verb(said: str, verb: str) -> str:
    return rephrase(f"'{said}': a prohibition is read only with a verb of going or touching ('never "
                    f"enter / touch / use X') or of a goal not to miss ('don't forget X'), and '{verb}' is "
                    "neither")


def partial_prohibition(rest: str) -> str:
    return rephrase(f"a prohibition for part of the mission ({rest}) is not understood; say 'never enter X' "
                    "(the whole mission) or 'do not enter X until ...'")


def there_goal_or_kept_out_until(goal_room: str, kept_out: str) -> str:
    return rephrase(f"'there' could be {goal_room}, where the goal named last is, or {kept_out}, kept out of "
                    "until then; name the room")


def time_after_goals(said: str) -> str:
    return rephrase(f"'{said}' after goals: does what follows come after them, or at any time? Say 'then' "
                    "or 'later' for after them, or leave the time out")


def order_by_a_time(said: str) -> str:
    return rephrase(f"'{said}' orders the steps by a time or an event, not by a place (a plan has no clock); "
                    "leave the time out, or set it apart with a comma ('Before lunch, check ...')")


def until_a_time(said: str) -> str:
    return rephrase(f"'{said}': a prohibition until a time or an event cannot be required (a plan has no "
                    "clock); say until which room or object is reached, or forbid it for the whole mission")


def until_needs_one_goal(prefix: bool = False) -> str:
    return rephrase("'until X, ...' needs one goal X" if prefix else "'... until X' needs one goal X")


def off_limits_list_of_one(said: str) -> str:
    return rephrase(f"'{said}': is each of them off limits, or only the last one? Join them with 'and' "
                    "('X and Y are off limits'), or say the others in a sentence of their own")


def left_by_no_goal(said: str) -> str:
    return rephrase(f"'{said}' says where something was left, by a place that is no goal: is it a place to "
                    "look? Name it as a goal ('check the ...') if it is, or leave the remark out")


def done_in_a_room_of_goals(said: str) -> str:
    return rephrase(f"'until' {said!r} is done: until you enter it, or until what you do there is done? Say "
                    f"'until you have been to {said}', or name the goal ('until you have checked ...')")


def until_what_it_forbids() -> str:
    return rephrase("'... until X' where X is the very place forbidden (as when 'it' points back to it): "
                    "name what must come first, e.g. 'don't enter the kitchen until you have picked up the "
                    "bowl'")


def until_prohibitions_only() -> str:
    return rephrase("'until X, ...' is understood with prohibitions only (e.g. 'until you have been to the "
                    "kitchen, stay out of the office'); put goals in their own sentence")


def states_something(said: str) -> str:
    return rephrase(f"'{said} ...' states something; it is not understood as a goal or a prohibition (say "
                    "what to do, e.g. 'go to ...', 'never enter ...', '... is off limits')")


def stay_for_the_rest(before: str, verb: str) -> str:
    return rephrase(f"'{before} {verb} ...': staying on a floor for the rest of the mission only is not "
                    "understood; say 'stay on ... the whole time'")


def no_other_floor(said: str) -> str:
    return rephrase(f"'{said}': the building has no other floor")


# ------------------------------------------------------------------------------------------ conditions
def negative_trigger() -> str:
    return rephrase("negative triggers ('whenever you do not ...') are not understood")


def negative_condition() -> str:
    return rephrase("negative conditions ('if you do not ...') are not understood")


def condition_goes_on(rest: str) -> str:
    return rephrase(f"the condition goes on with {rest}; a condition is one action (e.g. 'if you go to the "
                    "kitchen, ...')")


def condition_names_nothing() -> str:
    return rephrase("the condition names no room or object")


def trigger_needs_one() -> str:
    return rephrase("'whenever ...' needs one room or object (or a choice of them) as its trigger")


def whenever_goals_only() -> str:
    return rephrase("'whenever X, ...' is understood with goals only (e.g. 'whenever you enter the kitchen, "
                    "open the fridge'), not with prohibitions")


def when_afterwards() -> str:
    return rephrase("'when you go to X, ... afterwards' is read by some as on each visit of X and by others "
                    "as once; say 'every time you go into X, ...' (each visit) or 'if you go into X, ... "
                    "afterwards' (after that visit)")


def optional_remark(said: str) -> str:
    return rephrase(f"'{said}' makes a step optional, which cannot be expressed; leave the step out or make "
                    "it a goal")


def condition_not_inside(said: str) -> str:
    return rephrase(f"'{said}' is not being in the place (near it, past it); only going into a place can be "
                    "a condition ('if you go into X, ...')")


def first_in_consequent(said: str) -> str:
    return rephrase(f"in '{said}', 'first' is not clear: before going there, or the first thing done there? "
                    "Say the order with 'then' ('if you go into X, check Y, then Z')")


def condition_again(said: str) -> str:
    return rephrase(f"'{said}': a condition on a second visit is not understood; say what to do on every "
                    "visit ('every time you go into X, ...') or after a visit ('if you go into X, ... "
                    "afterwards')")


def once_or_each_visit(said: str) -> str:
    return rephrase(f"'{said}' is read by some as once and by others as on each visit; say 'every time you "
                    "go into X, ...' (each visit) or 'if you go into X, ... afterwards' (after that visit)")


def before_then(said: str) -> str:
    return rephrase(f"in '{said}' it is not clear whether what follows 'then' comes before or after the "
                    "place named after 'before'; say it in order ('A, then B, then X' or 'A, then X, then "
                    "B')")


def before_near(said: str) -> str:
    return rephrase(f"'{said}' can mean 'stay out of it until then' or 'go there afterwards'; say 'do not go "
                    "into X until ...' or '..., then go to X'")


def bare_when() -> str:
    return rephrase("'when X, Y' can mean 'after X, Y' (in order), 'whenever X, Y' (each time) or 'if X, Y' "
                    "(X at all); say which")


def nothing_to_do(where: str) -> str:
    return rephrase(f"nothing to do {where}")


def several_actions_after_condition() -> str:
    return rephrase("a condition followed by several actions: it is not clear which of them belong to the "
                    "condition; put the other goals in a sentence of their own")


def several_actions_before_condition(rest: str) -> str:
    return rephrase(f"several actions before {rest}: it is not clear which of them the condition is about; "
                    "give the condition its own sentence ('If ..., ...')")


def only_after_which_wait(waiting: list[str]) -> str:
    return rephrase(f"'only after' follows several goals, one of them what it waits for: it is not clear "
                    f"whether {' and '.join(waiting)} all wait or only the last; say 'go to X only after Y' "
                    "in a sentence of its own")


def any_time_in_sequence(said: str) -> str:
    return rephrase(f"'{said}': the last goal anywhere in that order, or after the rest? Say it in a "
                    "sentence of its own ('At any point, sit on X.') or put it in the order with 'then'")


def superlative(word: str) -> str:
    return rephrase(f"'{word}' compares things the scene does not measure; name the one meant (by its room "
                    "or what is near it)")


def not_the_one(said: str) -> str:
    return rephrase(f"'{said}': which one is meant (instead of one named before), or a place to keep away "
                    "from? Name the one meant, or say 'never enter X' / 'avoid X' to keep away")


def not_after_comma(said: str) -> str:
    return rephrase(f"'{said}' after a comma: which one is meant (instead of it), or a place to keep away "
                    "from? Say 'never enter X' / 'avoid X' to keep away")


# ------------------------------------------------------------------------------------- back-references
def antecedent_qualifier_or_goal(pronoun: str, qualifier: str, goal: str) -> str:
    return rephrase(f"'{pronoun}' could be '{qualifier}', named to say which place, or '{goal}', a goal "
                    "named before it; name the thing")


def one_of_several_set_aside(pronoun: str, phrase: str, keys: list[str]) -> str:
    return rephrase(f"'{pronoun}' refers to '{phrase}', said in a sentence that is not part of the mission, "
                    f"which matches {len(keys)} things ({', '.join(keys)}); name the one meant, or say 'any "
                    "one of them'")


def count_or_times(said: str) -> str:
    return rephrase(f"'{said}': how many there are, or how many times? Say 'both ...' / 'the two ...', or "
                    "'twice'")


def next_without_to(said: str) -> str:
    return rephrase(f"'{said}': 'next to' (beside it) or 'next,' (then)? Say 'next to' or 'then'")


def word_of_two_kinds(said: str, categories: list[str]) -> str:
    return rephrase(f"'{said}' can name a {' or a '.join(categories)} here; say which (e.g. "
                    f"'the {categories[0]}s')")


def antecedent_of_several(pronoun: str, phrases: list[str]) -> str:
    named = ", ".join(f"'{p}'" for p in dict.fromkeys(phrases))
    return rephrase(f"'{pronoun}' could be any of {named}, named in a sentence that is not part of the "
                    "mission; name the one meant")


def no_antecedent(pronoun: str, plural: bool) -> str:
    return rephrase(f"'{pronoun}' does not refer to any {'group of ' if plural else ''}room or object named "
                    "before it")


def no_room_antecedent() -> str:
    return rephrase("'it' does not refer to any room named before it")


def that_of_several(phrases: list[str]) -> str:
    return rephrase("'that' could be any of " + ", ".join(f"'{p}'" for p in phrases)
                    + " named before it; name the one meant")


def next_door_to_nothing(said: str) -> str:
    return rephrase(f"'{said}' does not say next to which room: no room or object was named before it; name "
                    "the room ('the bathroom next to the bedroom')")


def next_to_an_object(said: str, phrase: str) -> str:
    return rephrase(f"'{said}': 'it' is '{phrase}', an object; 'next to' is understood for rooms only "
                    "(distances between objects are not known)")


def there_refers_to_nothing() -> str:
    return rephrase("'there' does not refer to any place named before it")


def antecedent_or_kept_out(pronoun: str, before: str, locating: str) -> str:
    return rephrase(f"'{pronoun}' could be '{before}', or '{locating}', named to say which place to keep out "
                    f"of; name the thing instead of '{pronoun}'")


def counted_floor(said: str) -> str:
    return rephrase(f"'{said}': a floor is one place, not things to count; name the rooms or objects on it "
                    "('both bathrooms on the top floor')")


def there_goal_or_kept_out(goal: str, kept_out: str) -> str:
    return rephrase(f"'there' could be '{goal}', the last place to go, or '{kept_out}', a place to keep out "
                    "of named after it; name the place")


def way_of_no_goal(said: str) -> str:
    return rephrase(f"'{said}': on the way to which goal? Say 'go up to X, and Y on your way up', or put the "
                    "goals in order with 'then'")


def wait_for_an_end(said: str) -> str:
    return rephrase(f"'{said}': the robot cannot wait for that to end (a plan has no clock and senses no "
                    "events); leave it out, or say the goals only")


def brought_to_speaker(placed: str) -> str:
    return rephrase(f"'me' is where you are, said in words not read ('{placed}'); say where to take it "
                    "('bring it to the couch')")


def goal_and_forbidden(places: list[str]) -> str:
    return rephrase(f"the mission both asks for {' and '.join(places)} and forbids it for the whole mission; "
                    "say which holds")


def cannot_be_done(parts: list[str]) -> str:
    return rephrase("no way through this scene's rooms and doors from its starts can do all of this "
                    "together: " + " ".join(parts) + " Say which of them holds")


def one_of_goals(said: str, group: str) -> str:
    return rephrase(f"'{said}' after '{group}': only one of them, or all of them and then one again? Say "
                    "'one of ...' with the place instead")


def there_done_before(goal: str) -> str:
    return rephrase(f"'there' could be '{goal}', named last, or the place to go after it; name the place")


def there_goal_or_mention(goal: str, mention: str) -> str:
    return rephrase(f"'there' could be '{goal}', the last place to go, or '{mention}', named after it in "
                    "what was set aside; name the place")


def there_place_or_thing(place: str, thing: str) -> str:
    return rephrase(f"'there' is '{place}', named in what was set aside with '{thing}' in it: is the goal to "
                    f"go into the room, or to reach '{thing}'? Name the goal")


def antecedent_goal_or_mention(pronoun: str, goal: str, mention: str) -> str:
    return rephrase(f"'{pronoun}' could be '{goal}', named last as a goal, or '{mention}', named after it in "
                    "what was set aside; name the thing")


def stated_there_order(said: str) -> str:
    return rephrase(f"'{said}' puts it at the place named before: is what follows done on that visit, or at "
                    "any time? Say 'then ...' for on that visit")


def thing_left_there(said: str, thing: str) -> str:
    return rephrase(f"'{said}' says the {thing} is where the robot goes: is the goal to reach the {thing}, "
                    "or only to go there? Name the goal")


def back_there(phrase: str) -> str:
    return rephrase(f"'back there': 'there' is the place named last ('{phrase}'), where the robot just was; "
                    "name the place to go back to")


def there_is_several(phrase: str) -> str:
    return rephrase(f"'there' refers back to '{phrase}', which is several places; name the one meant")


def there_is_not_a_floor(noun: str, what: str) -> str:
    return rephrase(f"'{noun} there': 'there' refers back to {what}, not a floor (rooms are not inside "
                    "rooms); name the floor (e.g. 'on floor 1') or the room")


def floor_or_place(said: str, floor: str, place: str) -> str:
    return rephrase(f"'{said}' could refer back to '{floor}' or to '{place}', named after it; name the floor "
                    "or room again")


def group_size(said: str, phrase: str, n: int, count: int) -> str:
    return rephrase(f"'{said}': '{phrase}' is {n}, not {count}")


def demonstrative_size(said: str, antecedent: str, n: int, count: int) -> str:
    return rephrase(f"'{said}' refers back to '{antecedent}', which is {n}, not {count}")


def whose_room(said: str, rooms: list[str]) -> str:
    named = f"rooms said before: {', '.join(rooms)}" if rooms else "no room was said to be someone's"
    return rephrase(f"'{said}': whose room? ({named}); name the room ('the bedroom with the two beds')")


def permission_only(said: str) -> str:
    return rephrase(f"'{said}' gives permission, which neither asks for the place nor forbids it; say 'go to "
                    "X' if it is a goal, or leave it out")


def times_of_what(said: str) -> str:
    return rephrase(f"'{said}': how many times is said for several places or twice; say it after one place "
                    "('visit the kitchen twice, then the office')")


def pick_from_one(remark: str, phrase: str) -> str:
    return rephrase(f"'{remark}' after '{phrase}', which is one place: one of what? Name the room or object "
                    "to choose from ('any chair in the kitchen')")


def ordinal_of_several(said: str, phrase: str) -> str:
    return rephrase(f"'{said}': '{phrase}' names several at once, so which came first is not said; name it "
                    "again ('the bed in the ...')")


def ordinal_of_unordered(said: str, first: str, second: str) -> str:
    return rephrase(f"'{said}': '{first}' and '{second}' were named in no order, so the first named may "
                    "not be the first visited; name it again")


def ordinal_of_too_few(said: str, named: int) -> str:
    before = "only one was" if named == 1 else f"only {named} were"
    return rephrase(f"'{said}' counts what was named before it, and {before}; name it ('the bed in the ...')")


def placed_on_a_room(said: str, phrase: str) -> str:
    return rephrase(f"'{said}': 'it' is '{phrase}', which is no object; name what the thing is on")


def between_rooms_only(said: str) -> str:
    return rephrase(f"'{said}': 'between' is read for a room between two or more rooms (connected to each); "
                    "name the rooms")


def short_stay_not_a_goal(said: str, phrase: str) -> str:
    return rephrase(f"'{phrase} {said}': '{said}' is read only after a goal (the plan reaches it and does "
                    "not time the stay); a place kept away from, or a condition, for a while only is not "
                    "understood")


def its_of_which(said: str, phrases: list[str]) -> str:
    named = " or ".join(f"'{p}'" for p in phrases)
    return rephrase(f"'{said}': 'its' could be of {named}, and these differ here; name it ('the ... in the "
                    "...')")


def no_other(noun: str) -> str:
    return rephrase(f"'the other {noun}': no {noun} was named before it")


def choice_back_reference(said: str, phrase: str, alternative: bool) -> str:
    what = "one alternative of a choice ('... or ...')" if alternative else "a choice"
    return rephrase(f"'{said}' refers back to '{phrase}', {what}: which one depends on the choice the robot "
                    "makes; name the room or object instead")


def which_room_again(said: str, named: str) -> str:
    return rephrase(f"'{said}': which one? Rooms named before it: {named}; name the room again")


def demonstrative_disagrees(said: str, phrase: str, keys: str) -> str:
    return rephrase(f"'{said}' refers back to '{phrase}' ({keys}), which does not fit what the phrase says; "
                    "name the room or object again")


def demonstrative_of_several(said: str, phrase: str, keys: str) -> str:
    return rephrase(f"'{said}' refers back to '{phrase}', which is several ({keys}); say which one")


def demonstrative_of_one(said: str, phrase: str, key: str) -> str:
    return rephrase(f"'{said}' refers back to '{phrase}', which is one ({key}), not several; name the room "
                    "or object again")


def demonstrative_of_nothing(said: str, what: str) -> str:
    return rephrase(f"'{said}' does not refer back to any {what} named before it (a demonstrative such as "
                    f"'that' / 'this' / 'the same' names again something already said); name the {what}")


def demonstrative_read_or_told(said: str, read: str, told: str) -> str:
    return rephrase(f"'{said}' could be '{read}', named before as part of the mission, or '{told}', named "
                    "after it in what was set aside; name it")


def demonstrative_or_step_room(said: str, antecedent: str, room: str, here: str) -> str:
    return rephrase(f"'{said}' after going to {room}: the one named before ('{antecedent}') or the one "
                    f"there ({here})? say 'the same {said.split()[-1]}' or name it with its room")


# ---------------------------------------------------------------------------------------------- floors
def floor_outside(said: str, building: str, floors: int, british: bool = False) -> str:
    first = ("floor 1, counted from the ground floor the mission names" if british else "floor 0")
    return rephrase(f"'{said}': the building {building!r} has floors 0 to {floors - 1} (floor 0 is the "
                    f"lowest; 'the first floor' is {first})")


def floor_move_after_goal(said: str) -> str:
    return rephrase(f"'{said}' right after a goal: where that goal is, or a move of its own? Say 'the X on "
                    "the bottom floor' or '..., then go down to ...'")


def floor_move_then_after_goal(said: str) -> str:
    return rephrase(f"'{said}' after another goal: does what follows the move come after that goal too? Say "
                    "it in order ('A, then go upstairs to B') or in sentences of their own")


def before_with_prohibition(said: str) -> str:
    return rephrase(f"'{said}': a prohibition beside other goals or times after 'before': which of them hold "
                    "only until then? Say 'don't enter X until you have been to Y' in a sentence of its own")


def ordinal_floor_either_way(said: str) -> str:
    return rephrase(f"'{said}' is the lowest floor counted one way (US: the first floor is floor 0) and the "
                    "one above it counted the other (British: the ground floor, then the first floor), and "
                    "both name places here; say 'floor 0' / 'the ground floor' or 'floor 1'")


def no_middle_floor(said: str, building: str, floors: int) -> str:
    return rephrase(f"'{said}': the building {building!r} has {floors} floors (0 to {floors - 1}), so no "
                    "middle one; say which floor")


def needs_start_floor(said: str, building: str, listing: str, to_stay: bool = False) -> str:
    which = "say which floor to stay on" if to_stay else "say which floor"
    return rephrase(f"'{said}' depends on where the robot starts, which is not known here; {which} (the "
                    f"building {building!r} has {listing})")


def off_the_building(said: str, start: int, building: str, floors: int) -> str:
    return rephrase(f"'{said}': the robot starts on floor {start} and the building {building!r} has floors 0 "
                    f"to {floors - 1}")


def relative_to_which(said: str, phrase: str, floors: str, start: int) -> str:
    return rephrase(f"'{said}' after '{phrase}' (floors {floors}): relative to the start (floor {start}) or "
                    "to there? Say which floor")


def readings_differ(said: str, after: str, start: int) -> str:
    return rephrase(f"'{said}' after '{after}': relative to the start (floor {start}) or to there? The two "
                    "differ here; say which floor")


def same_floor_of_a_choice(phrase: str, floors: str) -> str:
    return rephrase(f"'the same floor' as '{phrase}', which is on floors {floors}: the floor depends on "
                    "which one is chosen; say which floor, or give each choice its own sentence")


def same_floor_of_nothing() -> str:
    return rephrase("'the same floor' / 'that floor' does not refer to any place named before it")


def up_there_of_nothing(word: str) -> str:
    return rephrase(f"'{word} there' does not refer to any place named before it")


def up_there_not_so(said: str, last: str) -> str:
    return rephrase(f"'{said}' after '{last}', which is not {said.split()[0]}stairs from where the robot "
                    f"starts: the floor of '{last}', or another? Name the floor ('on floor 1')")


def stay_where(word: str, where: str, building: str, floors: int) -> str:
    return rephrase(f"'stay {word}': the start floor {where} and the building {building!r} has floors 0 to "
                    f"{floors - 1}; say 'stay on floor k' or 'never go to floor k'")


def stated_floor_unclear(word: str, building: str, floors: int, extreme: int) -> str:
    return rephrase(f"'{word}': the building {building!r} has floors 0 to {floors - 1}; say which floor the "
                    f"robot is on (e.g. 'I am on floor {extreme}')")


def stated_floor_contradicts(said: str, floor: int, start: int) -> str:
    return rephrase(f"'{said}' says the robot is on floor {floor}, but it starts on floor {start}; say where "
                    "it really is")


def stairs_on_kept_floors(keys: list[str]) -> str:
    return rephrase(f"'the stairs' on a mission kept to its floor: the staircase ({', '.join(keys)}) is on "
                    "that floor; say 'never enter the staircase' to keep out of it too, or leave it out "
                    "(staying on the floor already keeps off the way up and down)")


def not_on_kept_floors(floors: Sequence[int]) -> str:
    return f", on the floor(s) the mission stays on ({', '.join(str(f) for f in floors)})"
