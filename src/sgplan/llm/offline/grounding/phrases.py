"""Grounding a noun phrase: the rooms or objects of the scene it denotes, given what was said before it.

:func:`ground_phrase` takes a phrase of the syntax tree, the context it is read in (:class:`.Where`) and the
discourse so far (:class:`.Discourse`), records the grounded phrase there (back-references may point to
it) and returns it. A definite phrase must denote exactly one entity, a phrase must denote at least one;
otherwise it is refused, listing the candidates and saying how to single one out.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from sgplan.errors import MissionError
from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding import backref
from sgplan.llm.offline.grounding.discourse import Discourse, Grounded, Where
from sgplan.llm.offline.grounding.everyday import kids_room
from sgplan.llm.offline.grounding.floors import determined, floors_of, on_floors, one_floor
from sgplan.llm.offline.grounding.hints import hint
from sgplan.llm.offline.grounding.places import there_rooms
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.registry import Registry
from sgplan.llm.offline.syntax.tree import (
    Described,
    FloorPlace,
    GroupRepeat,
    HandledAt,
    InRoom,
    Its,
    KeyHead,
    Mode,
    NounPhrase,
    OneHead,
    PhraseList,
    Pronoun,
    SameRoom,
    ThereNP,
)


@dataclass
class Noun:
    """A described phrase while its qualifiers are applied: its current head, entities, and whether its
    objects are located through a room."""

    head: Head
    entities: list[Entity]
    room_scoped: bool
    guessed: str | None = None
    """Floor words counted from a start floor that is not known, read because the entities they could
    name lie on one floor (checked once the qualifiers are applied, :func:`.described.ground_described`)."""


def ground_list(phrases: PhraseList, where: Where, disc: Discourse) -> list[Grounded]:
    """The phrases of a list, each grounded (the verb's floor and the pronoun's kind apply to the first); a
    choice (*or*, *either*) is one phrase of all the alternatives, mode ``any``."""
    out: list[Grounded] = []
    choice = "or" in phrases.joiners or phrases.either
    for k, item in enumerate(phrases.items):
        here = where if k == 0 else replace(where, floor=None, objects=False)
        rooms = [e for g in out for e in g.entities if e.kind == "room"]
        if rooms and not choice and where.role == "goal" and not here.scope:
            # "the dining room, any vase": an object after a room of the list is looked for there first
            here = replace(here, scope=tuple(dict.fromkeys(rooms)), lenient=True)
        shared = [] if choice or where.role != "goal" or here.scope else shared_room(phrases, k, disc)
        if shared:  # "the sink and the toilet in the bathroom": the sink is looked for there first
            here = replace(here, scope=tuple(shared), lenient=True)
        out.append(ground_phrase(item, here, disc))
    if "nor" in phrases.joiners or not choice:
        return out
    said = disc.said(phrases.span.start, phrases.span.end)
    if any(g.mode == "all" and len(g.entities) > 1 for g in out):
        rf.refuse(rf.group_in_a_choice(said))
    # Being at an object implies being in its room, so locating some alternatives by their room and others
    # not changes nothing: the merged phrase locates all of them.
    for g in out:
        g.alternative = True
    return [Grounded(said, phrases.span.start, phrases.span.end, [e for g in out for e in g.entities], "any",
                     any(g.room_scoped for g in out), where.role)]


def shared_room(phrases: PhraseList, k: int, disc: Discourse) -> list[Entity]:
    """The room that the last item of an *and* list is located in (*the sink and the toilet in the
    ground-floor bathroom*), for item ``k`` before it that has no room of its own: the words may locate both,
    so it is looked for there first (and elsewhere when the room holds none: *the fridge and the toilet in
    the bathroom*); ``[]`` when there is none, or the item is plural (*the clocks and the bed in the
    bedroom*: every clock, or those of the bedroom? Each clock, as before)."""
    last, item = phrases.items[-1], phrases.items[k]
    if (phrases.joiners != {"and"} or k == len(phrases.items) - 1 or not isinstance(item, Described)
            or not isinstance(last, Described) or not isinstance(item.head, Head) or item.head.plural):
        return []  # not "the clocks, the one in the bedroom first"
    if any(isinstance(q, InRoom) for q in item.qualifiers) or item.compound is not None:
        return []
    located = [q for q in last.qualifiers if isinstance(q, InRoom) and len(q.rooms) == 1 and not q.choice]
    if len(located) != 1:
        return []
    try:
        room = ground_phrase(located[0].rooms[0], Where("qualifier"), disc.fork())
    except MissionError:
        return []  # refused where the last item is grounded, with its reason
    return [e for e in room.entities if e.kind == "room"]


GROUNDERS: Registry[Callable[[Any, Where, Discourse], Grounded]] = Registry("grounding")
"""How each kind of phrase of the syntax tree is grounded."""
grounds = GROUNDERS.register


def ground_phrase(np: NounPhrase, where: Where, disc: Discourse) -> Grounded:
    """Ground one phrase (see the module docstring)."""
    grounded: Grounded = GROUNDERS(np, where, disc)
    return grounded


@grounds(Pronoun)
def pronoun(np: Pronoun, where: Where, disc: Discourse) -> Grounded:
    """*it* / *them* / *they*: the phrase named last that agrees in number (objects only after *put*);
    *that* (*check that first, then ...*) only when one thing was named before it."""
    if np.word == "that":
        named = [g.phrase for g in (*disc.references, *disc.mentions) if g.start < np.span.start
                 and g.role != "qualifier" and g.phrase.lower() not in lx.PRONOUNS]
        if len(named) > 1:
            rf.refuse(rf.that_of_several(named))
    ref = antecedent(np.word, disc, "object" if where.objects else "room" if where.rooms else None)
    if ref in disc.mentions and ref.mode == "the" and len(ref.entities) > 1:  # "The sink is dripping. ..."
        rf.refuse(rf.one_of_several_set_aside(np.word, ref.phrase, [e.key for e in ref.entities]))
    mode: Mode = "all" if np.word in lx.PLURAL_PRONOUNS else ref.mode
    g = Grounded(disc.said(np.span.start, np.span.end), np.span.start, np.span.end, list(ref.entities), mode,
                 ref.room_scoped, where.role)
    g.choice_of = backref.choice_refusal(np.word, ref, len(ref.entities))
    if g.choice_of is not None and where.role != "goal":  # only a carried goal may leave it open
        rf.refuse(g.choice_of)
    if where.role == "avoid" and ref.role == "goal":  # "the kitchen you mustn't enter it"
        rf.refuse(rf.avoided_goal(np.word, ref.phrase))
    g.mentioned = ref in disc.mentions
    return disc.record(g)


@grounds(ThereNP)
def there_place(np: ThereNP, where: Where, disc: Discourse) -> Grounded:
    """*there* as a place: the last place named as a goal (its rooms, inside a qualifier)."""
    goals = [g for g in disc.references if g.role == "goal" and g.phrase.lower() not in lx.PRONOUNS]
    mentioned = [g for g in disc.mentions if g.start < np.span.start and len({e.room_key for e in g.entities})
                 == 1]  # not "the bedroom" among two
    if mentioned and (not goals or max(g.start for g in goals) < mentioned[-1].start):
        if goals:  # "Go to the kitchen. The dog sleeps in the office. Go there.": which of the two?
            last = max(goals, key=lambda g: g.start)
            rf.refuse(rf.there_goal_or_mention(last.phrase, mentioned[-1].phrase))
        goals = mentioned[-1:]  # "Grandpa's napping in the bedroom, so stay out of there"
        rooms = {e.room_key for e in mentioned[-1].entities}
        things = [g for g in disc.mentions if g.start < np.span.start and g.entities
                  and all(e.kind == "object" for e in g.entities)
                  and any(e.room_key in rooms for e in g.entities)]
        if where.role == "goal" and things:  # "the teddy's probably in the lounge, look there": the room?
            rf.refuse(rf.there_place_or_thing(mentioned[-1].phrase, things[-1].phrase))
    if not goals:
        rf.refuse(rf.there_refers_to_nothing())
    ref = max(goals, key=lambda g: g.start)
    if ref in disc.done_before:  # "go to the dining room only after the oven. Once there, ...": which?
        rf.refuse(rf.there_done_before(ref.phrase))
    kept_out = [g for g in disc.references if g.role == "avoid" and ref.start < g.start < np.span.start]
    if where.role == "avoid" and kept_out:  # "look at the vase. Skip the kitchen, don't go in there": which?
        rf.refuse(rf.there_goal_or_kept_out(ref.phrase, kept_out[-1].phrase))
    if where.role == "goal" and (until := kept_out_until(ref, disc)) is not None:
        # "keep out of the bedroom until you've checked the toilet. Then go there": which?
        rf.refuse(rf.there_goal_or_kept_out_until(f"'{ref.phrase}'", f"'{until.phrase}'"))
    determined("there", ref, len({e.room_key for e in ref.entities}))
    if where.role == "goal" and where.going_back:  # "A, then B, then go back there": B is where it is
        rf.refuse(rf.back_there(ref.phrase))
    # "both bedrooms, then back there": which one? (but "wipe both sinks in the bathroom, and stay out of the
    # bedroom while you're up there" is where they all are)
    one_room = where.role == "goal" and len({e.room_key for e in ref.entities}) == 1
    if where.role != "qualifier" and ref.mode == "all" and len(ref.entities) > 1 and not one_room:
        rf.refuse(rf.there_is_several(ref.phrase))
    entities = list(ref.entities)
    before = disc.text[:np.span.start].split()
    inside = bool(before) and before[-1].lower() in ("in", "into", "inside")
    if where.role == "qualifier" or inside:  # "the clock in there", "go in there": the room of the last goal
        entities = list({e.room_key: disc.vocab.by_key[e.room_key] for e in entities}.values())
    scoped = ref.room_scoped and not (inside and where.role != "qualifier")  # rooms now, not objects
    return disc.record(Grounded("there", np.span.start, np.span.end, entities, ref.mode, scoped, where.role))


def kept_out_until(goal: Grounded, disc: Discourse) -> Grounded | None:
    """The room kept out of until ``goal`` (*don't go into the bedroom until you've checked the toilet*: the
    bedroom, kept out of until the goals of the clause after it), or ``None`` (*... until you've checked the
    microwave, then turn off the telly in there*: the telly lifts nothing)."""
    kept = [g for g in disc.references if g.role == "avoid" and g.start < goal.start
            and any(e.key in disc.kept_until for e in g.entities)]
    if not kept:
        return None
    between = disc.text[kept[-1].end:goal.start]  # "... until you've checked the toilet and the laptop, ..."
    in_clause = not any(mark in between for mark in ".!?;") and " then " not in f" {between.lower()} "
    others = any(g.role == "goal" and kept[-1].start < g.start < goal.start for g in disc.references)
    return kept[-1] if in_clause or not others else None


@grounds(GroupRepeat)
def group_repeat(np: GroupRepeat, where: Where, disc: Discourse) -> Grounded:
    """*all of them* / *both of them* / *all three of them*: the group named before (its size checked);
    *one of them*: any one of a group named in words set aside (*The TVs keep flickering. Check one of
    them.*); after a group of goals it is refused (one only, or all of them and one again?)."""
    ref = antecedent("them", disc)
    said = disc.said(np.span.start, np.span.end)
    if np.choice and ref not in disc.mentions:  # "the TVs in the office - just look at one of them"
        rf.refuse(rf.one_of_goals(said, ref.phrase))
    if np.count is not None and len(ref.entities) != np.count:
        rf.refuse(rf.group_size(said, ref.phrase, len(ref.entities), np.count))
    return disc.record(Grounded(said, np.span.start, np.span.end, list(ref.entities),
                                "any" if np.choice else "all", ref.room_scoped, "goal"))


@grounds(SameRoom)
def same_room(np: SameRoom, where: Where, disc: Discourse) -> Grounded:
    """*the sink in the same room*: the room of the place named last."""
    rooms = there_rooms(np.span.start, disc, f"the same {np.word}")
    if len(rooms) != 1:
        rf.refuse(rf.same_room_unclear(np.word, [r.key for r in rooms]))
    said = disc.said(np.span.start, np.span.end)
    return disc.record(Grounded(said, np.span.start, np.span.end, rooms, "the", False, where.role))


@grounds(Its)
def its(np: Its, where: Where, disc: Discourse) -> Grounded:
    """*its sink*, *one of its chairs*: the sinks / chairs in the room just named (or in the room of the
    object named); *its bathroom*: the bathroom attached to the room (of the object); *its room* after an
    object: the room holding it."""
    ref = antecedent("it", disc)
    # "the bathroom next to the bedroom with the chair ... its toilet": of the phrases nested there, the one
    # whose room has a toilet (the chair's has none); refused when several have one
    chain = [ref, *(o for o in disc.references if o is not ref and o.start <= ref.start and ref.end <= o.end)]
    readings = {tuple(e.key for e in got): got for g in chain if (got := owned_by(np, g, disc))}
    owned = next(iter(readings.values())) if len(readings) == 1 else owned_by(np, ref, disc)
    if len(readings) > 1:
        rf.refuse(rf.its_of_which(disc.said(np.span.start, np.span.end), [g.phrase for g in chain]))
    mode: Mode = np.mode or ("all" if np.head.plural else "the")
    g = Grounded(disc.said(np.span.start, np.span.end), np.span.start, np.span.end, owned, mode,
                 np.head.kind == "object", where.role)
    check(g, np.head, None, False, disc)
    return disc.record(g)


@grounds(HandledAt)
def handled_at(np: HandledAt, where: Where, disc: Discourse) -> Grounded:
    """*rinse the watering can at the kitchen sink*: the object where the thing is handled; the thing, which
    the scene does not hold, is said back as set aside."""
    disc.put_aside(disc.said(np.thing.start, np.thing.end))
    return ground_phrase(np.at, where, disc)


@grounds(FloorPlace)
def floor_place(np: FloorPlace, where: Where, disc: Discourse) -> Grounded:
    """*the top floor* as a place: any of its rooms as a goal or condition, all of them to avoid."""
    reading = floors_of(np.floor, disc)
    rooms = on_floors(disc.vocab.of_head(Head("room", frozenset(), True, 1)), reading, disc)
    one_floor(rooms, reading.said if reading.unknown else None, disc)
    chosen: Mode = "all" if where.role == "avoid" or np.mode == "all" else "any"
    said = disc.said(np.span.start, np.span.end)
    return disc.record(Grounded(said, np.span.start, np.span.end, rooms, chosen, False, where.role,
                                floor=True))


def antecedent(pronoun: str, disc: Discourse, kind: str | None = None) -> Grounded:
    """The phrase a pronoun refers to: the last one mentioned (by position) that agrees in number.

    ``it`` takes a phrase denoting one entity, ``them``/``they`` one denoting several, so in "go to the
    bedroom with the TV and turn it on" *it* is the TV, and in "take both bowls in the kitchen and put
    them in the fridge" *them* are the bowls. An object named inside an object phrase to locate it is
    not the antecedent: in "get the book from the bedroom with the vase, then bring it ..." *it* is the
    book.
    """
    plural = pronoun in lx.PLURAL_PRONOUNS

    def agreeing(named: list[Grounded]) -> list[Grounded]:
        return [g for g in sorted(named, key=lambda g: g.start, reverse=True)
                if (g.mode == "all" and len(g.entities) > 1) == plural and g.phrase.lower() not in lx.PRONOUNS
                and (kind is None or all(e.kind == kind for e in g.entities))]
    # what was read first; else what was set aside ("The vase in the hall is dusty. Dust it.")
    read = agreeing(disc.references)
    later = [m for m in agreeing(disc.mentions) if read and m.start > read[0].end]
    if later:  # "Head up to the office. I left my laptop there. Check it.": the office, or the laptop?
        rf.refuse(rf.antecedent_goal_or_mention(pronoun, read[0].phrase, later[0].phrase))
    fits = read or agreeing(disc.mentions)
    if not fits:
        rf.refuse(rf.no_antecedent(pronoun, plural))
    if not read:  # only what was set aside: it must name one thing
        outermost = {tuple(e.key for e in g.entities) for g in fits
                     if not any(o is not g and o.start <= g.start and g.end <= o.end for o in fits)}
        if len(outermost) > 1:  # "The teddy bear keeps falling off the couch, check on it": which?
            rf.refuse(rf.antecedent_of_several(pronoun, [g.phrase for g in reversed(fits)]))
    g = fits[0]
    kept_out = [o for o in fits[1:] if o.start <= g.start and g.end <= o.end and o.role == "avoid"]
    others = [f for f in fits[1:] if not any(o.start <= f.start and f.end <= o.end for o in kept_out)
              and not any(o is not f and o.start <= f.start and f.end <= o.end for o in fits)]
    if kept_out and others:  # "get the laptop, but don't go into the bedroom with the teddy bear until you've
        rf.refuse(rf.antecedent_or_kept_out(pronoun, others[0].phrase, g.phrase))  # got it": which?
    goal_before = [f for f in fits[1:] if f.role == "goal" and f.end <= g.start
                   and all(e.kind == "object" for e in f.entities)]
    if g.role == "qualifier" and goal_before and not plural:  # "bring the teddy, go to the bedroom with the
        rf.refuse(rf.antecedent_qualifier_or_goal(pronoun, g.phrase, goal_before[0].phrase))  # TV, tuck it"
    # "the book from the bedroom with the vase ... it": the object the phrase is about (its head), not an
    # object named inside it to locate it
    outer = [o for o in fits[1:] if o.start <= g.start and g.end <= o.end and all(e.kind == "object"
                                                                                 for e in o.entities)]
    return min(outer, key=lambda o: o.start) if outer else g


def owned_by(np: Its, ref: Grounded, disc: Discourse) -> list[Entity]:
    """What *its <head>* names when *it* is ``ref``: the heads in its room (the room of the object), the room
    attached to it, or (*its room* after an object) the room holding it."""
    container = [disc.vocab.by_key[k] for k in dict.fromkeys(e.room_key for e in ref.entities)]
    determined("its", ref, len(container))
    of_head = disc.vocab.of_head(np.head)
    holding = [room for room in container if room in of_head]
    if np.head.kind == "room" and holding and all(e.kind == "object" for e in ref.entities):
        return holding  # "the teddy bear ... its room": the room holding it (not "its bathroom")
    if np.head.kind == "room":
        return disc.vocab.next_to(of_head, container)
    return disc.vocab.inside(of_head, container)


def last_head(disc: Discourse, rooms: bool = False) -> Head | None:
    """The kind and category of the last room or object named (what *the one* / *the other one* is), in
    words read or set aside (*The plants are looking sad. Water the one in the office*); with ``rooms``, of
    the last room named, in a qualifier too (*the sink in the downstairs bathroom, then the sink in the
    upstairs one*)."""
    named = [g for g in disc.references if g.role != "qualifier" or rooms] + disc.mentions
    if rooms:
        named = [g for g in named if g.entities and all(e.kind == "room" for e in g.entities)]
    for g in sorted(named, key=lambda g: g.start, reverse=True):
        categories = {e.category for e in g.entities}
        if g.generic:  # "the room where the book is, then the one ..."
            return Head("room", frozenset(), False, 1)
        if g.entities and len(categories) == 1:
            return Head(g.entities[0].kind, frozenset(categories), False, 1)
    return None


def head_entities(np: Described, disc: Discourse, rooms: bool = False) -> Noun:
    """The head noun of ``np`` and every entity it may denote (*dining* chairs: those in a dining room);
    ``rooms``: it must name rooms (*the one* is then of the last room named)."""
    vocab = disc.vocab
    if isinstance(np.head, KeyHead):
        entity = vocab.by_key.get(np.head.key)
        if entity is None:
            rf.refuse(rf.unknown_key(np.head.key))
        return Noun(Head(entity.kind, frozenset({entity.category}), False, 1), [entity], False)
    head = resolved_head(np.head, disc, rooms)
    if head.everyday is not None:
        return Noun(head, [kids_room(vocab, head.everyday)], False)
    entities = vocab.of_head(head)
    if np.modifier is not None:  # "the dining chairs": the chairs in the dining room
        entities = vocab.inside(entities, vocab.rooms_named_by(np.modifier))
    return Noun(head, entities, np.modifier is not None)


def resolved_head(ref: Head | OneHead, disc: Discourse, rooms: bool = False) -> Head:
    """The head noun, *one* / *ones* read as the kind it stands for (refused when nothing says which)."""
    if isinstance(ref, Head):
        return ref
    given = ref.given if ref.given is not None else (last_head(disc, rooms) or disc.announced) \
        if ref.from_context else None
    if given is None:
        rf.refuse(rf.one_without_kind("ones" if ref.plural else "one"))
    return Head(given.kind, given.categories, ref.plural, 1)


def check(g: Grounded, head: Head, count: int | None, remark_follows: bool, disc: Discourse,
          either: bool = False) -> None:
    """Refuse a phrase that matches nothing, not the number it said, or several where it means one (a
    choice remark after it, *any one will do*, makes it a choice; *the stairs* to avoid on a mission that
    stays on some floors is each of them); ``either``: the remark after it says one of two (*a TV, either
    one*), so it may not match more."""
    if g.role == "qualifier":
        if not g.entities:
            rf.refuse(rf.qualifier_matches_nothing(g.phrase, head.kind, existing(head, disc)))
        return
    if not g.entities:
        kept = rf.not_on_kept_floors(sorted(disc.confined)) if disc.confined is not None and g.role in (
            "goal", "condition") else ""
        rf.refuse(rf.matches_nothing(g.phrase, head.kind, kept, existing(head, disc)))
    if g.role == "avoid" and g.phrase.lower().split()[:1] == ["either"]:
        # "don't go into either bathroom": the two of them (3 in the building: which two?), on kept floors
        staying = [e for e in g.entities if disc.confined is None or e.floor in disc.confined]
        if len(staying) != 2:
            rf.refuse(rf.wrong_count(g.phrase, 2, head.kind, len(staying),
                                     ", ".join(e.describe() for e in staying)))
    if either and g.role == "goal" and len(g.entities) > 2:  # "check a TV, either one" with 3: which two?
        rf.refuse(rf.wrong_count(f"{g.phrase}, either", 2, head.kind, len(g.entities),
                                 ", ".join(e.describe() for e in g.entities)))
    if count is not None and len(g.entities) != count:
        rf.refuse(rf.wrong_count(g.phrase, count, head.kind, len(g.entities),
                                 ", ".join(e.describe() for e in g.entities)))
    if g.mode == "the" and len(g.entities) > 1 and head.kind == g.entities[0].kind and not head.plural \
            and remark_follows:
        g.mode = "any"  # "the toilet on this floor, any one will do": one of them
    if g.mode == "the" and len(g.entities) > 1 and one_room_of_a_kind(g.entities):
        # "sit at the dining table" where the dining room holds four: any of them serves (to avoid, each)
        g.mode = "all" if g.role == "avoid" else "any"
    if (g.mode == "the" and g.role == "avoid" and g.phrase.lower().split()[-1] in lx.PLURAL_LOOKING
            and disc.confined is not None):
        # "stay on the top floor and keep off the stairs": the staircases of the other floors (grounded so:
        # described.py), forbidden anyway, every one of them. Without a confinement, all of them or those
        # of the floors the mission uses differ: asked below.
        g.mode = "all"
    if g.mode == "the" and len(g.entities) > 1:
        listing = ", ".join(f"{e.key} (floor {e.floor})" if e.kind == "room"
                            else f"{e.key} (in {e.room_key}, floor {e.floor})" for e in g.entities)
        said = hint(g.entities, disc.vocab)
        raise MissionError(rf.ambiguous(g.phrase, len(g.entities), head.kind, listing, said))


def one_room_of_a_kind(entities: list[Entity]) -> bool:
    """Whether ``entities`` are objects of one category in one room (the parts of one dining table, the
    vases of a lobby): where a phrase names one of them, the words cannot tell which, and any serves."""
    kinds = {(e.room_key, e.category) for e in entities}
    return all(e.kind == "object" for e in entities) and len(kinds) == 1


def existing(head: Head, disc: Discourse) -> str:
    """`` (this scene has: ...)`` listing what the head may denote, for a refusal."""
    found = disc.vocab.of_head(head)
    if not found:
        return ""
    listing = ", ".join(e.describe() for e in found[:8]) + (", ..." if len(found) > 8 else "")
    return f" (this scene has: {listing})"
