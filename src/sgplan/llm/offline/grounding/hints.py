"""What tells the candidates of an ambiguous phrase apart: a wording that singles one out in the scene.

When *the book* matches two books, the refusal suggests a phrase the translator reads as one of them (*the
book in the bedroom with the vase*), never one that is itself ambiguous (*the book in the bedroom on floor
2* where both bedrooms are on floor 2). Each suggestion is checked against the whole scene, as the
translator would ground it: by its floor, by the category of its room, by that room's floor, by what the
room holds, by what the room is next to; for a room, by its floor, its contents, its neighbours. When none
singles one out, the suggestion is a choice (*any book*, *every book*) or an ID.
"""

from __future__ import annotations

from collections.abc import Iterator

from sgplan.llm.offline.names import Entity, SceneVocabulary


def hint(entities: list[Entity], vocab: SceneVocabulary) -> str:
    """How to single one of ``entities`` (the candidates of an ambiguous phrase, of one kind) out."""
    word = entities[0].category
    for e in entities:
        found = next(object_wordings(e, vocab) if e.kind == "object" else room_wordings(e, vocab), None)
        if found is not None:
            how, said = found
            return f"say {how} (e.g. '{said}')"
    return f"say 'any {word}' or 'every {word}', or name it by its ID (e.g. {entities[0].key})"


def object_wordings(e: Entity, vocab: SceneVocabulary) -> Iterator[tuple[str, str]]:
    """Phrases that name the object ``e`` (or, where its room holds several alike, any of them), with what
    they say: its floor, its room's category, floor, contents or neighbour, the first that singles out its
    room among the rooms holding such objects."""
    room = vocab.by_key[e.room_key]
    holders = [vocab.by_key[k] for k in dict.fromkeys(o.room_key for o in vocab.entities
                                                       if o.kind == "object" and o.category == e.category)]
    if [r for r in holders if r.floor == room.floor] == [room]:
        yield "which floor", f"the {e.category} on floor {room.floor}"
    for _, said in room_wordings(room, vocab, among=holders):
        yield "which room it is in", f"the {e.category} in {said}"


def room_wordings(room: Entity, vocab: SceneVocabulary,
                  among: list[Entity] | None = None) -> Iterator[tuple[str, str]]:
    """Phrases that single out ``room`` among the rooms of its category (of ``among`` when given): the
    category alone, its floor, an object it holds, both, a room it is next to."""
    alike = [r for r in (among if among is not None else vocab.entities)
             if r.kind == "room" and r.category == room.category]
    name = f"the {room.category}"
    if among is not None and alike == [room]:
        yield "which room", name
    if [r for r in alike if r.floor == room.floor] == [room]:
        yield "which floor", f"{name} on floor {room.floor}"
    for held in sorted({o.category for o in vocab.entities if o.kind == "object" and o.room_key == room.key}):
        holding = [r for r in alike if holds(r, held, vocab)]
        if holding == [room]:
            yield "what it contains", f"{name} with the {held}"
        if [r for r in holding if r.floor == room.floor] == [room]:
            yield "what it contains", f"{name} on floor {room.floor} with the {held}"
    for near in sorted(neighbours(room, vocab)):
        if [r for r in alike if near in neighbours(r, vocab)] == [room]:
            yield "what it is next to", f"{name} next to the {near}"


def neighbours(room: Entity, vocab: SceneVocabulary) -> set[str]:
    """The categories of the rooms connected to ``room``."""
    return {vocab.by_key[k].category for k in vocab.adjacent.get(room.key, ()) if k in vocab.by_key}


def holds(room: Entity, category: str, vocab: SceneVocabulary) -> bool:
    """Whether ``room`` holds an object of ``category``."""
    return any(o.kind == "object" and o.room_key == room.key and o.category == category
               for o in vocab.entities)
