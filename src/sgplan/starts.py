"""Where a plan starts: a grid cell, a metric point, a room, or one of the scene's initial positions.

:func:`start_cell` turns any of these into the ``(row, col, floor)`` cell the planner needs:

- ``None``: the scene's first initial position (``initial_positions.yaml``);
- an ``int``: the scene's initial position with that index;
- three integers ``(row, col, floor)``: that grid cell, as given;
- a :class:`Point` ``(x_m, y_m, floor)``, or three numbers of which ``x`` or ``y`` is a float: the cell
  holding that metric point; if the robot could not stand there (an inflated obstacle), the nearest
  traversable cell of the same floor within :data:`SNAP_M`;
- a string: a room, by its key ``room_<uuid>`` or its category (``"kitchen"``, case-insensitive, which must
  name one room, or ``"bathroom on floor 1"``): the room's traversable cell farthest from every obstacle.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from sgplan.english import count, series
from sgplan.errors import PlanningError
from sgplan.scene.fields import is_int, is_number
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building, Room, category_words

_ON_FLOOR = re.compile(r"^(.*?)\s+on\s+floor\s+(\d+)$", re.IGNORECASE)
SNAP_M = 0.5
"""How far (metres) a metric start may be moved to the nearest cell the robot can stand on."""


class Point(NamedTuple):
    """A metric start: ``x_m``, ``y_m`` in the scene's frame (metres) on floor ``floor``."""

    x_m: float
    y_m: float
    floor: int


StartSpec = None | int | str | Point | Sequence[float]
"""Anything :func:`start_cell` accepts."""


def start_cell(
    building: Building, grid: OccupancyGrid, start: StartSpec = None
) -> tuple[tuple[int, int, int], str]:
    """The start cell ``(row, col, floor)`` meant by ``start`` (see the module), and how it was chosen
    (for messages and results, e.g. ``"room kitchen room_5"``).

    Raises
    ------
    PlanningError
        ``status="invalid-start"`` for an unknown or ambiguous room, a room without a traversable cell,
        a point off the grid or too far from any traversable cell, a floor that does not exist, or an
        initial position index out of range; ``status="error"`` for a value of another type.
    """
    if start is None or (is_int(start) and not isinstance(start, Sequence)):
        index = None if start is None else int(start)
        try:
            cell = initial_cell(building, index=index)
        except PlanningError as error:
            raise PlanningError(str(error), status="invalid-start") from None
        return cell, f"initial position {index or 0}"
    if isinstance(start, str):
        return _room_start(building, grid, _find_room(building, start))
    if isinstance(start, Sequence) and len(start) == 3 and all(is_number(v) for v in start):
        if not is_int(start[2]):
            raise PlanningError(
                f"start {tuple(start)}: the floor must be a whole number", status="invalid-start"
            )
        if isinstance(start, Point) or not (is_int(start[0]) and is_int(start[1])):
            return _point_start(building, grid, float(start[0]), float(start[1]), int(start[2]))
        return (int(start[0]), int(start[1]), int(start[2])), "cell"
    raise PlanningError(
        f"start {start!r} is none of: a cell (row, col, floor), a Point(x_m, y_m, floor), a room name or "
        "key, "
        "an initial position index, None"
    )


def start_floor(building: Building, start: StartSpec = None) -> int | None:
    """The floor ``start`` names, read without building the grid (for the offline translator's
    *upstairs* / *downstairs*, known before planning); ``None`` when it names none that exists. A start
    that :func:`start_cell` would refuse is refused there, not here."""
    try:
        if start is None or (is_int(start) and not isinstance(start, Sequence)):
            return initial_cell(building, index=None if start is None else int(start))[2]
        if isinstance(start, str):
            return _find_room(building, start).floor
        if isinstance(start, Sequence) and len(start) == 3 and is_int(start[2]):
            floor = int(start[2])
            return floor if 0 <= floor < building.num_floors else None
    except PlanningError:
        return None
    return None


def initial_cell(building: Building, index: int | None = None) -> tuple[int, int, int]:
    """The scene's initial cell ``(row, col, floor)`` number ``index`` (initial_positions.yaml), or its
    first one."""
    cells = building.initial_cells
    if not cells:
        raise PlanningError(
            f"scene {building.name!r} has no initial positions: give a start cell (row, col, floor)"
        )
    k = 0 if index is None else index
    if not 0 <= k < len(cells):
        raise PlanningError(
            f"start index {k} is out of range: scene {building.name!r} has {len(cells)} initial positions"
        )
    return cells[k]


def _find_room(building: Building, name: str) -> Room:
    key = name.strip()
    if key.lower().startswith("room_") and key[5:].isdigit():
        uuid = int(key[5:])
        if not building.has_room(uuid):
            raise PlanningError(
                f"start: building {building.name!r} has no room {key}", status="invalid-start"
            )
        return building.room(uuid=uuid)
    on_floor = _ON_FLOOR.match(key)
    rooms = building.rooms_named(on_floor[1], int(on_floor[2])) if on_floor else building.rooms_named(key)
    if len(rooms) == 1:
        return rooms[0]
    if not rooms:
        names = sorted({room.name for room in building.rooms()})
        raise PlanningError(f"start: building {building.name!r} has no room called {name!r} (rooms: "
                            f"{', '.join(names)})", status="invalid-start")
    choices = ", ".join(f"'{spec}' ({about})" for spec, about in _telling_apart(building, rooms))
    raise PlanningError(f"start: {name!r} names {count(len(rooms), 'room')}; say which, with one of: "
                        f"{choices}", status="invalid-start")


def _telling_apart(building: Building, rooms: list[Room]) -> list[tuple[str, str]]:
    """For each of ``rooms`` (one category), a start that names it alone -- ``'bathroom on floor 1'`` where
    it is its floor's only one, else its key -- and what sets it apart (key or floor, neighbours)."""
    floors = [room.floor for room in rooms]
    out = []
    for room in rooms:
        alone = floors.count(room.floor) == 1
        neighbours = [f"the {n}" for n in sorted({category_words(building.room(id=i).name)
                                                   for i in room.connected_room_ids})]
        near = f", next to {series(neighbours)}" if neighbours else ", no door to another room"
        spec = f"{room.name} on floor {room.floor}" if alone else room.key
        out.append((spec, f"{room.key if alone else f'floor {room.floor}'}{near}"))
    return out


def _room_start(building: Building, grid: OccupancyGrid, room: Room) -> tuple[tuple[int, int, int], str]:
    free = (grid.room_map[room.floor] == room.id) & grid.traversable[room.floor]
    if not free.any():
        raise PlanningError(
            f"start: room {room.name} {room.key} has no cell a robot of radius {grid.robot_radius_m} m can "
            "stand on",
            status="invalid-start",
        )
    from scipy import ndimage  # slow to import: only for a start given as a room or a point

    # The cell deepest inside the room's free area: clear of walls, furniture and doorways.
    depth = ndimage.distance_transform_edt(free)
    row, col = np.unravel_index(int(np.argmax(depth)), depth.shape)
    return (int(row), int(col), room.floor), f"room {room.name} {room.key}"


def _point_start(building: Building, grid: OccupancyGrid, x_m: float, y_m: float,
                 floor: int) -> tuple[tuple[int, int, int], str]:
    if not (math.isfinite(x_m) and math.isfinite(y_m)):
        raise PlanningError(f"start point ({x_m}, {y_m}) is not finite", status="invalid-start")
    if not 0 <= floor < building.num_floors:
        raise PlanningError(f"start point on floor {floor}: building {building.name!r} has floors "
                            f"0..{building.num_floors - 1}", status="invalid-start")
    row, col = building.floors[floor].xy_to_cell(x_m, y_m)
    _, rows, cols = grid.shape
    if not (0 <= row < rows and 0 <= col < cols):
        raise PlanningError(
            f"start point ({x_m:g}, {y_m:g}) m lies off floor {floor}'s grid "
            f"({building.floors[floor].extent_text()})", status="invalid-start"
        )
    where = f"point ({x_m:g}, {y_m:g}) m floor {floor}"
    if grid.traversable[floor, row, col]:
        return (row, col, floor), where
    from scipy import ndimage

    blocked = ~grid.traversable[floor]
    distance, (near_r, near_c) = (
        ndimage.distance_transform_edt(blocked, sampling=grid.resolution_m, return_indices=True)
        if not blocked.all() else (np.full(blocked.shape, np.inf), (blocked, blocked))
    )
    if distance[row, col] > SNAP_M:
        raise PlanningError(
            f"start {where} is not free for a robot of radius {grid.robot_radius_m} m and no free cell lies "
            "within "
            f"{SNAP_M} m",
            status="invalid-start",
        )
    cell = (int(near_r[row, col]), int(near_c[row, col]), floor)
    return cell, f"{where}, moved {float(distance[row, col]):.2f} m to the nearest free cell"
