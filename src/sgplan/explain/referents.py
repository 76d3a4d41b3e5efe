"""What a proposition names in the scene: category, floor and id, as English noun phrases.

A :class:`Referent` is the scene-side meaning of one proposition, the entity it refers to
(``enter(room_11)`` -> the kitchen, room_11 on floor 0). The explanation renderers only see referents,
never the user's text, so what they print is what the planner will use. (The offline translator's
vocabulary has its own :class:`sgplan.llm.offline.names.Entity`: a room or object as words name it.)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

from sgplan.english import a_or_an
from sgplan.errors import FormulaError
from sgplan.scene.labels import Proposition
from sgplan.scene.model import Building, category_words

ReferentKind = Literal["room", "object", "unknown"]


@dataclass(frozen=True)
class Referent:
    """One proposition's meaning in a scene.

    Attributes
    ----------
    proposition:
        the proposition name in the formula / automaton (``p1`` or ``enter(room_2)``).
    kind:
        ``"room"`` (true inside the room), ``"object"`` (true within reach of the object) or
        ``"unknown"`` (the scene has no such entity, or no scene was given).
    key:
        the unique id used in missions, e.g. ``room_11`` or ``object_27``; the proposition name for
        ``unknown``.
    category:
        the scene's category with underscores as spaces (``living room``), ``None`` if unknown.
    floor:
        the floor index, ``None`` if unknown.
    room_key, room_category:
        for an object, the room that holds it.
    """

    proposition: str
    kind: ReferentKind
    key: str
    category: str | None = None
    floor: int | None = None
    room_key: str | None = None
    room_category: str | None = None

    @property
    def where(self) -> str:
        """The location part of the phrase: ``floor 0`` or ``in the bathroom room_2, floor 0``."""
        parts = []
        if self.room_key is not None:
            parts.append(f"in the {self.room_category} {self.room_key}")
        if self.floor is not None:
            parts.append(f"floor {self.floor}")
        return ", ".join(parts)

    def phrase(self) -> str:
        """``the kitchen (room_11, floor 0)``, ``the sink (object_27, in the bathroom room_2, floor 0)``."""
        if self.kind == "unknown":
            return (
                f"{self.key} (not in this scene)" if self.key.startswith(("room_", "object_")) else self.key
            )
        where = self.where
        return f"the {self.category} ({self.key}{', ' + where if where else ''})"


def referent_of(name: str, proposition: Proposition | None, building: Building | None) -> Referent:
    """The entity ``proposition`` (named ``name`` in the formula) denotes in ``building``."""
    if proposition is None:
        try:
            proposition = Proposition.parse(name)
        except FormulaError:  # not an action token: a bare name with no meaning in the scene
            return Referent(name, "unknown", name)
    key = f"{'room' if proposition.kind == 'enter' else 'object'}_{proposition.uuid}"
    if building is None:
        return Referent(name, "room" if proposition.kind == "enter" else "object", key)
    if proposition.kind == "enter":
        if not building.has_room(proposition.uuid):
            return Referent(name, "unknown", key)
        room = building.room(uuid=proposition.uuid)
        return Referent(name, "room", key, category_words(room.name), room.floor)
    if not building.has_object(proposition.uuid):
        return Referent(name, "unknown", key)
    obj = building.object(uuid=proposition.uuid)
    room = building.room(id=obj.room_id)
    return Referent(name, "object", key, category_words(obj.name), room.floor, room.key,
                    category_words(room.name))


def referents_of(
    names: Sequence[str], propositions: Mapping[str, Proposition] | None, building: Building | None
) -> dict[str, Referent]:
    """``{name: Referent}`` for every proposition name, in the given order."""
    meaning = propositions or {}
    return {name: referent_of(name, meaning.get(name), building) for name in names}


def group_phrase(entities: Sequence[Referent], article: str = "a") -> str:
    """Alternatives of one kind and category as one phrase: ``a bedroom (room_5 or room_6, floor 1)``.

    Entities sharing their location print it once; otherwise each id carries its own
    (``a bedroom (room_5, floor 0, or room_6, floor 1)``). Mixed categories list the phrases with "or".
    """
    if len(entities) == 1:
        return entities[0].phrase()
    first = entities[0]
    if first.kind == "unknown" or any(e.kind != first.kind or e.category != first.category for e in entities):
        return " or ".join(e.phrase() for e in entities)
    wheres = {e.where for e in entities}
    if len(wheres) == 1:
        where = wheres.pop()
        keys = " or ".join(e.key for e in entities)
        return f"{_with_article(article, first.category)} ({keys}{', ' + where if where else ''})"
    items = [f"{e.key}, {e.where}" if e.where else e.key for e in entities]
    return f"{_with_article(article, first.category)} ({', or '.join(items)})"


def _with_article(article: str, category: str | None) -> str:
    """``a``/``an`` by the category's sound; any other article (``the``, ``every``) as given."""
    return a_or_an(str(category)) if article == "a" else f"{article} {category}"
