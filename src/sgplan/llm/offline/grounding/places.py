"""What *there*, *in there*, *the same room* and *next to it* point back to: the place named last.

*there* after an object (*grab a bottle there*) is the room of the last place named as a goal or a
condition; after a room (*a bathroom there*) the floor of a floor named last as a place; *next to it* is
the whole phrase named last, which must be a room. Each is refused when what it points back to is a
choice whose alternatives differ in what it would denote, or when a floor and a place named after it
would give two readings.
"""

from __future__ import annotations

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.discourse import Discourse, FloorReading, Grounded
from sgplan.llm.offline.grounding.floors import determined, floor_or_place
from sgplan.llm.offline.names import Entity, head_word
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax.tree import Span


def places_before(before: int, disc: Discourse) -> list[Grounded]:
    """The places named as goals or conditions before character ``before`` (not pronouns)."""
    return [g for g in disc.references if g.role in ("goal", "condition") and g.start < before and g.entities
            and g.phrase.lower() not in lx.PRONOUNS]


def there_rooms(before: int, disc: Discourse, said: str = "there") -> list[Entity]:
    """The rooms *there* means at character offset ``before``: those of the last place named as a goal or a
    condition before it (*whenever you enter the kitchen, grab a bottle there*), or of one room named in
    words set aside after the last such place (*The downstairs bathroom is a mess. Check the toilet there.*;
    refused when a goal was named before that room: which of the two?)."""
    places = places_before(before, disc)
    mentioned = [g for g in disc.mentions if g.start < before and len({e.room_key for e in g.entities}) == 1]
    if mentioned and (not places or max(g.start for g in places) < mentioned[-1].start):
        if places:
            last_goal = max(places, key=lambda g: g.start)
            rf.refuse(rf.there_goal_or_mention(last_goal.phrase, mentioned[-1].phrase))
        places = mentioned[-1:]
    if not places:
        rf.refuse(rf.there_refers_to_nothing())
    last = max(places, key=lambda g: g.start)
    floor_or_place(said, last, disc, rooms=True)
    rooms = [disc.vocab.by_key[k] for k in dict.fromkeys(e.room_key for e in last.entities)]
    if not last.floor:  # a floor is one place: "the top floor ... a book there" is any room of it
        determined(said, last, len(rooms))
    return rooms


def there_holding(before: int, objects: list[Entity], disc: Discourse) -> list[Entity]:
    """*the TV in there*: the one room named before character ``before`` as a place to keep out of that holds
    one of ``objects`` (:func:`there_rooms_holding` asks it: *don't go in the living room until you've checked
    the microwave; look at the TV in there*); none when no such room or several do. Another goal is never
    taken instead (*the kitchen, then the bedroom, and the sink in there*: the user may have meant another
    room)."""
    holders = {o.room_key for o in objects}
    named = {e.key for g in disc.references if g.start < before and g.role == "avoid"
             for e in g.entities if e.kind == "room" and e.key in holders}
    return [disc.vocab.by_key[k] for k in named] if len(named) == 1 else []


def there_rooms_holding(before: int, objects: list[Entity], rooms: list[Entity],
                        disc: Discourse) -> list[Entity]:
    """The rooms *in there* means for ``objects`` at character offset ``before``: ``rooms`` (of the place
    named last) when one holds one of them, else :func:`there_holding`; refused when a place kept out of
    until a goal also holds one (*don't go into the dining room until you've checked the microwave; after
    that, straighten one of the chairs in there*: the kitchen's chairs, or the dining room's?)."""
    holding = [r for r in rooms if any(o.room_key == r.key for o in objects)]
    kept_out = there_holding(before, objects, disc)
    if holding and any(r.key in disc.kept_until and r not in holding for r in kept_out):
        rf.refuse(rf.there_goal_or_kept_out_until(" or ".join(r.key for r in holding), kept_out[0].key))
    return holding or kept_out


def there_floors(before: int, head: Head, disc: Discourse,
                 action_floor: tuple[FloorReading, int] | None) -> frozenset[int]:
    """The floor(s) *there* after a room (*a bathroom there*) means at character offset ``before``: a floor
    named last as a place, or the floor of a floor move before it (*go upstairs, then X there*), or the
    floors the mission stays on. A room or object named last is refused: rooms are not inside rooms, and
    reading *there* as nothing would silently widen the phrase."""
    places = places_before(before, disc)
    last = max(places, key=lambda g: g.start) if places else None
    if action_floor is not None and (last is None or last.start < action_floor[1]):
        return action_floor[0].floors
    if last is None and disc.confined is not None:  # "keep to the top floor and visit X there"
        return disc.confined
    if last is None or not last.floor:
        what = f"'{last.phrase}'" if last is not None else "nothing"
        rf.refuse(rf.there_is_not_a_floor(head_word(disc.vocab.of_head(head)), what))
    return frozenset(e.floor for e in last.entities)


def next_to_it(span: Span, said: str, disc: Discourse, by_room: bool = False) -> Grounded:
    """*next to it* / *just off it* (``said``): *it* is the last whole phrase named (not one nested in it:
    in "the bedroom where the teddy bear is" that is the bedroom); it must be a room, since distances
    between objects are not known. With ``by_room`` (*next door*, or a room next to it) an object stands for
    its room: a room is next to rooms only, so *the bed ..., then the bathroom next door / next to it* is
    next to the bed's room."""
    refs = [g for g in disc.references if g.phrase.lower() not in lx.PRONOUNS and g.entities]
    outer = [g for g in refs if not any(o is not g and o.start <= g.start and g.end <= o.end
                                        and (o.start, o.end) != (g.start, g.end) for o in refs)]
    if not outer:
        rf.refuse(rf.next_door_to_nothing(said) if said.endswith("next door") else rf.no_room_antecedent())
    ref = max(outer, key=lambda g: g.start)
    goals = [g for g in outer if g.role == "goal" and g.start < ref.start]
    if ref.role == "avoid" and goals:  # "go to the bedroom, avoid the other one. ... the bathroom next to it"
        rf.refuse(rf.antecedent_or_kept_out("it", goals[-1].phrase, ref.phrase))
    entities = list(ref.entities)
    if by_room:  # the rooms of the objects named: several rooms of a choice are refused just below
        entities = [disc.vocab.by_key[k] for k in dict.fromkeys(e.room_key for e in entities)]
    determined(said, ref, len(entities))
    if any(e.kind != "room" for e in entities):
        rf.refuse(rf.next_to_an_object(said, ref.phrase))
    return disc.record(Grounded("it", span.start, span.end, entities, ref.mode, False, "qualifier"))
