"""The scene as the translator grounds phrases in it: its rooms and objects, and the filters qualifiers apply.

Every room and object of a :class:`~sgplan.scene.model.Building` becomes an :class:`Entity` keyed by its
unique ID (``room_<uuid>``, ``object_<uuid>``). Categories are the Gibson names with ``_`` read as a
space (``dining_room`` -> "dining room"); the words that name them are the scene's :class:`.NounLexicon`
(:attr:`SceneVocabulary.nouns`).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable
from dataclasses import dataclass

from sgplan.llm.offline.nouns import Head, Kind, NounLexicon
from sgplan.scene.model import Building, category_words


@dataclass(frozen=True)
class Entity:
    """A room or an object of the scene, as the translator sees it.

    ``room_key`` is the key of the room itself (rooms) or of the containing room (objects).
    """

    key: str
    kind: Kind
    category: str
    floor: int
    room_key: str

    @property
    def action(self) -> str:
        """The action token that is true when the robot is at this entity."""
        return f"enter({self.key})" if self.kind == "room" else f"reach({self.key})"

    def describe(self) -> str:
        """``room_2 (bathroom, floor 0)`` / ``object_27 (sink in room_2, floor 0)``."""
        if self.kind == "room":
            return f"{self.key} ({self.category}, floor {self.floor})"
        return f"{self.key} ({self.category} in {self.room_key}, floor {self.floor})"


def head_word(entities: list[Entity]) -> str:
    """The category of a group of entities, for messages (``room`` when they differ)."""
    categories = {e.category for e in entities}
    return categories.pop() if len(categories) == 1 else entities[0].kind if entities else "room"


class SceneVocabulary:
    """The entities of one building, the head nouns that name them, and the qualifier filters.

    Parameters
    ----------
    building:
        the scene; its room categories and object classes become the head nouns.
    """

    def __init__(self, building: Building) -> None:
        self.building_name = building.name
        self.num_floors = building.num_floors
        entities: list[Entity] = []
        self.adjacent: dict[str, frozenset[str]] = {}
        for room in building.rooms():
            entities.append(Entity(room.key, "room", category_words(room.name), room.floor, room.key))
            self.adjacent[room.key] = frozenset(f"room_{u}" for u in room.connected_room_uuids)
            for obj in room.objects.values():
                entities.append(Entity(obj.key, "object", category_words(obj.name), room.floor, room.key))
        self.entities = tuple(entities)
        self.by_key = {e.key: e for e in entities}
        self.nouns = NounLexicon({e.category: e.kind for e in reversed(entities)})

    def rooms_named_by(self, modifier: str) -> list[Entity]:
        """The rooms whose category has several words, the first being ``modifier`` (*dining*)."""
        return [e for e in self.entities
                if e.kind == "room" and " " in e.category and e.category.split()[0] == modifier]

    def category_names(self, kind: Kind) -> list[str]:
        """The categories of one kind present in the scene, sorted."""
        return self.nouns.category_names(kind)

    # -- sets and filters ----------------------------------------------------------------------------
    def of_head(self, head: Head) -> list[Entity]:
        """Every entity the head noun may denote, in scene order."""
        return [
            e for e in self.entities
            if e.kind == head.kind and (not head.categories or e.category in head.categories)
        ]

    def on_floor(self, entities: Iterable[Entity], floors: int | Collection[int]) -> list[Entity]:
        """Entities on ``floors`` (one floor or several)."""
        wanted = {floors} if isinstance(floors, int) else set(floors)
        return [e for e in entities if e.floor in wanted]

    def inside(self, entities: Iterable[Entity], rooms: Iterable[Entity]) -> list[Entity]:
        """Objects among ``entities`` that lie in one of ``rooms``."""
        keys = {r.key for r in rooms}
        return [e for e in entities if e.kind == "object" and e.room_key in keys]

    def containing(self, rooms: Iterable[Entity], objects: list[Entity], count: int | None,
                   only: bool = False) -> list[Entity]:
        """Rooms holding at least one of ``objects`` (exactly ``count`` of them when ``count`` is given;
        with ``only``, nothing of another category)."""
        categories = {o.category for o in objects}
        out = []
        for room in rooms:
            n = sum(1 for o in objects if o.room_key == room.key)
            if only and any(e.kind == "object" and e.room_key == room.key and e.category not in categories
                            for e in self.entities):
                continue
            if (n >= 1 and count is None) or (count is not None and n == count):
                out.append(room)
        return out

    def lacking(self, rooms: Iterable[Entity], objects: list[Entity]) -> list[Entity]:
        """Rooms holding none of ``objects``."""
        holders = {o.room_key for o in objects}
        return [r for r in rooms if r.key not in holders]

    def next_to(self, rooms: Iterable[Entity], others: Iterable[Entity]) -> list[Entity]:
        """Rooms among ``rooms`` connected to one of ``others`` (and not one of them)."""
        other_keys = {o.key for o in others}
        return [r for r in rooms if r.key not in other_keys and self.adjacent.get(r.key, frozenset())
                & other_keys]
