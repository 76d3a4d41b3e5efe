"""The scene's vocabulary: which words name which rooms and objects, and the filters qualifiers apply.

Every room and object of a :class:`~sgplan.scene.model.Building` becomes an :class:`Entity` keyed by its
unique ID (``room_<uuid>``, ``object_<uuid>``). Categories are the Gibson names with ``_`` read as a
space (``dining_room`` -> "dining room"); each is known in the singular, the plural, and through the
synonyms of :data:`.lexicon.SYNONYMS` that fit a category the scene has (``sofa`` -> couch).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable
from dataclasses import dataclass
from typing import Literal

from sgplan.llm.offline.lexicon import GENERIC_ROOM_WORDS, ROOM_MODIFIERS, SYNONYMS, plural
from sgplan.scene.model import Building

Kind = Literal["room", "object"]


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


@dataclass(frozen=True)
class Head:
    """What a head noun denotes: a kind and the categories it covers (empty = every room)."""

    kind: Kind
    categories: frozenset[str]
    plural: bool
    words: int
    """How many words of the text the head noun spans."""


def category_name(gibson_name: str) -> str:
    """``dining_room`` -> ``dining room``; lower case."""
    return gibson_name.replace("_", " ").strip().lower()


class SceneVocabulary:
    """The entities of one building, the noun phrases that name them, and the qualifier filters.

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
            entities.append(Entity(room.key, "room", category_name(room.name), room.floor, room.key))
            self.adjacent[room.key] = frozenset(f"room_{u}" for u in room.connected_room_uuids)
            for obj in room.objects.values():
                entities.append(Entity(obj.key, "object", category_name(obj.name), room.floor, room.key))
        self.entities = tuple(entities)
        self.by_key = {e.key: e for e in entities}
        self._heads = self._head_table()
        self._longest = max((len(words) for words in self._heads), default=1)

    # -- head nouns --------------------------------------------------------------------------------
    def _head_table(self) -> dict[tuple[str, ...], Head]:
        by_kind: dict[str, Kind] = {}
        for e in self.entities:
            by_kind.setdefault(e.category, e.kind)
        names: dict[str, set[str]] = {c: {c} for c in by_kind}
        for word, targets in SYNONYMS.items():
            present = {t for t in targets if t in by_kind}
            kinds = {by_kind[t] for t in present}
            # A synonym that is itself a category name keeps its literal meaning; one spanning rooms and
            # objects would be ambiguous in kind, so it is not used.
            if present and word not in by_kind and len(kinds) == 1:
                names.setdefault(word, set()).update(present)
        table: dict[tuple[str, ...], Head] = {}
        for word, cats in names.items():
            kind = by_kind[next(iter(cats))]
            for form, is_plural in ((word, False), (plural(word), True)):
                key = tuple(form.split())
                # A word whose plural is itself ("stairs") stays singular: "the stairs" is then one
                # staircase, ambiguous where there are several, rather than silently all of them.
                table.setdefault(key, Head(kind, frozenset(cats), is_plural, len(key)))
        for word in GENERIC_ROOM_WORDS:
            table.setdefault((word,), Head("room", frozenset(), word.endswith("s"), 1))
        return table

    def match_head(self, words: list[str], start: int) -> Head | None:
        """The longest head noun beginning at ``words[start]``, or ``None``."""
        for n in range(min(self._longest, len(words) - start), 0, -1):
            head = self._heads.get(tuple(words[start : start + n]))
            if head is not None:
                return head
        return None

    def room_modifier(self, words: list[str], start: int) -> list[Entity]:
        """``dining`` in "the dining chairs": the first word of a room category (one of
        :data:`.lexicon.ROOM_MODIFIERS`, not an adjective such as *living*) before an object noun -> the
        rooms of that category (empty list otherwise)."""
        if (start + 1 >= len(words) or words[start] not in ROOM_MODIFIERS
                or self.match_head(words, start) is not None):
            return []
        after = self.match_head(words, start + 1)
        if after is None or after.kind != "object":
            return []
        return [e for e in self.entities
                if e.kind == "room" and len(e.category.split()) > 1 and e.category.split()[0] == words[start]]

    def category_names(self, kind: Kind) -> list[str]:
        """The categories of one kind present in the scene, sorted."""
        return sorted({e.category for e in self.entities if e.kind == kind})

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
