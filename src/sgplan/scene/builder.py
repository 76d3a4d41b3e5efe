"""Build one's own building in code: floors, rooms (polygons, boxes or rasters), objects (boxes), doors
and staircases. The result is an ordinary :class:`~sgplan.scene.model.Building` that plans, draws and
round-trips through sgplan's native format like a loaded scene.

>>> b = BuildingBuilder("flat", size_m=(6.0, 4.0))            # 0.05 m cells, origin (0, 0)
>>> f = b.add_floor()
>>> hall = b.add_room(f, "corridor", box=(0.0, 0.0, 6.0, 1.5))
>>> kitchen = b.add_room(f, "kitchen", box=(0.0, 1.5, 3.0, 4.0))
>>> b.add_door(hall, kitchen, at=(1.5, 1.5))
>>> b.add_object(kitchen, "sink", box=(0.3, 3.4, 0.9, 3.9), height_m=0.9)  # doctest: +ELLIPSIS
1
>>> building = b.build()

Conventions (:mod:`sgplan.scene.model`): metric ``x`` runs along grid rows, ``y`` along columns; a box is
``(x0, y0, x1, y1)`` in metres and holds the cells whose centres lie inside it; a polygon is a sequence
of ``(x, y)`` vertices, holding the cells whose centres lie inside it. Every room gets a wall of
``wall_m`` on its inside edge (so two touching rooms are separated by ``2 * wall_m``, and a door opening
is cut through both); the cells of no room are outside. Door cells and room connections are derived
from the rasters (:func:`sgplan.scene.doors.door_cells`); uuids are assigned: building 1, then the floors,
the rooms and the objects in the order they were added. Ids (rooms 1.., objects 1..) are returned by the
``add_*`` methods. Every input is checked, with a :class:`~sgplan.errors.SceneError` naming what is
wrong; numpy numbers are accepted wherever numbers are.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from matplotlib.path import Path as Polygon
from scipy import ndimage

from sgplan.errors import SceneError
from sgplan.scene.doors import connections, door_cells
from sgplan.scene.fields import is_number
from sgplan.scene.grid import floor_heights_m
from sgplan.scene.model import NO_ROOM, Building, CatCode, Floor, Room, SceneObject, StairsEnd

DEFAULT_FLOOR_GAP_M = 3.0
ROOM_HEIGHT_M = 2.8
STAIRS_COST_FACTOR = 1.5
"""Default stairs cost: this many times the 3-D distance between the portals (a stair is no straight line)."""


@dataclass
class _Room:
    id: int
    name: str
    floor: int
    mask: np.ndarray


@dataclass
class _Object:
    id: int
    room: int
    name: str
    mask: np.ndarray
    box_m: tuple[float, float, float, float]
    height_m: float
    affordances: tuple[str, ...]


@dataclass
class _Stairs:
    room: int
    lower_portal_m: tuple[float, float]
    upper_portal_m: tuple[float, float]
    steps: np.ndarray | None
    cost_m: float | None


@dataclass
class _Door:
    a: int
    b: int
    at_m: tuple[float, float]
    width_m: float


@dataclass
class BuildingBuilder:
    """Collects a building's parts, checks each as it is added, and assembles them in :meth:`build`.

    Parameters
    ----------
    name:
        the building's name.
    size_m:
        ``(x, y)`` extent in metres of every floor's grid.
    resolution_m:
        cell size in metres (square cells).
    origin_m:
        metric ``(x, y)`` of the grid's lower corner.
    wall_m:
        wall thickness inside each room's edge, metres (at least one cell is used).
    robot_radius_m, reach_radius_m:
        the scene's default radii (metres), or ``None``.
    """

    name: str
    size_m: tuple[float, float]
    resolution_m: float = 0.05
    origin_m: tuple[float, float] = (0.0, 0.0)
    wall_m: float = 0.1
    robot_radius_m: float | None = None
    reach_radius_m: float | None = None
    _floors: list[tuple[str, float]] = field(default_factory=list, init=False)
    _rooms: dict[int, _Room] = field(default_factory=dict, init=False)
    _objects: list[_Object] = field(default_factory=list, init=False)
    _doors: list[_Door] = field(default_factory=list, init=False)
    _stairs: dict[int, _Stairs] = field(default_factory=dict, init=False)
    _starts: list[tuple[int, int, int]] = field(default_factory=list, init=False)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise SceneError(f"building name must be a non-empty string, got {self.name!r}")
        self.size_m = _pair(self.size_m, "size_m", positive=True)
        self.origin_m = _pair(self.origin_m, "origin_m")
        self.resolution_m = _number(self.resolution_m, "resolution_m", positive=True)
        self.wall_m = _number(self.wall_m, "wall_m", positive=True)
        for what in ("robot_radius_m", "reach_radius_m"):
            if getattr(self, what) is not None:
                setattr(self, what, _number(getattr(self, what), what, positive=what == "reach_radius_m"))
        self.shape = (math.ceil(self.size_m[0] / self.resolution_m - 1e-9),
                      math.ceil(self.size_m[1] / self.resolution_m - 1e-9))
        rows, cols = np.meshgrid(np.arange(self.shape[0]), np.arange(self.shape[1]), indexing="ij")
        self._centres = np.column_stack([self.origin_m[0] + (rows.ravel() + 0.5) * self.resolution_m,
                                         self.origin_m[1] + (cols.ravel() + 0.5) * self.resolution_m])

    # -- parts ---------------------------------------------------------------------------------------

    def add_floor(self, *, ground_z_m: float | None = None, name: str | None = None) -> int:
        """Add the next floor up; returns its index. ``ground_z_m`` defaults to 3 m above the one below."""
        index = len(self._floors)
        if ground_z_m is None:
            ground_z_m = self._floors[-1][1] + DEFAULT_FLOOR_GAP_M if self._floors else 0.0
        z = _number(ground_z_m, f"floor {index} ground_z_m")
        if self._floors and z <= self._floors[-1][1]:
            raise SceneError(f"floor {index}: ground_z_m {z} m must be above floor {index - 1}'s "
                             f"{self._floors[-1][1]} m")
        self._floors.append((name or chr(ord("A") + index % 26), z))
        return index

    def add_room(self, floor: int, name: str, *, box: Sequence[float] | None = None,
                 polygon: Sequence[Sequence[float]] | None = None, cells: np.ndarray | None = None) -> int:
        """Add a room on ``floor`` given by exactly one of ``box``, ``polygon`` or ``cells`` (a bool raster
        of the grid's shape); returns its id. It may not overlap another room of the floor."""
        floor = self._floor(floor)
        what = f"room {len(self._rooms) + 1} ({name!r})"
        if not isinstance(name, str) or not name.strip():
            raise SceneError(f"{what}: the category name must be a non-empty string")
        mask = self._region(what, box=box, polygon=polygon, cells=cells)
        self._check_free(what, floor, mask)
        room_id = len(self._rooms) + 1
        self._rooms[room_id] = _Room(room_id, name.strip(), floor, mask)
        return room_id

    def add_object(self, room: int, name: str, *, box: Sequence[float], height_m: float = 1.0,
                   affordances: Sequence[str] = ()) -> int:
        """Add an object standing in ``room`` with footprint ``box`` (inside the room); returns its id."""
        host = self._room(room)
        what = f"object {len(self._objects) + 1} ({name!r})"
        if not isinstance(name, str) or not name.strip():
            raise SceneError(f"{what}: the class name must be a non-empty string")
        mask = self._region(what, box=box)
        if (mask & ~host.mask).any():
            raise SceneError(f"{what}: box {tuple(box)} reaches outside room {room} ({host.name})")
        taken = [o.id for o in self._objects if o.room == room and (o.mask & mask).any()]
        if taken:
            raise SceneError(f"{what}: box {tuple(box)} overlaps object {taken[0]}")
        if not all(isinstance(a, str) for a in affordances):
            raise SceneError(f"{what}: affordances must be strings")
        object_id = len(self._objects) + 1
        self._objects.append(
            _Object(
                object_id, room, name.strip(), mask, _box(box, what),
                _number(height_m, f"{what} height_m", positive=True), tuple(affordances),
            )
        )
        return object_id

    def add_door(self, room_a: int, room_b: int, *, at: Sequence[float], width_m: float = 0.9) -> None:
        """Open a door of ``width_m`` between two rooms at metric point ``at`` on the wall between them."""
        a, b = self._room(room_a), self._room(room_b)
        if room_a == room_b:
            raise SceneError(f"door: room {room_a} cannot have a door to itself")
        if not self._floors_of(a) & self._floors_of(b):
            raise SceneError(
                f"door: rooms {room_a} (floor {a.floor}) and {room_b} (floor {b.floor}) share no floor"
            )
        self._doors.append(
            _Door(room_a, room_b, _pair(at, "door at"), _number(width_m, "door width_m", positive=True))
        )

    def add_staircase(
        self, floor: int, *, portal: Sequence[float], upper_portal: Sequence[float] | None = None,
        box: Sequence[float] | None = None, polygon: Sequence[Sequence[float]] | None = None,
        cells: np.ndarray | None = None, steps: Sequence[float] | None = None, cost_m: float | None = None,
    ) -> int:
        """Add a staircase room from ``floor`` to the floor above (drawn on both); returns its room id.

        ``portal`` / ``upper_portal`` (default: the same point) are the metric points where the stairs are
        taken on the lower / upper floor; ``steps`` an optional box of stair cells (obstacles);
        ``cost_m`` the cost of taking the stairs (default :data:`STAIRS_COST_FACTOR` times the 3-D distance).
        """
        floor = self._floor(floor)
        if floor + 1 >= len(self._floors):
            raise SceneError(f"staircase from floor {floor}: add floor {floor + 1} first")
        if floor in self._stairs:
            raise SceneError(f"floor {floor} already has a staircase up (one per pair of floors)")
        room_id = self.add_room(floor, "staircase", box=box, polygon=polygon, cells=cells)
        mask = self._rooms[room_id].mask
        try:
            self._check_free(f"staircase {room_id}", floor + 1, mask)
        except SceneError:
            del self._rooms[room_id]
            raise
        lower = _pair(portal, "staircase portal")
        upper = _pair(upper_portal, "staircase upper_portal") if upper_portal is not None else lower
        for point, which in ((lower, "portal"), (upper, "upper_portal")):
            cell = self._cell(point)
            if cell is None or not mask[cell]:
                del self._rooms[room_id]
                raise SceneError(f"staircase {room_id}: {which} {point} lies outside the staircase")
        step_mask = self._region(f"staircase {room_id} steps", box=steps) if steps is not None else None
        if step_mask is not None and (step_mask & ~mask).any():
            del self._rooms[room_id]
            raise SceneError(f"staircase {room_id}: steps {tuple(steps or ())} reach outside the staircase")
        cost = _number(cost_m, f"staircase {room_id} cost_m", positive=True) if cost_m is not None else None
        self._stairs[floor] = _Stairs(room_id, lower, upper, step_mask, cost)
        return room_id

    def add_start(self, x_m: float, y_m: float, floor: int) -> tuple[int, int, int]:
        """Add an initial position (``Building.initial_cells``) at a metric point; returns its cell."""
        cell = self._cell(_pair((x_m, y_m), "start"))
        if cell is None:
            raise SceneError(f"start ({x_m}, {y_m}) lies off the grid")
        start = (cell[0], cell[1], self._floor(floor))
        self._starts.append(start)
        return start

    # -- assembly ------------------------------------------------------------------------------------

    def build(self) -> Building:
        """The building. Raises :class:`SceneError` for no floors, a door that opens no passage (its point
        is not on the wall between its rooms), a portal or start on a wall or object, or a stairs cost
        below the straight-line distance the planner's heuristics assume."""
        if not self._floors:
            raise SceneError(f"building {self.name!r} has no floors: call add_floor()")
        cats, rooms_maps = self._rasters()
        doors = [door_cells(room_map, cat) for room_map, cat in zip(rooms_maps, cats)]
        for door in self._doors:
            if not any((door.a, door.b) in floor_doors for floor_doors in doors):
                raise SceneError(f"door between rooms {door.a} and {door.b} at {door.at_m} opens no passage: "
                                 "put its point on the wall between them (or widen it)")
        uuid = iter(range(2, 2 + len(self._floors) + len(self._rooms) + len(self._objects)))
        floor_uuids = [next(uuid) for _ in self._floors]
        room_uuids = {room_id: next(uuid) for room_id in self._rooms}
        rooms = {room_id: self._make_room(room, room_uuids, doors) for room_id, room in self._rooms.items()}
        for obj in self._objects:
            rooms[obj.room].objects[obj.id] = self._make_object(obj, next(uuid), room_uuids[obj.room])
        floors = [
            Floor(index=k, name=name, uuid=floor_uuids[k], origin_m=self.origin_m,
                  resolution_m=(self.resolution_m, self.resolution_m), ground_z_m=z,
                  cat_map=cats[k].astype(np.int16), room_map=rooms_maps[k].astype(np.int16),
                  rooms={i: rooms[i] for i, room in self._rooms.items() if room.floor == k})
            for k, (name, z) in enumerate(self._floors)
        ]
        building = Building(id=1, uuid=1, name=self.name, floors=floors, robot_radius_m=self.robot_radius_m,
                            reach_radius_m=self.reach_radius_m, initial_cells=list(self._starts))
        self._attach_stairs(building, room_uuids)
        for start in self._starts:
            if (
                cats[start[2]][start[0], start[1]] != CatCode.GROUND
                or rooms_maps[start[2]][start[0], start[1]] <= 0
            ):
                raise SceneError(f"start cell {start} lies on a wall, an object or outside every room")
        return building

    def _rasters(self) -> tuple[list[np.ndarray], list[np.ndarray]]:
        cats = [np.full(self.shape, CatCode.OUTSIDE, dtype=np.int16) for _ in self._floors]
        room_maps = [np.full(self.shape, NO_ROOM, dtype=np.int16) for _ in self._floors]
        half = max(1, round(self.wall_m / self.resolution_m))
        for room in self._rooms.values():
            inner = ndimage.binary_erosion(room.mask, iterations=half, border_value=0)
            for k in self._floors_of(room):
                room_maps[k][room.mask] = room.id
                cats[k][room.mask] = CatCode.WALL
                cats[k][inner] = CatCode.GROUND
        for door in self._doors:
            x, y = door.at_m
            r = door.width_m / 2
            opening = self._region("door", box=(x - r, y - r, x + r, y + r), allow_empty=True)
            for k in self._floors_of(self._rooms[door.a]) & self._floors_of(self._rooms[door.b]):
                cut = opening & np.isin(room_maps[k], (door.a, door.b)) & (cats[k] == CatCode.WALL)
                cats[k][cut] = CatCode.GROUND
        for floor, stairs in self._stairs.items():
            if stairs.steps is not None:
                cats[floor][stairs.steps] = CatCode.STAIRS_UP
                cats[floor + 1][stairs.steps] = CatCode.STAIRS_DOWN
        for obj in self._objects:
            cats[self._rooms[obj.room].floor][obj.mask] = obj.id
        return cats, room_maps

    def _make_room(
        self, room: _Room, uuids: dict[int, int], doors: list[dict[tuple[int, int], np.ndarray]]
    ) -> Room:
        linked = sorted(connections(doors).get(room.id, set()))
        rows, cols = np.nonzero(room.mask)
        lo, hi = (int(rows.min()), int(cols.min())), (int(rows.max()), int(cols.max()))
        z = self._floors[room.floor][1]
        return Room(
            id=room.id, uuid=uuids[room.id], name=room.name, floor=room.floor,
            location_m=np.array([*self._centre(lo, hi), z + ROOM_HEIGHT_M / 2]),
            size_m=np.array([(hi[0] - lo[0] + 1) * self.resolution_m, (hi[1] - lo[1] + 1) * self.resolution_m,
                             ROOM_HEIGHT_M]),
            grid_min=lo, grid_max=hi, connected_room_ids=tuple(linked),
            connected_room_uuids=tuple(uuids[i] for i in linked),
            door_cells={b: cells for d in doors for (a, b), cells in d.items() if a == room.id},
        )

    def _make_object(self, obj: _Object, uuid: int, room_uuid: int) -> SceneObject:
        rows, cols = np.nonzero(obj.mask)
        x0, y0, x1, y1 = obj.box_m
        z = self._floors[self._rooms[obj.room].floor][1]
        return SceneObject(
            id=obj.id, uuid=uuid, name=obj.name, room_id=obj.room, room_uuid=room_uuid,
            location_m=np.array([(x0 + x1) / 2, (y0 + y1) / 2, z + obj.height_m / 2]),
            size_m=np.array([x1 - x0, y1 - y0, obj.height_m]),
            grid_min=(int(rows.min()), int(cols.min())), grid_max=(int(rows.max()), int(cols.max())),
            action_affordance=obj.affordances,
        )

    def _attach_stairs(self, building: Building, uuids: dict[int, int]) -> None:
        heights = floor_heights_m(building)
        for floor, stairs in sorted(self._stairs.items()):
            ends = []
            for k, point in ((floor, stairs.lower_portal_m), (floor + 1, stairs.upper_portal_m)):
                cell = self._cell(point)
                assert cell is not None  # checked in add_staircase
                if building.floors[k].cat_map[cell] != CatCode.GROUND:
                    raise SceneError(
                        f"staircase {stairs.room}: the portal {point} on floor {k} lies on a wall, the "
                        "steps or an object; move it onto the landing"
                    )
                ends.append(cell)
            d_xy = math.hypot(
                (ends[0][0] - ends[1][0]) * self.resolution_m, (ends[0][1] - ends[1][1]) * self.resolution_m
            )
            floor_gap = self._floors[floor + 1][1] - self._floors[floor][1]
            shortest = math.hypot(d_xy, float(heights[floor + 1] - heights[floor]))
            cost = (
                stairs.cost_m
                if stairs.cost_m is not None
                else STAIRS_COST_FACTOR * math.hypot(d_xy, floor_gap)
            )
            if cost < shortest:
                raise SceneError(
                    f"staircase {stairs.room}: cost {cost} m is below the straight-line distance "
                    f"{shortest:.3f} m between its portals; give a larger cost_m"
                )
            for k, cell, attribute in ((floor, ends[0], "up_stairs"), (floor + 1, ends[1], "down_stairs")):
                setattr(
                    building.floors[k], attribute,
                    StairsEnd(room_id=stairs.room, room_uuid=uuids[stairs.room], portal=cell, cost_m=cost),
                )

    # -- checks and geometry -------------------------------------------------------------------------

    def _floor(self, floor: int) -> int:
        if not (is_number(floor) and float(floor).is_integer() and 0 <= int(floor) < len(self._floors)):
            raise SceneError(
                f"no floor {floor!r}: floors are 0..{len(self._floors) - 1} (add_floor() adds one)"
            )
        return int(floor)

    def _room(self, room: int) -> _Room:
        if not is_number(room) or int(room) not in self._rooms:
            raise SceneError(f"no room {room!r}: rooms are {sorted(self._rooms)} (add_room() returns the id)")
        return self._rooms[int(room)]

    def _floors_of(self, room: _Room) -> set[int]:
        """The floors a room is drawn on: its own, and the one above for a staircase."""
        return (
            {room.floor, room.floor + 1}
            if room.floor in self._stairs and self._stairs[room.floor].room == room.id
            else {room.floor}
        )

    def _check_free(self, what: str, floor: int, mask: np.ndarray) -> None:
        for other in self._rooms.values():
            if floor in self._floors_of(other) and (other.mask & mask).any():
                raise SceneError(f"{what} overlaps room {other.id} ({other.name}) on floor {floor} in "
                                 f"{int((other.mask & mask).sum())} cells")

    def _region(self, what: str, *, box: Sequence[float] | None = None,
                polygon: Sequence[Sequence[float]] | None = None, cells: np.ndarray | None = None,
                allow_empty: bool = False) -> np.ndarray:
        given = [v is not None for v in (box, polygon, cells)]
        if sum(given) != 1:
            raise SceneError(f"{what}: give exactly one of box, polygon or cells")
        if cells is not None:
            mask = np.asarray(cells)
            if mask.shape != self.shape or mask.dtype != bool:
                raise SceneError(f"{what}: cells must be a bool array of the grid's shape {self.shape}, "
                                 f"got {mask.dtype} {mask.shape}")
            mask = mask.copy()
        elif box is not None:
            x0, y0, x1, y1 = _box(box, what)
            x, y = self._centres[:, 0], self._centres[:, 1]
            mask = ((x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)).reshape(self.shape)
        else:
            vertices = np.asarray(polygon, dtype=object)
            if vertices.ndim != 2 or vertices.shape[1] != 2 or len(vertices) < 3 or \
                    not all(is_number(v) and math.isfinite(float(v)) for v in vertices.ravel()):
                raise SceneError(f"{what}: a polygon is three or more (x, y) points in metres")
            mask = Polygon(vertices.astype(float)).contains_points(self._centres).reshape(self.shape)
        if not mask.any() and not allow_empty:
            raise SceneError(f"{what}: the region holds no cell of the {self.shape[0]}x{self.shape[1]} grid "
                             f"(cells of {self.resolution_m} m from {self.origin_m})")
        return mask

    def _cell(self, point: tuple[float, float]) -> tuple[int, int] | None:
        row = math.floor((point[0] - self.origin_m[0]) / self.resolution_m)
        col = math.floor((point[1] - self.origin_m[1]) / self.resolution_m)
        return (row, col) if 0 <= row < self.shape[0] and 0 <= col < self.shape[1] else None

    def _centre(self, lo: tuple[int, int], hi: tuple[int, int]) -> tuple[float, float]:
        return (self.origin_m[0] + (lo[0] + hi[0] + 1) / 2 * self.resolution_m,
                self.origin_m[1] + (lo[1] + hi[1] + 1) / 2 * self.resolution_m)


def _number(value: object, what: str, *, positive: bool = False) -> float:
    if not is_number(value) or not math.isfinite(float(value)) or (positive and float(value) <= 0):  # type: ignore[arg-type]
        raise SceneError(f"{what} must be a finite number{' > 0' if positive else ''}, got {value!r}")
    return float(value)  # type: ignore[arg-type]


def _pair(value: object, what: str, *, positive: bool = False) -> tuple[float, float]:
    if not isinstance(value, (Sequence, np.ndarray)) or len(value) != 2:
        raise SceneError(f"{what} must be a pair of numbers (x, y) in metres, got {value!r}")
    return (_number(value[0], what, positive=positive), _number(value[1], what, positive=positive))


def _box(value: object, what: str) -> tuple[float, float, float, float]:
    if not isinstance(value, (Sequence, np.ndarray)) or len(value) != 4:
        raise SceneError(f"{what}: a box is (x0, y0, x1, y1) in metres, got {value!r}")
    x0, y0, x1, y1 = (_number(v, f"{what} box") for v in value)
    if x1 <= x0 or y1 <= y0:
        raise SceneError(f"{what}: box {tuple(value)} needs x0 < x1 and y0 < y1")
    return (x0, y0, x1, y1)
