"""Rooms and objects named as people name them, and their names said back.

A room is named by its key (``room_5``), its category when one room has it (``kitchen``, any case,
underscores or spaces), or its category on a floor (``bathroom on floor 1``). An object is named by its
key (``object_27``), its category when one object has it (``refrigerator``), or its category in a room
(``chair in the kitchen``, ``sink in room_5``). A name that fits several entities is refused with the
candidates, never guessed.

>>> from sgplan.scene.demo import demo_building
>>> building = demo_building()
>>> room_phrase(find_room(building, "kitchen"))
'the kitchen (room_4, floor 0)'
>>> object_phrase(building, find_object(building, "sink in the bathroom on floor 0"))
'the sink (object_21, in the bathroom room_5, floor 0)'
"""

from __future__ import annotations

import re

from sgplan.errors import SceneError
from sgplan.scene.model import Building, Room, SceneObject, category_words

_ON_FLOOR = re.compile(r"^(.*?)\s+on\s+floor\s+(\d+)$", re.IGNORECASE)
_IN_ROOM = re.compile(r"^(.*?)\s+in\s+(?:the\s+)?(.+)$", re.IGNORECASE)
_KEY = re.compile(r"^(room|object)_(\d+)$")


def _category(name: str) -> str:
    """A category as people write it (:func:`~sgplan.scene.model.category_words`), no leading article."""
    text = category_words(name)
    return text[4:] if text.startswith("the ") else text


def room_phrase(room: Room) -> str:
    """``the kitchen (room_4, floor 0)``."""
    return f"the {_category(room.name)} ({room.key}, floor {room.floor})"


def object_phrase(building: Building, obj: SceneObject) -> str:
    """``the sink (object_21, in the bathroom room_5, floor 0)``."""
    room = building.room(id=obj.room_id)
    where = f"in the {_category(room.name)} {room.key}, floor {room.floor}"
    return f"the {_category(obj.name)} ({obj.key}, {where})"


def find_room(building: Building, name: str) -> Room:
    """The one room ``name`` names (see the module).

    Raises
    ------
    SceneError
        naming the rooms the building has when none fits, or the candidates when several do.
    """
    text = str(name).strip()
    key = _KEY.match(text)
    if key is not None and key[1] == "room":
        if not building.has_room(int(key[2])):
            raise SceneError(f"building {building.name!r} has no room {text}")
        return building.room(uuid=int(key[2]))
    on_floor = _ON_FLOOR.match(text)
    wanted, floor = (_category(on_floor[1]), int(on_floor[2])) if on_floor else (_category(text), None)
    rooms = [r for r in building.rooms()
             if _category(r.name) == wanted and (floor is None or r.floor == floor)]
    if len(rooms) == 1:
        return rooms[0]
    if not rooms:
        names = ", ".join(sorted({_category(r.name) for r in building.rooms()}))
        raise SceneError(f"building {building.name!r} has no room called {text!r} (rooms: {names})")
    listing = ", ".join(f"{r.key} (floor {r.floor})" for r in rooms)
    raise SceneError(f"{text!r} names {len(rooms)} rooms ({listing}); give a key or say "
                     f"'{wanted} on floor N'")


def find_object(building: Building, name: str) -> SceneObject:
    """The one object ``name`` names (see the module).

    Raises
    ------
    SceneError
        when no object fits (naming the categories the building has) or several do (naming them).
    """
    text = str(name).strip()
    key = _KEY.match(text)
    if key is not None and key[1] == "object":
        if not building.has_object(int(key[2])):
            raise SceneError(f"building {building.name!r} has no object {text}")
        return building.object(uuid=int(key[2]))
    in_room = _IN_ROOM.match(text)
    room = find_room(building, in_room[2]) if in_room else None
    wanted = _category(in_room[1] if in_room else text)
    objects = [o for o in building.objects()
               if _category(o.name) == wanted and (room is None or o.room_id == room.id)]
    if len(objects) == 1:
        return objects[0]
    where = f" in {room_phrase(room)}" if room is not None else ""
    if not objects:
        names = ", ".join(sorted({_category(o.name) for o in building.objects()}))
        raise SceneError(f"building {building.name!r} has no object called {wanted!r}{where} "
                         f"(objects: {names})")
    listing = "; ".join(object_phrase(building, o) for o in objects)
    hint = "give a key" if room is not None else f"give a key or say '{wanted} in ROOM'"
    raise SceneError(f"{text!r} names {len(objects)} objects ({listing}); {hint}")
