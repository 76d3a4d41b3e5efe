"""Which floors the floor words of a phrase name, in this building and for this robot.

Floors are numbered from 0 = the lowest. *upstairs* / *downstairs* and the floors counted from the start
(*the floor above*) need the start floor (or, for *upstairs* / *downstairs*, a two-floor building); without
it they are read only where they cannot change which entity is meant (the phrase's entities on the floors
the words could name lie on one floor: *the TV upstairs in the bedroom* where the bedrooms' TV is one); said
after a goal on another floor they could be counted from there too, so both readings are kept
(:class:`.discourse.FloorReading`) and must agree (:func:`on_floors`). Floors the building does not have
are refused.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding import backref
from sgplan.llm.offline.grounding.discourse import Discourse, FloorReading, Grounded
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.syntax.tree import (
    FloorNumber,
    FloorOffset,
    FloorSpec,
    MiddleFloor,
    RelativeFloor,
    StartFloor,
    StayExtreme,
    TopFloor,
    UpThere,
)

_GROUND_FLOOR = re.compile(r"\b(?:ground|gnd|grnd)[\s-]*(?:floor|level|storey|flr|fl)\b", re.IGNORECASE)


_ORDINALS = "|".join(lx.FLOOR_ORDINALS)
_ORDINAL_FLOOR = re.compile(rf"\b(?:{_ORDINALS})[\s-]*(?:floor|level|storey|story|flr|fl)\b", re.IGNORECASE)


def british_ordinal(said: str, text: str, counted_from: int | None = None) -> bool:
    """Whether the ordinal floor ``said`` (*the first floor*) counts from the ground floor, British style:
    where the mission ``text`` also names the ground floor (*the first-floor corridor, then the ground-floor
    loo*), whose writer does not name one floor two ways; ``counted_from`` (0 or 1) when the translator tries
    both ways (:func:`ordinal_read_either_way`)."""
    if said.split()[0] not in lx.FLOOR_ORDINALS:
        return False
    return _GROUND_FLOOR.search(text) is not None if counted_from is None else counted_from == 1


def ordinal_read_either_way(text: str) -> str | None:
    """The first ordinal floor of ``text`` as said (*first floor*, *2nd-floor*) when the text does not name
    the ground floor: its *first floor* is the lowest floor for some (US) and the one above it for others
    (British), so the scene must tell which (:meth:`.translator.PatternTranslator.translate`); ``None``
    otherwise."""
    found = _ORDINAL_FLOOR.search(text)
    return found.group(0) if found is not None and _GROUND_FLOOR.search(text) is None else None


def floors_of(spec: FloorSpec, disc: Discourse, candidates: list[Entity] | None = None) -> FloorReading:
    """The floors ``spec`` names; ``candidates``: the entities of the noun it qualifies (*the downstairs
    bathroom* in a taller building: the lower of the floors holding bathrooms)."""
    vocab = disc.vocab
    if isinstance(spec, FloorNumber):
        british = british_ordinal(spec.said, disc.text, disc.ordinals_from)
        number = spec.number + (1 if british else 0)
        if not 0 <= number < vocab.num_floors:
            rf.refuse(rf.floor_outside(spec.said, vocab.building_name, vocab.num_floors, british))
        return FloorReading(frozenset({number}))
    if isinstance(spec, TopFloor):
        return FloorReading(frozenset({vocab.num_floors - 1}))
    if isinstance(spec, MiddleFloor):
        if vocab.num_floors % 2 == 0:
            rf.refuse(rf.no_middle_floor(spec.said, vocab.building_name, vocab.num_floors))
        return FloorReading(frozenset({vocab.num_floors // 2}))
    if isinstance(spec, StartFloor):
        if disc.start_floor is None:
            every = f"floors 0 to {vocab.num_floors - 1}"
            rf.refuse(rf.needs_start_floor(spec.said, vocab.building_name, every, spec.to_stay))
        return FloorReading(frozenset({disc.start_floor}))
    if isinstance(spec, FloorOffset):
        return shifted(spec, disc)
    if isinstance(spec, RelativeFloor):
        return back_to_start(spec, disc) or relative(spec.word, disc, candidates, spec.robot_there)
    if isinstance(spec, StayExtreme):
        return FloorReading(staying(spec.word, disc))
    if isinstance(spec, UpThere):
        return FloorReading(up_there(spec.word, disc))
    assert spec.as_phrase is None, "a floor 'as X' is grounded with X (see .described.on_floor)"
    return FloorReading(same_floor(None, disc))


def listing(disc: Discourse) -> str:
    """*floors 0 to 2* (or *floor 0*) of the building, for messages."""
    n = disc.vocab.num_floors
    return "floor 0" if n == 1 else f"floors 0 to {n - 1}"


def on_floors(entities: Iterable[Entity], reading: FloorReading, disc: Discourse) -> list[Entity]:
    """``entities`` on the floors of ``reading``; when the words could also be read from the floor of the
    goal named before them, both readings must pick the same entities, else it is refused."""
    entities = list(entities)
    out = disc.vocab.on_floor(entities, reading.floors)
    if reading.second is not None and {e.key for e in disc.vocab.on_floor(entities, reading.second)} != {
            e.key for e in out}:
        rf.refuse(rf.readings_differ(reading.said, reading.after, disc.start_floor or 0))
    return out


def one_floor(entities: list[Entity], guessed: str | None, disc: Discourse) -> None:
    """Floor words counted from an unknown start floor (``guessed``, as said) are read only when the entities
    they leave lie on one floor: the start floor would tell which otherwise (refused)."""
    if guessed is not None and len({e.floor for e in entities}) > 1:
        rf.refuse(rf.needs_start_floor(guessed, disc.vocab.building_name, listing(disc)))


def second_reading(said: str, disc: Discourse,
                   relate: Callable[[int], frozenset[int]]) -> FloorReading | None:
    """Words relative to the start floor said after a goal on another floor could be relative to where
    that goal took the robot: that reading (``relate``: a floor -> the floors the words mean from there),
    or ``None`` when the last goal is on the start floor (or there is none); refused when the last goal is
    on several floors (no second reading to compare)."""
    last = disc.last_goal()
    if last is None:
        return None
    at = {e.floor for e in last.entities}
    if at == {disc.start_floor}:
        return None
    if len(at) > 1:
        rf.refuse(rf.relative_to_which(said, last.phrase, ", ".join(str(f) for f in sorted(at)),
                                       disc.start_floor or 0))
    return FloorReading(relate(at.pop()), None, said, last.phrase)


def back_to_start(spec: RelativeFloor, disc: Discourse) -> FloorReading | None:
    """*come back up and X* after goals below the start floor (*back down* after goals above it): the start
    floor, where the robot comes back to; ``None`` otherwise (then read as any *upstairs*)."""
    last = disc.last_goal()
    if not spec.back or disc.start_floor is None or last is None:
        return None
    step = lx.RELATIVE_FLOORS[spec.word]
    floors = {e.floor for e in last.entities}
    return FloorReading(frozenset({disc.start_floor})) if floors and all(
        (disc.start_floor - f) * step > 0 for f in floors) else None


def relative(word: str, disc: Discourse, candidates: list[Entity] | None,
             robot_there: bool = False) -> FloorReading:
    """*upstairs* / *downstairs*: the floors above / below the start floor when it is known; in a two-floor
    building, the upper / lower floor (after a goal on another floor, where the start has no floor that
    way, from that goal's floor: *go up to X, then come back down*, and the reverse); for a noun (*the
    downstairs bathroom*) whose candidates lie on exactly two floors, the lower / upper of those, as people
    name such rooms whatever floor they stand on, also when the robot starts where no floor lies that way in
    a two-floor building (*the downstairs bathroom* said on the ground floor); ``robot_there`` (*while you're
    upstairs*, said of where the robot is): the start floor when no floor lies that way from it (it is
    upstairs, so the words are true); otherwise refused, naming the floors."""
    step, n, start = lx.RELATIVE_FLOORS[word], disc.vocab.num_floors, disc.start_floor
    on = sorted({e.floor for e in candidates or []})
    if start is None and n > 2 and len(on) == 2:
        return FloorReading(frozenset({on[1] if step > 0 else on[0]}))
    if start is not None:
        second = second_reading(word, disc,
                                lambda base: frozenset(f for f in range(n) if (f - base) * step > 0))
        wanted = frozenset(f for f in range(n) if (f - start) * step > 0)
        if not wanted and second is not None and second.floors:
            return FloorReading(second.floors)  # "go upstairs ..., then come back down": down from there
        if not wanted and robot_there and second is None:
            return FloorReading(frozenset({start}))  # "while you're upstairs" said on the top floor: true
        if not wanted and candidates is not None and n == 2:
            # "the downstairs bathroom" said on the ground floor of a two-floor house: named so from anywhere
            return FloorReading(frozenset({1 if step > 0 else 0}))
        if not wanted:
            rf.refuse(rf.off_the_building(word, start, disc.vocab.building_name, n))
        # "the upstairs bathroom" after a goal on the top floor: from there it names nothing; from the start
        return with_second(wanted, second if second is not None and second.floors else None)
    if n == 2:
        return FloorReading(frozenset({1 if step > 0 else 0}))
    # any start: the floors above the lowest / below the highest, read where they cannot change the entity
    return FloorReading(frozenset(range(1, n) if step > 0 else range(n - 1)), said=word, unknown=True)


def shifted(spec: FloorOffset, disc: Discourse) -> FloorReading:
    """The floor ``spec.delta`` floors above the start floor (below if negative); refused without a start
    floor or outside the building."""
    n, start = disc.vocab.num_floors, disc.start_floor
    if start is None:  # any start: the floors it could name, read where they cannot change the entity
        possible = frozenset(f for f in range(n) if 0 <= f - spec.delta < n)
        if not possible:
            rf.refuse(rf.needs_start_floor(spec.said, disc.vocab.building_name, f"floors 0 to {n - 1}"))
        return FloorReading(possible, said=spec.said, unknown=True)
    second = second_reading(spec.said, disc, lambda base: frozenset({base + spec.delta})
                            if 0 <= base + spec.delta < n else frozenset())
    floor = start + spec.delta
    if not 0 <= floor < n:
        rf.refuse(rf.off_the_building(spec.said, start, disc.vocab.building_name, n))
    return with_second(frozenset({floor}), second)


def with_second(floors: frozenset[int], second: FloorReading | None) -> FloorReading:
    """``floors``, with the second reading when there is one."""
    if second is None:
        return FloorReading(floors)
    return FloorReading(floors, second.floors, second.said, second.after)


def staying(word: str, disc: Discourse) -> frozenset[int]:
    """*stay downstairs* / *stay upstairs*: the lower / upper floor of a two-floor building, or the start
    floor when it is the lowest / highest; otherwise it is not clear which floors are meant (refused)."""
    n, step = disc.vocab.num_floors, lx.RELATIVE_FLOORS[word]
    extreme = 0 if step < 0 else n - 1
    if n == 2 or disc.start_floor == extreme:
        return frozenset({extreme})
    where = "is not known here" if disc.start_floor is None else f"is floor {disc.start_floor}"
    rf.refuse(rf.stay_where(word, where, disc.vocab.building_name, n))


def up_there(word: str, disc: Discourse) -> frozenset[int]:
    """*up there* / *down there*: the floor(s) of the goal named last (one floor, not a choice of several);
    with no goal before it, of the place a sentence set aside named last (*The guest rooms are on the top
    floor. Check the bathroom up there.*)."""
    last = disc.last_goal()
    said = f"{word} there"
    if last is None and disc.confined is not None:  # "stay on the top floor and use the bathroom up there"
        return disc.confined
    mentioned = disc.mentions[-1] if disc.mentions else None
    if mentioned is not None and (last is None or last.start < mentioned.start):
        if last is not None:  # "Check the kitchen. The bedrooms are upstairs. ... up there": which?
            rf.refuse(rf.there_goal_or_mention(last.phrase, mentioned.phrase))
        last = mentioned
    if last is None:
        rf.refuse(rf.up_there_of_nothing(word))
    floor_or_place(said, last, disc)
    floors = frozenset(e.floor for e in last.entities)
    determined(said, last, len(floors))
    # "Check the oven. While you're up there, ...": a floor not up (down) from the start floor, or, that
    # unknown, from any floor, is not what the words say: the floor meant is in doubt
    start = disc.start_floor
    low, high = (start, start) if start is not None else (0, disc.vocab.num_floors - 1)
    if min(floors) <= low if word == "up" else max(floors) >= high:
        rf.refuse(rf.up_there_not_so(said, last.phrase))
    return floors


def same_floor(ref: Grounded | None, disc: Discourse) -> frozenset[int]:
    """*on the same floor (as X)* / *on that floor*: the floor of X (``ref``) when said, else of the last goal
    named; one floor (after a choice across floors the floor depends on the choice, which is refused)."""
    if ref is None:
        ref = disc.last_goal()
        if ref is None:
            rf.refuse(rf.same_floor_of_nothing())
        floor_or_place("the same floor' / 'that floor", ref, disc)
    floors = frozenset(e.floor for e in ref.entities)
    if len(floors) != 1:
        rf.refuse(rf.same_floor_of_a_choice(ref.phrase, ", ".join(str(f) for f in sorted(floors))))
    return floors


def floor_or_place(said: str, last: Grounded, disc: Discourse, rooms: bool = False) -> None:
    """Refuses ``said`` (*there*, *up there*, *on that floor*) when a floor was named as a place before
    ``last``, the place named last, and the two readings differ: "go to the top floor, then the kitchen,
    then a bathroom up there" could mean either floor; with ``rooms`` (*there* as rooms: "a book there")
    the floor and a room on it already differ."""
    floors = [g for g in disc.references
              if g.floor and g.role in ("goal", "condition") and g.start < last.start]
    if last.floor or not floors:
        return
    floor = max(floors, key=lambda g: g.start)
    if rooms or {e.floor for e in floor.entities} != {e.floor for e in last.entities}:
        rf.refuse(rf.floor_or_place(said, floor.phrase, last.phrase))


def determined(said: str, ref: Grounded, places: int) -> None:
    """Refuses ``said`` (*there*, *up there*, *its*, *next to it*) pointing back to a choice whose
    alternatives differ in what ``said`` denotes (``places`` of them)."""
    reason = backref.choice_refusal(said, ref, places)
    if reason is not None:
        rf.refuse(reason)
