"""The attribute hierarchy: a compact text of floors -> rooms -> objects for language-model prompts.

Example (Benevolence, abridged)::

    Building Benevolence: 3 floors, 16 rooms, 41 objects.
    Floor 0:
      room_2: bathroom. Connects to: room_14. Objects: object_27 (sink), object_41 (toilet), ...
      room_18: staircase. Connects to: room_10 (floor 1), room_17.
    Floor 1:
      ...

Every entity carries the unique ID missions use (``room_<uuid>``, ``object_<uuid>``). Order is
deterministic: floors by index, rooms and objects by uuid, connections by uuid; a connection to a room of
another floor (through a staircase) says which floor.
"""

from __future__ import annotations

from sgplan.scene.model import Building, Room


def attribute_hierarchy(building: Building, *, connections: bool = True, objects: bool = True) -> str:
    """The hierarchy text of ``building`` (one line per floor and per room, ending with a newline).

    Parameters
    ----------
    building:
        Any building; rooms without connections (e.g. read from a raw npz) say ``Connects to: none``.
    connections, objects:
        Leave out the room connections or the objects (for shorter prompts).
    """
    num_rooms = sum(1 for _ in building.rooms())
    num_objects = sum(1 for _ in building.objects())
    lines = [
        f"Building {building.name}: {_count(building.num_floors, 'floor')}, {_count(num_rooms, 'room')}, "
        f"{_count(num_objects, 'object')}."
    ]
    for floor in building.floors:
        lines.append(f"Floor {floor.index}:")
        for room in sorted(floor.rooms.values(), key=lambda r: r.uuid):
            parts = [f"  {room.key}: {room.name}."]
            if connections:
                parts.append(f"Connects to: {_connections(building, room)}.")
            if objects and room.objects:
                ordered = sorted(room.objects.values(), key=lambda o: o.uuid)
                listed = ", ".join(f"{o.key} ({o.name})" for o in ordered)
                parts.append(f"Objects: {listed}.")
            lines.append(" ".join(parts))
    return "\n".join(lines) + "\n"


def _connections(building: Building, room: Room) -> str:
    neighbours = sorted((building.room(uuid=u) for u in room.connected_room_uuids), key=lambda r: r.uuid)
    if not neighbours:
        return "none"
    return ", ".join(r.key if r.floor == room.floor else f"{r.key} (floor {r.floor})" for r in neighbours)


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}" + ("" if number == 1 else "s")
