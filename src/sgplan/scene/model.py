"""The scene-graph model: a building of floors, each with rooms, each with objects.

Identifiers
-----------
- ``id``: the Gibson 3D Scene Graph id, unique per node type (two rooms never share an id, but a room and
  an object may). Rasters (``Floor.cat_map``, ``Floor.room_map``) store ids.
- ``uuid``: unique over all nodes of the building (building = 1). Missions, propositions
  (``enter(room_<uuid>)``, ``reach(object_<uuid>)``), prompts and LLM guidance use uuids.

Grid conventions
----------------
A cell is ``(row, col)`` on a floor; ``row`` runs along metric x and ``col`` along metric y. Every floor
of a building has the same grid shape ``(rows, cols)``. Metric coordinates are metres.
``Floor.cell_to_xy`` gives a cell's centre.

Raster codes (``Floor.cat_map``): object id (> 0) on object footprints, and the values of
:class:`CatCode` otherwise. ``Floor.room_map``: room id (> 0, staircases included) or ``NO_ROOM``.
"""

from __future__ import annotations

import enum
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from sgplan.english import count
from sgplan.errors import SceneError

Cell = tuple[int, int]
"""A grid cell ``(row, col)`` on one floor."""


def category_words(name: str) -> str:
    """A room's or object's category as people write it: ``dining_room`` -> ``dining room`` (lower case,
    underscores as spaces, runs of spaces as one). The one spelling every message, say-back and name
    lookup uses."""
    return " ".join(name.replace("_", " ").lower().split())


class CatCode(enum.IntEnum):
    """Non-object values of a decoded category map (the authors' PNG value minus 5)."""

    GROUND = 0
    STAIRS_UP = -1
    STAIRS_DOWN = -2
    WALL = -3
    CEILING = -4
    OUTSIDE = -5


NO_ROOM = -5
"""Room-map value of a cell that lies in no room."""


@dataclass(eq=False)
class SceneObject:
    """An object (Gibson ``class_``), e.g. a sink, inside one room.

    ``grid_min`` / ``grid_max`` are the inclusive ``(row, col)`` bounding box of its footprint.
    """

    id: int
    uuid: int
    name: str
    room_id: int
    room_uuid: int
    location_m: np.ndarray
    size_m: np.ndarray
    grid_min: Cell
    grid_max: Cell
    action_affordance: tuple[str, ...] = ()

    @property
    def key(self) -> str:
        """The unique ID used in missions and prompts, e.g. ``object_27``."""
        return f"object_{self.uuid}"


@dataclass(eq=False)
class Room:
    """A room (Gibson ``scene_category``, e.g. bathroom) on one floor.

    ``door_cells[r]`` holds the ground cells of neighbour room ``r`` (an id) that are 4-adjacent to this
    room, as an ``(n, 2)`` int array of ``(row, col)``. It may exist for rooms that are not connected.
    ``connected_room_ids`` / ``connected_room_uuids`` list the same rooms in the same order.
    A staircase room of floor k is drawn on floor k and k+1 and may connect to rooms of both.
    """

    id: int
    uuid: int
    name: str
    floor: int
    location_m: np.ndarray
    size_m: np.ndarray
    grid_min: Cell
    grid_max: Cell
    connected_room_ids: tuple[int, ...] = ()
    connected_room_uuids: tuple[int, ...] = ()
    door_cells: dict[int, np.ndarray] = field(default_factory=dict)
    objects: dict[int, SceneObject] = field(default_factory=dict)

    @property
    def key(self) -> str:
        """The unique ID used in missions and prompts, e.g. ``room_2``."""
        return f"room_{self.uuid}"

    @property
    def is_staircase(self) -> bool:
        return self.name == "staircase"

    def __repr__(self) -> str:
        doors = ", ".join(f"room_{uuid}" for uuid in self.connected_room_uuids) or "none"
        return (f"<Room {self.key} {self.name} (id {self.id}, floor {self.floor}): "
                f"{count(len(self.objects), 'object')}, connected to {doors}>")


@dataclass(frozen=True)
class StairsEnd:
    """One end of a staircase on a floor: the staircase room and the portal cell where it is taken."""

    room_id: int
    room_uuid: int
    portal: Cell
    cost_m: float
    """Cost of the stairs move between this portal and the matching portal of the adjacent floor."""


@dataclass(eq=False)
class Floor:
    """One floor: its rooms and its rasters.

    ``cat_map`` and ``room_map`` are decoded ``int16`` arrays of shape ``(rows, cols)``.
    ``origin_m`` is the metric ``(x, y)`` of the grid's lower corner and ``resolution_m`` the cell size
    ``(res_x, res_y)`` in metres per cell along rows and columns.
    """

    index: int
    name: str
    uuid: int
    origin_m: tuple[float, float]
    resolution_m: tuple[float, float]
    ground_z_m: float
    cat_map: np.ndarray
    room_map: np.ndarray
    rooms: dict[int, Room] = field(default_factory=dict)
    up_stairs: StairsEnd | None = None
    down_stairs: StairsEnd | None = None

    @property
    def shape(self) -> tuple[int, int]:
        return (int(self.cat_map.shape[0]), int(self.cat_map.shape[1]))

    @property
    def has_maps(self) -> bool:
        """False for a floor read from a source without rasters (a raw 3D Scene Graph ``.npz``).

        Such a floor has ``(0, 0)`` rasters, ``origin_m = (0, 0)``, ``resolution_m = (0, 0)``,
        ``ground_z_m = nan`` and no stairs; its rooms and objects have ``(0, 0)`` grid boxes and no doors.
        """
        return self.cat_map.size > 0

    def undeclared_map_ids(self) -> tuple[list[int], list[int]]:
        """Ids stored in the rasters that the floor does not declare: ``(object ids, room ids)``.

        The cat map may hold the ids of this floor's objects; the room map those of this floor's rooms
        and of the staircase arriving from below (drawn on both floors). Both lists are empty for a
        consistent floor.
        """
        objects = {o for room in self.rooms.values() for o in room.objects}
        rooms = set(self.rooms) | ({self.down_stairs.room_id} if self.down_stairs is not None else set())
        return (
            [i for i in _positive_values(self.cat_map) if i not in objects],
            [i for i in _positive_values(self.room_map) if i not in rooms],
        )

    def __repr__(self) -> str:
        rows, cols = self.shape
        return (f"<Floor {self.index} ({self.name}): {count(len(self.rooms), 'room')}, grid {rows} x {cols} "
                f"cells of {self.resolution_m[0]:g} m>")

    def cell_to_xy(self, cell: Cell) -> tuple[float, float]:
        """Metric centre ``(x, y)`` of a cell."""
        return (
            self.origin_m[0] + (cell[0] + 0.5) * self.resolution_m[0],
            self.origin_m[1] + (cell[1] + 0.5) * self.resolution_m[1],
        )

    def extent_text(self) -> str:
        """``x a..b m, y c..d m``: the metric extent of the floor's grid, for messages."""
        (rows, cols), (x, y), (rx, ry) = self.shape, self.origin_m, self.resolution_m
        return f"x {x:.2f}..{x + rows * rx:.2f} m, y {y:.2f}..{y + cols * ry:.2f} m"

    def xy_to_cell(self, x_m: float, y_m: float) -> Cell:
        """The cell containing metric point ``(x, y)`` (may lie outside the grid)."""
        return (
            int(np.floor((x_m - self.origin_m[0]) / self.resolution_m[0])),
            int(np.floor((y_m - self.origin_m[1]) / self.resolution_m[1])),
        )


def _positive_values(raster: np.ndarray) -> list[int]:
    """The distinct values > 0 of an integer raster, ascending (a histogram: maps are ~0.6 M cells)."""
    positive = raster[raster > 0]
    return np.flatnonzero(np.bincount(positive)).tolist() if positive.size else []


@dataclass(eq=False)
class Building:
    """A building: floors indexed ``0..n-1`` from the lowest, with look-ups by id, uuid and name.

    ``robot_radius_m`` / ``reach_radius_m`` / ``initial_cells`` are the scene's defaults when its folder
    provides them (``radius_config.bash``, ``initial_positions.yaml``), else ``None`` / empty.
    Initial cells are ``(row, col, floor)``.
    """

    id: int
    uuid: int
    name: str
    floors: list[Floor]
    source: Path | None = None
    robot_radius_m: float | None = None
    reach_radius_m: float | None = None
    initial_cells: list[tuple[int, int, int]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self._index()

    def _index(self) -> None:
        """(Re)build the look-up tables; call after mutating rooms or objects.

        Raises :class:`SceneError` if floors are not indexed ``0..n-1`` in order, if two rooms (or two
        objects) share an id, or if two nodes of any type share a uuid: every look-up must be unambiguous.
        """
        self._rooms_by_id: dict[int, Room] = {}
        self._rooms_by_uuid: dict[int, Room] = {}
        self._objects_by_id: dict[int, SceneObject] = {}
        self._objects_by_uuid: dict[int, SceneObject] = {}
        uuid_owner: dict[int, str] = {self.uuid: f"building {self.name!r}"}

        def claim(uuid: int, owner: str) -> None:
            if uuid in uuid_owner:
                raise SceneError(f"building {self.name!r}: {owner} and {uuid_owner[uuid]} share uuid {uuid}")
            uuid_owner[uuid] = owner

        for position, floor in enumerate(self.floors):
            if floor.index != position:
                message = f"building {self.name!r}: floor at position {position} has index {floor.index}"
                raise SceneError(message)
            claim(floor.uuid, f"floor {floor.index}")
            for room in floor.rooms.values():
                if room.id in self._rooms_by_id:
                    raise SceneError(f"building {self.name!r}: two rooms have id {room.id}")
                claim(room.uuid, f"room {room.id}")
                self._rooms_by_id[room.id] = room
                self._rooms_by_uuid[room.uuid] = room
                for obj in room.objects.values():
                    if obj.id in self._objects_by_id:
                        raise SceneError(f"building {self.name!r}: two objects have id {obj.id}")
                    claim(obj.uuid, f"object {obj.id}")
                    self._objects_by_id[obj.id] = obj
                    self._objects_by_uuid[obj.uuid] = obj

    def __repr__(self) -> str:
        rows, cols = self.grid_shape
        rooms, objects = len(self._rooms_by_id), len(self._objects_by_id)
        where = f" from {self.source}" if self.source is not None else ""
        return (f"<Building {self.name!r}: {count(self.num_floors, 'floor')}, {count(rooms, 'room')}, "
                f"{count(objects, 'object')}, grid {rows} x {cols} cells of {self.resolution_m[0]:g} m"
                f"{where}>")

    # -- shape -------------------------------------------------------------------------------------
    @property
    def num_floors(self) -> int:
        return len(self.floors)

    @property
    def grid_shape(self) -> tuple[int, int]:
        """``(rows, cols)``, the same on every floor."""
        return self.floors[0].shape

    @property
    def resolution_m(self) -> tuple[float, float]:
        return self.floors[0].resolution_m

    # -- iteration ---------------------------------------------------------------------------------
    def rooms(self) -> Iterator[Room]:
        """All rooms, floor by floor."""
        for floor in self.floors:
            yield from floor.rooms.values()

    def objects(self) -> Iterator[SceneObject]:
        """All objects, room by room."""
        for room in self.rooms():
            yield from room.objects.values()

    # -- look-ups ----------------------------------------------------------------------------------
    def room(self, *, id: int | None = None, uuid: int | None = None) -> Room:
        """The room with this Gibson id or this uuid; :class:`SceneError` if there is none."""
        table, value, what = (
            (self._rooms_by_id, id, "id") if id is not None else (self._rooms_by_uuid, uuid, "uuid")
        )
        try:
            return table[int(value)]  # type: ignore[arg-type]
        except (KeyError, TypeError):
            raise SceneError(f"building {self.name!r} has no room with {what} {value}") from None

    def object(self, *, id: int | None = None, uuid: int | None = None) -> SceneObject:
        """The object with this Gibson id or this uuid; :class:`SceneError` if there is none."""
        table, value, what = (
            (self._objects_by_id, id, "id") if id is not None else (self._objects_by_uuid, uuid, "uuid")
        )
        try:
            return table[int(value)]  # type: ignore[arg-type]
        except (KeyError, TypeError):
            raise SceneError(f"building {self.name!r} has no object with {what} {value}") from None

    def has_room(self, uuid: int) -> bool:
        return uuid in self._rooms_by_uuid

    def has_object(self, uuid: int) -> bool:
        return uuid in self._objects_by_uuid

    def rooms_named(self, name: str, floor: int | None = None) -> list[Room]:
        """Rooms whose category equals ``name`` (case-insensitive), optionally on one floor."""
        name = name.lower()
        return [r for r in self.rooms() if r.name.lower() == name and (floor is None or r.floor == floor)]

    def objects_named(self, name: str, room_uuid: int | None = None) -> list[SceneObject]:
        """Objects whose class equals ``name`` (case-insensitive), optionally inside one room."""
        name = name.lower()
        return [
            o
            for o in self.objects()
            if o.name.lower() == name and (room_uuid is None or o.room_uuid == room_uuid)
        ]

    def floor_of_object(self, obj: SceneObject) -> int:
        return self._rooms_by_id[obj.room_id].floor
