"""Grounding a phrase with a head noun: its head's entities, narrowed by the context (floors, the rooms of
the step), by each of its qualifiers in turn, by a demonstrative's antecedent and by an apposition; then
checked (exactly one for *the*, the number said, at least one).

Each kind of qualifier of the syntax tree has its applier here (:data:`APPLIERS`), which takes the phrase so
far (:class:`.phrases.Noun`) and returns it narrowed.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import replace
from itertools import pairwise
from typing import Any

from sgplan.errors import MissionError
from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding import backref
from sgplan.llm.offline.grounding.discourse import Discourse, FloorReading, Grounded, Where
from sgplan.llm.offline.grounding.floors import determined, floors_of, on_floors, one_floor, same_floor
from sgplan.llm.offline.grounding.phrases import (
    Noun,
    antecedent,
    check,
    ground_phrase,
    grounds,
    head_entities,
)
from sgplan.llm.offline.grounding.places import next_to_it, there_floors, there_rooms, there_rooms_holding
from sgplan.llm.offline.names import Entity, head_word
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.registry import Registry
from sgplan.llm.offline.syntax.tree import (
    Attachment,
    Between,
    ByUnlisted,
    Contains,
    Described,
    Except,
    Holds,
    InRoom,
    Lacks,
    Mode,
    NextTo,
    NounPhrase,
    OnFloor,
    Possessive,
    RelativeFloor,
    SameFloor,
    ShortStay,
    Span,
    There,
    ThereNP,
    UpThere,
)

APPLIERS: Registry[Callable[[Any, Noun, Described, Where, Discourse], Noun]] = Registry("qualifier")
applies = APPLIERS.register


@grounds(Described)
def ground_described(np: Described, where: Where, disc: Discourse) -> Grounded:
    """Ground a described phrase (see the module docstring)."""
    noun = in_context(np, head_entities(np, disc, where.rooms), where, disc)
    guessed = noun.guessed
    for qualifier in np.qualifiers:
        noun = APPLIERS(qualifier, noun, np, where, disc)
        guessed = noun.guessed or guessed
    if disc.confined is not None and where.role == "avoid":
        noun = kept_floors_to_avoid(np, noun, disc)
    mode: Mode = np.determiner.mode or "the"
    if any(isinstance(q, InRoom) and in_chosen_rooms(q, noun.head) for q in np.qualifiers):
        mode = "any"  # "the chair in the living room or the dining room", "the toilet in either bathroom"
    core = core_text(np, disc)
    if np.determiner.owner is not None:  # "the baby's teddy bear": whose it is, the scene does not say
        if noun.head.kind == "room" and np.apposition is None:  # "the kids' bedroom - the one with ..."
            rf.refuse(rf.whose_room(core, []))
        disc.put_aside(np.determiner.owner)
    if np.determiner.pointer is not None:
        noun, mode = demonstrative(np, noun, mode, core, where, disc)
    noun = scoped(np, noun, mode, core, where, disc)
    if np.apposition is not None:  # "the bathroom, the one upstairs": the apposition says which
        which = ground_phrase(np.apposition, Where("qualifier"), disc)
        noun.entities = [e for e in noun.entities if (e in which.entities) != np.apposition_excludes]
    one_floor(noun.entities, guessed, disc)  # "the TV upstairs in the bedroom": the bedrooms' one TV
    kinds_of_room = {e.category for e in noun.entities} if noun.head.kind == "room" else set()
    several = mode in ("all", "any") or where.role == "avoid"  # one of them: refused as ambiguous below
    if several and len(kinds_of_room) > 1 and len(noun.head.categories) > 1:  # "no BRs": which kind?
        rf.refuse(rf.word_of_two_kinds(core, sorted(kinds_of_room)))
    # which couch is big is not known; nor which bathroom is the "downstair" one, even where only one of
    # them was visited before: a description must leave one entity before "back to" narrows by the visits
    if np.descriptive and len(noun.entities) > (np.determiner.count or 1):
        rf.refuse(rf.undecided_description(np.descriptive, core, noun.entities, not noun.head.plural))
    if where.revisit and mode in ("the", "any") and len(noun.entities) > 1:  # "then back to the bathroom"
        before = {e.key for g in disc.goals_before(np.span.start) for e in g.entities}
        visited = [e for e in noun.entities if e.key in before]
        if len(visited) == 1 or (mode == "any" and visited):  # "back to a TV": one of those of the visit
            noun.entities = visited
    g = Grounded(disc.said(np.span.start, np.span.end), np.span.start, np.span.end, noun.entities, mode,
                 noun.room_scoped, where.role, np.determiner.count,
                 noun.head.kind == "room" and not noun.head.categories)
    check(g, noun.head, np.determiner.count, np.remark_follows, disc, either=np.either_remark)
    return disc.record(g)


def in_chosen_rooms(q: InRoom, head: Head) -> bool:
    """Whether ``q`` places the object in one room of a choice: *in A or B* (*the chair in the living room or
    the dining room*), or, for one object, *in either / any / one of the <rooms>* (*the toilet in either
    bathroom*: the one of whichever room is chosen, so one of them all). *the beds in either bedroom* stays
    each bed (*either* is also *each of two*)."""
    if len(q.rooms) > 1:
        return q.choice
    room = q.rooms[0]
    return (q.choice or (isinstance(room, Described) and room.determiner.mode == "any")) and not head.plural


def kept_floors_to_avoid(np: Described, noun: Noun, disc: Discourse) -> Noun:
    """On a mission kept to some floors, a place to keep out of: *the bathroom* is the one there (the others
    are kept out of already, so the mission is the same either way; only the ambiguity goes), none there
    leaves it as it is; *the stairs* are the way up and down, the staircases of the other floors (blind
    writers read it so), refused when the only ones are on the kept floors."""
    assert disc.confined is not None
    kept = disc.vocab.on_floor(noun.entities, disc.confined)
    if disc.said(np.span.start, np.span.end).lower().split()[-1] not in lx.PLURAL_LOOKING:
        return replace(noun, entities=kept or noun.entities)
    if all(e in kept for e in noun.entities):
        rf.refuse(rf.stairs_on_kept_floors([e.key for e in noun.entities]))
    return replace(noun, entities=[e for e in noun.entities if e not in kept])


def core_text(np: Described, disc: Discourse) -> str:
    """The phrase as said, without its apposition (for messages)."""
    end = np.span.end if np.apposition is None else np.apposition.span.start
    return disc.said(np.span.start, end).rstrip(" ,")


def in_context(np: Described, noun: Noun, where: Where, disc: Discourse) -> Noun:
    """The head's entities narrowed by the words before the noun and by the context: *upstairs*, *the other
    X*, floor words, the floor of the verb or of a floor move, the floors the mission stays on; then a
    compound noun (*the kitchen sink*: the sink in the kitchen)."""
    vocab, entities = disc.vocab, noun.entities
    before = floors_of(np.floor_before, disc) if np.floor_before is not None else None
    if np.relative is not None:
        before = floors_of(RelativeFloor(np.relative), disc, entities)
    if np.determiner.other and not np.apposition_excludes:  # "the other X, not the one ...": it says which
        entities = others(entities, np.span.start, disc, np.apposition is not None)
    if np.determiner.ordinal is not None:
        entities = nth_named(entities, np.determiner.ordinal, np.span, disc)
    # "go upstairs and check A and B": both there
    moved = where.action_floor is not None and where.role in ("goal", "avoid")
    action = where.action_floor[0] if moved and where.action_floor is not None else None
    readings = [f for f in (before, where.floor, action) if f is not None]
    for reading in readings:
        entities = on_floors(entities, reading, disc)
    if disc.confined is not None and where.role in ("goal", "condition"):
        entities = vocab.on_floor(entities, disc.confined)  # "stay on this floor": goals there
    guessed = next((f.said for f in readings if f.unknown), None)
    if np.compound is not None:  # "the kitchen sink": the sink in the kitchen
        return Noun(np.compound, vocab.inside(vocab.of_head(np.compound), entities), True, guessed)
    return Noun(noun.head, entities, noun.room_scoped, guessed)


def others(entities: list[Entity], before: int, disc: Discourse, said_which: bool = False) -> list[Entity]:
    """*the other X*: the X not named before character ``before``: by a goal or a place to avoid naming
    only such X (*this floor* names its bedrooms among other rooms, and no bedroom in particular), or by a
    qualifier or words set aside naming one (a heading *Bathroom rounds* names no bathroom in particular);
    refused when none was, unless an apposition says which (``said_which``: *the other bedroom - the one with
    the plant*)."""
    fits = {e.key for e in entities}
    read = [g for g in disc.references if g.role != "qualifier" or len(g.entities) == 1]
    told = [g for g in disc.mentions if len(g.entities) == 1]
    said = [g for g in read + told
            if g.start < before and g.entities and all(e.key in fits for e in g.entities)]
    # a phrase naming every X names none in particular when another names one (*Bathrooms to clean: the one
    # with the vase, then the other one*); named alone, every X is named and no other is left
    particular = [g for g in said if len(g.entities) == 1 or {e.key for e in g.entities} != fits]
    named = {e.key for g in particular or said for e in g.entities} or held_in(fits, read + told, before)
    if not any(e.key in named for e in entities):
        if said_which:
            return entities
        rf.refuse(rf.no_other(head_word(entities)))
    return [e for e in entities if e.key not in named]


def held_in(rooms: set[str], said: list[Grounded], before: int) -> set[str]:
    """The rooms among ``rooms`` (keys) that hold an object named before character ``before``, each phrase
    naming one object: with no such room named itself, *the other bedroom* after *pick up the teddy bear* is
    the bedroom the teddy bear is not in (the definite check that follows refuses where that leaves
    several)."""
    return {g.entities[0].room_key for g in said if g.start < before and len(g.entities) == 1
            and g.entities[0].kind == "object" and g.entities[0].room_key in rooms}


def nth_named(entities: list[Entity], n: int, span: Span, disc: Discourse) -> list[Entity]:
    """*the first bed*, *back to the first one*: the ``n``-th of ``entities`` named before ``span`` (in the
    order first named, goals and places only). Refused unless two or more were named, each on its own (*both
    bedrooms, then the first one*: which came first?)."""
    keys, said = {e.key for e in entities}, disc.said(span.start, span.end)
    named = [g for g in sorted(disc.references, key=lambda g: g.start) if g.start < span.start
             and g.role != "qualifier" and g.entities and all(e.key in keys for e in g.entities)]
    several = next((g for g in named if len(g.entities) > 1), None)
    if several is not None:
        rf.refuse(rf.ordinal_of_several(said, several.phrase))
    together = next(((a, b) for a, b in pairwise(named) if a.entities != b.entities
                     and not said_in_order(disc.text[a.end:b.start], disc.text)), None)
    if together is not None:  # "the bedroom and the other one, then the first one": named or visited first?
        rf.refuse(rf.ordinal_of_unordered(said, together[0].phrase, together[1].phrase))
    order = list(dict.fromkeys(g.entities[0].key for g in named))
    if not order:  # "the first bathroom" with none named: perhaps its floor
        rf.refuse(rf.ordinal_not_of_a_floor(said.split()[1].lower()))
    if len(order) < 2 or n > len(order):
        rf.refuse(rf.ordinal_of_too_few(said, len(order)))
    return [e for e in entities if e.key == order[n - 1]]


def demonstrative(np: Described, noun: Noun, mode: Mode, said: str, where: Where,
                  disc: Discourse) -> tuple[Noun, Mode]:
    """*that bathroom*, *those two bedrooms*, *one of those X*: the entities of the phrase pointed back to
    (:func:`.backref.resolve`), never a fresh set; refused when it cannot be resolved."""
    det = np.determiner
    plural = noun.head.plural or det.quantified is not None or det.pointer in lx.PLURAL_DEMONSTRATIVES
    if det.pointer in lx.OWNERS:
        return Noun(noun.head, owners_room(np, noun, said, disc), False), "the"
    got = backref.resolve(said, noun.head, plural, noun.entities, pointed_in(said, noun, np.span.start, disc),
                          np.span.start, disc.vocab.by_key, where.role == "goal")
    if isinstance(got, str):
        rf.refuse(got)
    if det.count is not None and len(got.entities) != det.count:
        rf.refuse(rf.demonstrative_size(said, got.antecedent, len(got.entities), det.count))
    if (here := of_the_step_room(np, noun, got, said, where, disc)) is not None:
        return Noun(noun.head, here, True), "the"
    return Noun(noun.head, got.entities, noun.room_scoped or got.room_scoped), det.quantified or got.mode


def pointed_in(said: str, noun: Noun, start: int, disc: Discourse) -> list[Grounded]:
    """Where the demonstrative ``said`` (at character ``start``) points back: the phrases read, or, when none
    of them fits it, the rooms and objects named in words set aside (*The baby is napping in the bedroom
    with the vase, so avoid that room*), as *it* does; refused when a fitting one was set aside after the
    last fitting one read (which of the two?)."""
    read = backref.last_fitting(noun.head, disc.references, start, disc.vocab.by_key)
    told = backref.last_fitting(noun.head, disc.mentions, start, disc.vocab.by_key)
    if told is None:
        return disc.references
    if read is not None and read.end < told.start:
        rf.refuse(rf.demonstrative_read_or_told(said, read.phrase, told.phrase))
    return disc.references if read is not None else disc.mentions


def owners_room(np: Described, noun: Noun, said: str, disc: Discourse) -> list[Entity]:
    """*her room*: the room an earlier *her room* named, else the one room a statement set aside says
    someone stays, sleeps or lives in (*My sister is staying in the bedroom with the two beds.*); refused
    otherwise (whose room?). *her bed*: the beds of that room (of the scene's, when no room is told). A
    room named as a goal, or as where someone just is (*Grandma is in the kitchen*), is not taken for it."""
    word, fits = said.split()[0].lower(), {e.key for e in noun.entities}
    same = [g for g in disc.references if g.end <= np.span.start and g.phrase.split()[0].lower() == word]
    told = [g for g in disc.mentions if g.end <= np.span.start and lives_there(disc.text, g.start, word)]
    if noun.head.kind == "object":  # "my sister stays in the bedroom with the plant ... her bed": its bed
        rooms = {e.key: e for g in (*same[-1:], *told) for e in g.entities if e.kind == "room"}
        inside = disc.vocab.inside(noun.entities, rooms.values()) if len(rooms) == 1 else []
        return inside or noun.entities  # else as "the": one, or refused as several
    for named in (same[-1:], told):
        rooms = {e.key: e for g in named for e in g.entities if e.kind == "room" and e.key in fits}
        if len(rooms) == 1:
            return list(rooms.values())
        if rooms:
            rf.refuse(rf.whose_room(said, sorted(rooms)))
    if np.apposition is not None:  # "his room, the one with the teddy bear": the apposition says which
        return noun.entities
    rf.refuse(rf.whose_room(said, []))


def said_in_order(between: str, text: str) -> bool:
    """Whether the words ``between`` two phrases of the mission ``text`` put the second after the first
    (*then*, *after that*, the next item of a numbered list when no order remark is made anywhere), so that
    the one named first is also the one done first (sentences alone are in no order)."""
    words = between.lower().replace(",", " , ").replace("->", " then ").replace("\u2192", " then ").split()
    numbered = re.search(r"\n\s*\(?\d+[.)]", between) is not None and "order" not in text.lower()
    return numbered or any(tuple(words[k:k + len(p)]) == p for p in lx.SEQ_WORDS for k in range(len(words)))


def lives_there(text: str, start: int, owner: str) -> bool:
    """Whether the words of the sentence before character ``start`` say that someone ``owner`` (*her*,
    *his*, *their*) can stand for stays, sleeps or lives there (*my sister is staying in ...*: her room, not
    his)."""
    sentence = text[:start].replace("!", ".").replace("?", ".").replace("\n", ".").rsplit(".", 1)[-1]
    words = set(sentence.lower().replace("'", " ").split())
    return bool(words & lx.RESIDING) and bool(words & lx.owners(owner))


def of_the_step_room(np: Described, noun: Noun, got: backref.Resolved, said: str, where: Where,
                     disc: Discourse) -> list[Entity] | None:
    """*go to the office and water that plant too*: the plant of the office, the room of the step, not the
    one named before (which is elsewhere); without *too* / *also* / *as well* either is meant, so it is
    refused. None when the step names no room, its room holds no such object, or the one pointed back to
    is in it."""
    rooms = (*where.scope, *where.soft_scope) if where.role == "goal" and noun.head.kind == "object" else ()
    here = disc.vocab.inside(noun.entities, rooms)
    if not here or disc.vocab.inside(got.entities, rooms) or np.determiner.pointer != "that":
        return None
    after = disc.said(np.span.end, len(disc.text)).lower().lstrip(" ,")
    if len(here) == 1 and after.startswith(lx.ALSO_AFTER):
        return here
    room = " or ".join(f"the {r.category} ({r.key})" for r in rooms)
    rf.refuse(rf.demonstrative_or_step_room(said, got.antecedent, room, ", ".join(e.key for e in here)))
    return None


def scoped(np: Described, noun: Noun, mode: Mode, said: str, where: Where, disc: Discourse) -> Noun:
    """An object phrase located by the context: the one in the rooms of a condition (*whenever you enter
    the bathroom, use the sink*), of the step (*go to the kitchen and open the fridge*), or, for a definite
    one that fits several, of the step just before (*go to the bedroom, then check the plant*)."""
    vocab, head, entities = disc.vocab, noun.head, noun.entities
    # "his chair" is located by the step as "the chair" is (its owner's room, when told, was taken already)
    demo = np.determiner.pointer is not None and not (np.determiner.pointer in lx.OWNERS
                                                      and head.kind == "object")
    there = vocab.inside(entities, where.soft_scope) if where.role == "goal" and head.kind == "object" \
        and not demo else []
    if not noun.room_scoped and mode == "the" and not head.plural and len(entities) > 1 and len(there) == 1:
        return Noun(head, there, True)
    near = near_step_before(np, noun, mode, where, disc) if np.apposition is None else []
    if len(entities) > len(near) > 0:
        # "go to the bedroom with the vase, then check the plant" (an apposition says which: "then the vase,
        # the one in the dining room")
        return Noun(head, near, True)
    before = vocab.inside(entities, where.previous) if where.role == "goal" and not demo else []
    after = disc.said(np.span.end, len(disc.text)).lstrip()
    # "any chair, either one": a remark; "any chair, then / and / after that back to ...": the next step
    words = after[1:].lower().replace(",", " ").split()
    remark_after = after[:1] in ("-", "\u2014", "(", ":") or (
        after[:1] == "," and words[:1] != ["and"]
        and not any(tuple(words[:len(p)]) == p for p in lx.SEQ_WORDS))
    listed = vocab.inside(entities, where.listed_after) if head.kind == "object" and not demo else []
    if not noun.room_scoped and 0 < len(listed) < len(entities) and np.determiner.count is None:
        # "In the lobby check the vases, in any order": the lobby's, or every vase? (A number says which:
        # "both vases" where the room has one.)
        rooms = " or ".join(f"{r.key} ({r.category})" for r in where.listed_after)
        rf.refuse(rf.listed_room_or_anywhere(said, rooms, where.listed_after[0].category))
    own_step = vocab.inside(entities, [*where.scope, *where.soft_scope])  # "2. dining room, any chair"
    if (mode == "any" and (head.plural or (np.first_word in ("a", "an", "any") and not remark_after
                                           and not own_step))
            and not noun.room_scoped and 0 < len(before) < len(entities)):
        # "check the vase in the living room, then one of the TVs / a TV": one of those there, or any?
        rooms = " or ".join(f"{r.key} ({r.category})" for r in where.previous)
        word = head_word(entities)
        rf.refuse(rf.step_room_or_anywhere(said, rooms, lx.plural(word), where.previous[0].category, word))
    if not noun.room_scoped and 0 < len(there) < len(entities) and np.first_word in ("the", "a", "an", "one"):
        rooms = " or ".join(f"{r.key} ({r.category})" for r in where.soft_scope)
        word = head_word(entities)
        rf.refuse(rf.there_or_anywhere(said, rooms, lx.plural(word) if head.plural else word,
                                       where.soft_scope[0].category, word))
    if where.role == "qualifier" or not where.scope or head.kind != "object" or noun.room_scoped or demo:
        return noun
    inside = vocab.inside(entities, where.scope)
    if inside:
        return Noun(head, inside, True)
    if where.role == "goal" and entities and not where.lenient:
        # "go to the lobby and sit on the couch" where the lobby has no couch: another room's couch is not
        # what was asked for.
        rooms = " or ".join(f"{r.key} ({r.category})" for r in where.scope)
        rf.refuse(rf.not_in_this_step(said, rooms, ", ".join(e.describe() for e in entities[:8]),
                                      head_word(entities)))
    return noun


def near_step_before(np: Described, noun: Noun, mode: Mode, where: Where, disc: Discourse) -> list[Entity]:
    """The objects ``noun`` can be in the room of the step just before (:attr:`.Where.previous`), for an
    object of a goal that no room, description or pointer places: the one there for a definite singular
    (*the wicker chair* does not say which, nor is it the one just reached: *the swivel chair in the office,
    then the wicker chair*), the two there for *either* (*bath w/ 2 sinks -> either sink*), those there (two
    or more) for a choice remark after it (*upstairs bath -> toilet (either)*), those there for a number
    that only they fit (*the dining table, then both chairs*); else empty."""
    if (where.role != "goal" or where.scope or noun.head.kind != "object" or noun.room_scoped
            or np.determiner.pointer is not None or np.descriptive):
        return []
    near = disc.vocab.inside(noun.entities, where.previous)
    count = np.determiner.count
    if noun.head.plural:
        return near if count is not None and len(noun.entities) > count == len(near) else []
    if mode == "any" and np.first_word == "either":
        return near if len(near) == 2 else []
    if np.remark_follows and len(near) >= 2:  # "upstairs bath -> toilet (either)": one of those there
        return near
    just_reached = {e.key for g in disc.goals_before(np.span.start)[-1:] for e in g.entities}
    return near if mode == "the" and len(near) == 1 and near[0].key not in just_reached else []


def inner(np: Any, disc: Discourse) -> Grounded:
    """A phrase inside a qualifier, grounded as a qualifier."""
    return ground_phrase(np, Where("qualifier"), disc)


@applies(Possessive)
def possessive(q: Possessive, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the teddy bear's room*: the rooms holding it; *the kitchen's sink*: the sinks in it."""
    of_head = disc.vocab.of_head(q.head)
    if noun.head.kind == "object":
        return Noun(q.head, disc.vocab.containing(of_head, noun.entities, None), noun.room_scoped)
    return Noun(q.head, disc.vocab.inside(of_head, noun.entities), True)


@applies(OnFloor)
def on_floor(q: OnFloor, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*on floor 1*, *upstairs*, *up there*, *on the same floor (as X)*."""
    last = disc.last_goal()
    if isinstance(q.floor, SameFloor) and q.floor.as_phrase is not None:
        reading = FloorReading(same_floor(inner(q.floor.as_phrase, disc), disc))
    elif (isinstance(q.floor, UpThere) and where.action_floor is not None
          and (last is None or last.start < where.action_floor[1])):
        reading = where.action_floor[0]  # "While you're upstairs, check the bathroom up there": that floor
    else:
        reading = floors_of(q.floor, disc, noun.entities)
    return Noun(noun.head, on_floors(noun.entities, reading, disc), noun.room_scoped,
                reading.said if reading.unknown else None)


@applies(There)
def there(q: There, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*a bathroom there*: on the floor named last; *grab a bottle there*: in the room of the place named
    last."""
    if noun.head.kind == "room":
        floors = there_floors(np.span.start, noun.head, disc, where.action_floor)
        return Noun(noun.head, on_floors(noun.entities, FloorReading(floors), disc), noun.room_scoped)
    # "don't go in the living room until ... the TV in there": the one place kept out of holding one
    rooms = there_rooms_holding(np.span.start, noun.entities, there_rooms(np.span.start, disc), disc)
    return Noun(noun.head, disc.vocab.inside(noun.entities, rooms), True)


@applies(InRoom)
def in_room(q: InRoom, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the sink in the kitchen*: the objects in that room (the room phrase keeps only the rooms used); *every
    plant in the office and the kitchen*: those of each room, each of which must hold some."""
    # (a floor move's floors go on to the room: "While you're upstairs, the bottle in the bathroom up there")
    rooms = [owners_room_holding(room, noun, disc)
             or ground_phrase(room, Where("qualifier", action_floor=where.action_floor, rooms=True), disc)
             for room in q.rooms]
    said = disc.said(q.span.start, q.span.end)
    anchor = rooms[0] if len(rooms) == 1 else None
    if noun.head.kind == "object" and anchor and anchor.entities and all(e.kind == "object"
                                                                        for e in anchor.entities):
        return by_an_object(said, noun, anchor, where, disc)  # "the bowl in the sink", "the book from it"
    if noun.head.kind != "object" or any(e.kind != "room" for g in rooms for e in g.entities):
        rf.refuse(rf.object_in_room(said))
    if len(q.rooms) == 1 and isinstance(q.rooms[0], ThereNP):
        # "don't go in the living room until ...; look at the TV in there": the one place named holding one
        rooms[0].entities = there_rooms_holding(q.span.start, noun.entities, rooms[0].entities, disc)
    entities = disc.vocab.inside(noun.entities, [e for g in rooms for e in g.entities])
    if q.choice and len(rooms) == 1 and len(rooms[0].entities) != 2:  # "in either bathroom": one of two
        rf.refuse(rf.either_of_more(f"either {rooms[0].phrase}", [e.describe() for e in rooms[0].entities]))
    for room in rooms:
        room.entities = [r for r in room.entities if any(e.room_key == r.key for e in entities)]
        if len(rooms) > 1 and not room.entities:  # not "... in A, and B": that would be another goal
            rf.refuse(rf.room_holds_none(said, room.phrase, head_word(noun.entities)))
    return Noun(noun.head, entities, True)


def owners_room_holding(room: NounPhrase, noun: Noun, disc: Discourse) -> Grounded | None:
    """*the teddy bear in her bedroom* where nothing said before tells whose room it is: the one room of that
    kind that holds such an object (the speaker places it there); ``None`` when the phrase is no owner's room,
    or what was said before decides it (:func:`owners_room`). Refused when the objects lie in several such
    rooms, or in none."""
    if (not isinstance(room, Described) or room.determiner.pointer not in lx.OWNERS
            or noun.head.kind != "object"):
        return None
    try:
        ground_phrase(room, Where("qualifier", rooms=True), disc.fork())
        return None
    except MissionError as told:
        anyone = replace(room, determiner=replace(room.determiner, pointer=None, mode="any"))
        got = ground_phrase(anyone, Where("qualifier", rooms=True), disc.fork())
        holding = disc.vocab.containing(got.entities, noun.entities, None)
        if len(holding) != 1:
            raise told
    got = ground_phrase(anyone, Where("qualifier", rooms=True), disc)
    got.entities, got.mode = holding, "the"
    return got


@applies(Holds)
def holds(q: Holds, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the room where the book is*: the rooms holding it (and each of the others said with it)."""
    entities = noun.entities
    for said in (q.thing, *q.also):
        thing = inner(said, disc)
        if any(e.kind != "object" for e in thing.entities):
            rf.refuse(rf.room_by_contents(thing.phrase))
        entities = disc.vocab.containing(entities, thing.entities, None)
        thing.entities = [o for o in thing.entities if any(o.room_key == r.key for r in entities)]
    return Noun(noun.head, entities, noun.room_scoped)


@applies(Lacks)
def lacks(q: Lacks, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the bedroom that doesn't have a book*: the rooms holding none."""
    thing = inner(q.thing, disc)
    if noun.head.kind != "room" or any(e.kind != "object" for e in thing.entities):
        rf.refuse(rf.room_without(disc.said(q.span.start, q.span.end)))
    return Noun(noun.head, disc.vocab.lacking(noun.entities, thing.entities), noun.room_scoped)


@applies(Contains)
def contains(q: Contains, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the bedroom with (only) (two) beds*: the rooms holding it (that many; nothing else)."""
    thing = inner(q.thing, disc)
    if noun.head.kind != "room" or any(e.kind != "object" for e in thing.entities):
        rf.refuse(rf.room_with(disc.said(q.span.start, q.span.end)))
    count = q.count if q.count is not None else thing.count
    entities = disc.vocab.containing(noun.entities, thing.entities, count, only=q.only)
    thing.entities = [o for o in thing.entities if any(o.room_key == r.key for r in entities)]
    return Noun(noun.head, entities, noun.room_scoped)


@applies(Attachment)
def attachment(q: Attachment, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the bedroom without a plant* / *the bedroom with the book and the vase*, read as descriptions."""
    thing = inner(q.thing, disc)
    if q.kind == "without":
        return Noun(noun.head, disc.vocab.lacking(noun.entities, thing.entities), noun.room_scoped)
    return Noun(noun.head, disc.vocab.containing(noun.entities, thing.entities, None), noun.room_scoped)


@applies(NextTo)
def next_to(q: NextTo, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the kitchen next to the dining room* (connected in the scene graph); an object next to a room is
    in a room connected to it."""
    vocab = disc.vocab
    if q.it_span is not None and q.relation in lx.OBJECT_PLACING:  # "wipe a table, then the bowl on it"
        return by_an_object(disc.said(q.span.start, q.span.end), noun, placed_on_it(q, disc), where, disc)
    said = q.relation if q.relation.endswith("next door") else f"{q.relation} it"
    # a room is next to rooms only: "the bathroom next to it" after an object is next to the object's room
    by_room = q.relation.endswith("next door") or noun.head.kind == "room"
    room = next_to_it(q.it_span, said, disc, by_room) if q.it_span is not None else inner(q.thing, disc)
    if noun.head.kind == "object" and room.entities and all(e.kind == "object" for e in room.entities):
        return by_an_object(disc.said(q.span.start, q.span.end), noun, room, where, disc)
    if any(e.kind != "room" for e in room.entities):
        rf.refuse(rf.next_to_rooms_only(disc.said(q.span.start, q.span.end)))
    if noun.head.kind == "object":  # "the toilet next to the bedroom": in a room next to it
        rooms = vocab.next_to([vocab.by_key[k] for k in dict.fromkeys(e.room_key for e in noun.entities)],
                              room.entities)
        room.entities = [r for r in room.entities
                         if any(r.key in vocab.adjacent.get(x.key, ()) for x in rooms)]
        return Noun(noun.head, vocab.inside(noun.entities, rooms), noun.room_scoped)
    entities = vocab.next_to(noun.entities, room.entities)
    room.entities = [r for r in room.entities
                     if any(r.key in vocab.adjacent.get(e.key, ()) for e in entities)]
    return Noun(noun.head, entities, noun.room_scoped)


@applies(Between)
def between(q: Between, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the bathroom between the bedrooms*: the rooms connected to each of the two or more rooms named (to
    each of a group, *the bedrooms*; to one of a phrase naming one, *the bathroom*)."""
    named = [inner(thing, disc) for thing in q.things]
    rooms = [e for g in named for e in g.entities]
    said_rooms = sum(len(g.entities) if g.mode == "all" else 1 for g in named)
    if said_rooms < 2 or any(e.kind != "room" for e in rooms):
        rf.refuse(rf.between_rooms_only(disc.said(q.span.start, q.span.end)))
    adjacent = disc.vocab.adjacent

    def connects(room: Entity) -> bool:
        near = adjacent.get(room.key, frozenset())
        return all((all if g.mode == "all" else any)(e.key in near for e in g.entities) for g in named)
    return Noun(noun.head, [e for e in noun.entities if connects(e)], noun.room_scoped)


def placed_on_it(q: NextTo, disc: Discourse) -> Grounded:
    """*the bowl on it*: *it* is the object named last (:func:`.phrases.antecedent`), which must be an object;
    a choice of them (*one of the tables*) only when they all lie in one room."""
    assert q.it_span is not None
    said = f"{q.relation} it"
    ref = antecedent("it", disc)
    if any(e.kind != "object" for e in ref.entities):
        rf.refuse(rf.placed_on_a_room(said, ref.phrase))
    determined(said, ref, len({e.room_key for e in ref.entities}))
    return disc.record(Grounded("it", q.it_span.start, q.it_span.end, list(ref.entities), ref.mode, False,
                                "qualifier"))


@applies(ByUnlisted)
def by_unlisted(q: ByUnlisted, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*the bowl on the counter*: the scene holds no counter, so the words are said back as set aside; which
    bowl is meant is decided as for descriptive words (:func:`ground_described`)."""
    disc.put_aside(disc.said(q.span.start, q.span.end))
    return noun


@applies(ShortStay)
def short_stay(q: ShortStay, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*sit on the couch for a bit*: a goal is reached, how long the robot stays is not planned; the words are
    said back as set aside. After a place to avoid or a condition (*stay off the couch for a bit*: only for a
    while?) refused."""
    said = disc.said(q.span.start, q.span.end)
    if where.role != "goal":
        rf.refuse(rf.short_stay_not_a_goal(said, disc.said(np.span.start, q.span.start).rstrip()))
    disc.put_aside(said)
    return noun


def by_an_object(said: str, noun: Noun, anchor: Grounded, where: Where, disc: Discourse) -> Noun:
    """*the vase off the dining table*, *the plant by the couch*, *the bowl in the sink* (``said``): the
    scene knows rooms, not what stands by what, so an object placed by another is one in the anchor's room;
    that is certain only when the anchor lies in one room, or in one room of the step (*go to the bedroom
    with the teddy bear and check the clock by the bed*); else refused: which room?"""
    rooms = list(dict.fromkeys(e.room_key for e in anchor.entities))
    here = [k for k in rooms if k in {r.key for r in where.scope}]
    if len(rooms) > 1 and len(here) == 1:
        rooms, anchor.entities = here, [e for e in anchor.entities if e.room_key == here[0]]
    if len(rooms) > 1:
        rf.refuse(rf.anchor_in_several_rooms(said, anchor.phrase, [disc.vocab.by_key[k] for k in rooms]))
    keys = {e.key for e in anchor.entities}
    return Noun(noun.head, [e for e in disc.vocab.inside(noun.entities, [disc.vocab.by_key[rooms[0]]])
                            if e.key not in keys], noun.room_scoped)


@applies(Except)
def except_for(q: Except, noun: Noun, np: Described, where: Where, disc: Discourse) -> Noun:
    """*all the corridors except the one on floor 0*: all but those (each must be one of them)."""
    excluded = [inner(thing, disc) for thing in q.things]
    keys = {e.key for g in excluded for e in g.entities}
    have = {e.key for e in noun.entities}
    stray = [g.phrase for g in excluded if not {e.key for e in g.entities} & have]
    if stray:  # "the dining room but not the kitchen": not an exception, and not understood
        rf.refuse(rf.not_an_exception(q.said, stray[0], q.restricted))
    return Noun(noun.head, [e for e in noun.entities if e.key not in keys], noun.room_scoped)

