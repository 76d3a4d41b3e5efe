"""Procedural buildings: real :class:`~sgplan.scene.model.Building` values generated from a seed.

Each floor is a rectangular house plan: a corridor runs along the middle, ordinary rooms line both sides
of it, every room has a door onto the corridor (optionally also to its neighbour), and staircases sit at
the corridor's left end. Staircase ``k`` joins floor ``k`` to ``k+1``: it is one room drawn on both floors
(stairs cells ``STAIRS_UP`` below, ``STAIRS_DOWN`` above) with a landing by its door holding the portal.
Objects with Gibson / COCO class names (``refrigerator``, ``bed``, ``toilet``, ...) stand inside rooms,
mostly against walls, never in front of doors.

Everything the loaders produce is produced here too, and consistently: ``door_cells`` and connections
are derived from the rasters (4-adjacent cells of two rooms, i.e. the door openings), uuids follow the
authors' rule (building 1; then rooms in id order, each floor's uuid right after its first room; then
objects), and each stairs cost is at least the 3-D Euclidean distance between its portals in the frame
of :func:`sgplan.scene.grid.floor_heights_m`, so Euclidean heuristics stay admissible.

The same seed always gives the same building (NumPy's ``default_rng``).

Public entry points: :func:`generate_building` (sizes chosen by the caller) and :func:`building_from_specs`
(the rooms chosen by the caller; the tests' tiny random buildings are made with it).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from sgplan.errors import SceneError
from sgplan.scene.doors import connections, door_cells
from sgplan.scene.model import NO_ROOM, Building, CatCode, Floor, Room, SceneObject, StairsEnd

# --- catalogues ----------------------------------------------------------------------------------------

OBJECT_SIZES_M: dict[str, tuple[float, float, float]] = {
    # class: (length, width, height) in metres; footprints are length x width, either orientation.
    "bed": (2.0, 1.5, 0.6),
    "couch": (2.0, 0.9, 0.8),
    "tv": (1.2, 0.4, 1.0),
    "refrigerator": (0.75, 0.7, 1.8),
    "oven": (0.6, 0.6, 0.9),
    "microwave": (0.5, 0.4, 0.3),
    "sink": (0.6, 0.5, 0.9),
    "toilet": (0.7, 0.45, 0.8),
    "dining table": (1.6, 0.9, 0.75),
    "chair": (0.5, 0.5, 0.9),
    "potted plant": (0.45, 0.45, 1.0),
    "vase": (0.3, 0.3, 0.5),
    "book": (0.3, 0.25, 0.05),
    "bottle": (0.2, 0.2, 0.3),
    "bowl": (0.3, 0.3, 0.1),
    "clock": (0.3, 0.2, 0.3),
    "laptop": (0.4, 0.3, 0.05),
    "teddy bear": (0.35, 0.3, 0.4),
    "bench": (1.4, 0.45, 0.45),
    "washing machine": (0.65, 0.6, 0.85),
}
"""Object classes the generator knows, with their footprint and height."""

ROOM_OBJECTS: dict[str, tuple[str, ...]] = {
    "kitchen": ("refrigerator", "oven", "sink", "microwave", "bowl", "bottle"),
    "living_room": ("couch", "tv", "potted plant", "vase", "clock", "book"),
    "dining_room": ("dining table", "chair", "chair", "vase", "bowl"),
    "bedroom": ("bed", "chair", "book", "clock", "teddy bear"),
    "bathroom": ("toilet", "sink", "bottle"),
    "home_office": ("chair", "laptop", "book", "potted plant"),
    "utility_room": ("washing machine", "sink", "bottle"),
    "lobby": ("bench", "potted plant", "clock"),
}
"""Room categories (Gibson ``scene_category`` names) and the object classes that belong in them."""

_ROOM_WIDTH_M = {
    "kitchen": 3.4,
    "living_room": 4.6,
    "dining_room": 3.6,
    "bedroom": 3.6,
    "bathroom": 2.2,
    "home_office": 3.0,
    "utility_room": 2.2,
    "lobby": 3.0,
}
_WALL_SIDE = {"dining table": False, "chair": False}  # free-standing; everything else stands at a wall


# --- plan ------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class RoomSpec:
    """An ordinary room to place: its category and the classes of the objects inside, in order."""

    category: str
    objects: tuple[str, ...] = ()
    width_m: float | None = None
    """Wall-to-wall width along the corridor; ``None`` for the category's typical width."""


@dataclass(frozen=True)
class Dimensions:
    """Lengths of the plan in metres (converted to whole cells, at least one each)."""

    band_depth_m: float = 4.0
    """Depth of the rooms on each side of the corridor."""
    corridor_m: float = 1.4
    outer_wall_m: float = 0.15
    inner_wall_m: float = 0.1
    door_m: float = 0.9
    margin_m: float = 0.3
    """Outside space around the building."""
    stairs_width_m: float = 2.4
    landing_m: float = 1.0
    floor_gap_m: tuple[float, float] = (2.8, 3.1)
    """Range of the height between consecutive floors' ground."""
    internal_door_probability: float = 0.35
    """Chance that two neighbouring rooms on the same side of the corridor share a door."""
    corridor_door_probability: float = 1.0
    """Chance that a room has a door onto the corridor (below 1, some rooms may be unreachable)."""


@dataclass
class _Box:
    """Half-open cell box ``rows [r0, r1) x cols [c0, c1)``."""

    r0: int
    r1: int
    c0: int
    c1: int

    def slices(self) -> tuple[slice, slice]:
        return slice(self.r0, self.r1), slice(self.c0, self.c1)


@dataclass
class _PlacedRoom:
    id: int
    category: str
    floor: int
    box: _Box
    objects: tuple[str, ...] = ()
    placed_objects: list[tuple[str, _Box]] = field(default_factory=list)
    upper_box: _Box | None = None
    """For a staircase: its box on the floor above (the same cells)."""


def _cells(length_m: float, cell_m: float, minimum: int = 1) -> int:
    return max(minimum, round(length_m / cell_m))


class _Planner:
    """Lays out floors on a shared grid and paints their rasters."""

    def __init__(self, rng: np.random.Generator, cell_m: float, dims: Dimensions) -> None:
        self.rng = rng
        self.cell_m = cell_m
        self.dims = dims
        self.margin = _cells(dims.margin_m, cell_m)
        self.outer = _cells(dims.outer_wall_m, cell_m)
        self.inner = _cells(dims.inner_wall_m, cell_m)
        self.corridor = _cells(dims.corridor_m, cell_m, 2)
        self.depth = _cells(dims.band_depth_m, cell_m, 3)
        self.door = _cells(dims.door_m, cell_m)
        self.stairs_width = _cells(dims.stairs_width_m, cell_m, 3)
        self.landing = _cells(dims.landing_m, cell_m, 1)
        # Rows: margin | outer wall | top band | wall | corridor | wall | bottom band | outer wall | margin.
        self.top = _Box(self.margin + self.outer, self.margin + self.outer + self.depth, 0, 0)
        corridor_r0 = self.top.r1 + self.inner
        self.corridor_rows = (corridor_r0, corridor_r0 + self.corridor)
        bottom_r0 = self.corridor_rows[1] + self.inner
        self.bottom = _Box(bottom_r0, bottom_r0 + self.depth, 0, 0)
        self.rows = self.bottom.r1 + self.outer + self.margin

    # -- widths ------------------------------------------------------------------------------------
    def room_width(self, spec: RoomSpec) -> int:
        base = spec.width_m if spec.width_m is not None else _ROOM_WIDTH_M.get(spec.category, 3.0)
        jitter = 1.0 if spec.width_m is not None else float(self.rng.uniform(0.85, 1.15))
        return _cells(base * jitter, self.cell_m, 3)

    def split_bands(
        self, specs: Sequence[RoomSpec], slots: tuple[bool, bool]
    ) -> tuple[list[tuple[RoomSpec, int]], list[tuple[RoomSpec, int]]]:
        """Assign rooms to the top / bottom band, balancing the band widths (stair slots included)."""
        bands: tuple[list[tuple[RoomSpec, int]], list[tuple[RoomSpec, int]]] = ([], [])
        widths = [self.stairs_width + self.inner if slot else 0 for slot in slots]
        for spec in specs:
            width = self.room_width(spec)
            side = 0 if widths[0] <= widths[1] else 1
            bands[side].append((spec, width))
            widths[side] += width + self.inner
        return bands

    def band_width(self, band: list[tuple[RoomSpec, int]], slot: bool) -> int:
        parts = [w for _, w in band] + ([self.stairs_width] if slot else [])
        return sum(parts) + self.inner * max(0, len(parts) - 1)

    # -- painting ------------------------------------------------------------------------------------
    def door_span(self, lo: int, hi: int) -> tuple[int, int]:
        """A door opening ``[start, stop)`` inside ``[lo, hi)``, one cell clear of each end if possible."""
        if hi - lo <= 2:
            return lo, hi
        width = max(1, min(self.door, hi - lo - 2))
        start = int(self.rng.integers(lo + 1, hi - width))
        return start, start + width


def _paint_door(
    cat: np.ndarray, room: np.ndarray, cells: _Box, near_id: int, far_id: int, split_rows: bool
) -> None:
    """Open a wall: GROUND cells, the half nearer each room assigned to it (so the rooms touch)."""
    r, c = cells.slices()
    cat[r, c] = CatCode.GROUND
    if split_rows:
        mid = cells.r0 + (cells.r1 - cells.r0 + 1) // 2
        room[cells.r0 : mid, c] = near_id
        room[mid : cells.r1, c] = far_id
    else:
        mid = cells.c0 + (cells.c1 - cells.c0 + 1) // 2
        room[r, cells.c0 : mid] = near_id
        room[r, mid : cells.c1] = far_id


def _reserve_front(reserved: np.ndarray, opening: _Box, depth: int, pad: int) -> None:
    """Keep objects out of the area in front of (and around) a door opening."""
    reserved[
        max(0, opening.r0 - depth) : opening.r1 + depth, max(0, opening.c0 - pad) : opening.c1 + pad
    ] = True


def _place_objects(
    rng: np.random.Generator, cat: np.ndarray, reserved: np.ndarray, room: _PlacedRoom, cell_m: float
) -> None:
    """Put the room's objects on free ground inside its box, against walls where that is natural."""
    box = room.box
    for name in room.objects:
        length, width, _ = OBJECT_SIZES_M[name]
        size = (_cells(length, cell_m), _cells(width, cell_m))
        for _ in range(24):
            h, w = size if rng.random() < 0.5 else size[::-1]
            if h > box.r1 - box.r0 or w > box.c1 - box.c0:
                continue
            r0 = int(rng.integers(box.r0, box.r1 - h + 1))
            c0 = int(rng.integers(box.c0, box.c1 - w + 1))
            if _WALL_SIDE.get(name, True):
                side = int(rng.integers(4))
                if side == 0:
                    r0 = box.r0
                elif side == 1:
                    r0 = box.r1 - h
                elif side == 2:
                    c0 = box.c0
                else:
                    c0 = box.c1 - w
            # One cell of clearance around the object keeps objects apart and the room walkable.
            around = (
                slice(max(box.r0, r0 - 1), min(box.r1, r0 + h + 1)),
                slice(max(box.c0, c0 - 1), min(box.c1, c0 + w + 1)),
            )
            if reserved[around].any() or (cat[around] != CatCode.GROUND).any():
                continue
            placed = _Box(r0, r0 + h, c0, c0 + w)
            room.placed_objects.append((name, placed))
            reserved[around] = True
            cat[placed.slices()] = -1000  # provisional marker; object ids are written once known
            break


@dataclass
class _FloorPlan:
    cat: np.ndarray
    room: np.ndarray
    rooms: list[_PlacedRoom]


def _build(
    name: str,
    floor_specs: Sequence[Sequence[RoomSpec]],
    cell_m: float,
    seed: int | np.random.Generator,
    dims: Dimensions,
    robot_radius_m: float | None,
    reach_radius_m: float | None,
) -> Building:
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    _check_specs(floor_specs, cell_m)
    plan = _Planner(rng, cell_m, dims)
    layout = _Layout.of(plan, floor_specs)
    stair_rooms: dict[int, _PlacedRoom] = {}
    floors = [_plan_floor(plan, layout, f, stair_rooms) for f in range(len(floor_specs))]
    plans = [floor.plan for floor in floors]
    for floor in floors:
        for placed in floor.plan.rooms:
            _place_objects(rng, floor.plan.cat, floor.reserved, placed, cell_m)
    for k, stair in sorted(stair_rooms.items()):
        plans[k].rooms.append(stair)
    return _assemble(name, plans, stair_rooms, plan, cell_m, rng, dims, robot_radius_m, reach_radius_m)


def _check_specs(floor_specs: Sequence[Sequence[RoomSpec]], cell_m: float) -> None:
    if not floor_specs:
        raise SceneError("a synthetic building needs at least one floor")
    if not (np.isfinite(cell_m) and cell_m > 0):
        raise SceneError(f"cell size must be a positive number of metres, got {cell_m}")
    for specs in floor_specs:
        for spec in specs:
            if spec.category == "staircase" or spec.category == "corridor":
                raise SceneError(
                    f"room category {spec.category!r} is generated automatically; do not list it"
                )
            unknown = [o for o in spec.objects if o not in OBJECT_SIZES_M]
            if unknown:
                raise SceneError(f"unknown object class(es) {unknown} for a {spec.category}")


_Band = list[tuple[RoomSpec, int]]
"""Rooms of one band (top or bottom of the corridor) with their widths in cells."""


@dataclass(frozen=True)
class _Layout:
    """Where everything goes: the grid shape, the first column inside the outer wall and the inner width
    (the same on every floor), per floor the staircase slots (top, bottom) and the two bands of rooms,
    and the room ids (each floor's first id; each staircase's id)."""

    floor_specs: Sequence[Sequence[RoomSpec]]
    shape: tuple[int, int]
    c_start: int
    inner_width: int
    slots: list[tuple[bool, bool]]
    bands: list[tuple[_Band, _Band]]
    base_ids: np.ndarray
    stair_ids: list[int]

    @classmethod
    def of(cls, plan: _Planner, floor_specs: Sequence[Sequence[RoomSpec]]) -> _Layout:
        num_floors = len(floor_specs)
        # Staircase k (floors k and k+1) uses slot k % 2: top-left, then bottom-left, alternating.
        slots = [
            (
                any(k % 2 == 0 for k in (f - 1, f) if 0 <= k < num_floors - 1),
                any(k % 2 == 1 for k in (f - 1, f) if 0 <= k < num_floors - 1),
            )
            for f in range(num_floors)
        ]
        bands = [plan.split_bands(specs, slots[f]) for f, specs in enumerate(floor_specs)]
        inner_width = max(
            max(plan.band_width(top, slots[f][0]), plan.band_width(bottom, slots[f][1]))
            for f, (top, bottom) in enumerate(bands)
        )
        c_start = plan.margin + plan.outer
        cols = c_start + inner_width + plan.outer + plan.margin
        # Room ids floor by floor: the corridor, the rooms in placement order, then the staircase going up.
        per_floor = [1 + len(specs) + (f < num_floors - 1) for f, specs in enumerate(floor_specs)]
        base_ids = np.cumsum([1] + per_floor)
        stair_ids = [int(base_ids[k]) + 1 + len(floor_specs[k]) for k in range(num_floors - 1)]
        return cls(floor_specs, (plan.rows, cols), c_start, inner_width, slots, bands, base_ids, stair_ids)


@dataclass
class _FloorCanvas:
    """One floor as it is painted: category and room rasters, the cells kept clear of objects, the rooms
    placed so far, the corridor's id and the next room id."""

    plan: _FloorPlan
    reserved: np.ndarray
    corridor_id: int
    next_room_id: int


def _plan_floor(plan: _Planner, layout: _Layout, f: int, stair_rooms: dict[int, _PlacedRoom]) -> _FloorCanvas:
    """Paint floor ``f``: the corridor, then each band's staircase slot and rooms, left to right."""
    shape = layout.shape
    cat = np.full(shape, CatCode.OUTSIDE, dtype=np.int16)
    room = np.full(shape, NO_ROOM, dtype=np.int16)
    reserved = np.zeros(shape, dtype=bool)
    cat[plan.margin : shape[0] - plan.margin, plan.margin : shape[1] - plan.margin] = CatCode.WALL
    corridor_id = int(layout.base_ids[f])
    corridor_box = _Box(plan.corridor_rows[0], plan.corridor_rows[1], layout.c_start,
                        layout.c_start + layout.inner_width)
    canvas = _FloorCanvas(_FloorPlan(cat, room, [_PlacedRoom(corridor_id, "corridor", f, corridor_box)]),
                          reserved, corridor_id, corridor_id + 1)
    cat[corridor_box.slices()] = CatCode.GROUND
    room[corridor_box.slices()] = corridor_id
    reserved[corridor_box.slices()] = True
    for side, band_box in ((0, plan.top), (1, plan.bottom)):
        _plan_band(plan, layout, canvas, f, side, band_box, stair_rooms)
    return canvas


def _band_entries(plan: _Planner, layout: _Layout, f: int,
                  side: int) -> list[tuple[str, RoomSpec | int, int]]:
    """What band ``side`` of floor ``f`` holds, left to right: its staircase slot (the floor the stairs
    climb from), then its rooms, each ``(kind, what, width in cells)``; the rooms share the slack in
    proportion to their widths, so that both bands end at one wall."""
    entries: list[tuple[str, RoomSpec | int, int]] = []
    num_floors = len(layout.floor_specs)
    if layout.slots[f][side]:
        k = f if (f < num_floors - 1 and f % 2 == side) else f - 1
        entries.append(("stairs", k, plan.stairs_width))
    band = layout.bands[f][side]
    free = layout.inner_width - plan.band_width(band, layout.slots[f][side])
    total = sum(width for _, width in band)
    extra = [free * width // total for _, width in band] if band else []
    if extra:
        extra[-1] += free - sum(extra)
    for (spec, width), more in zip(band, extra):
        entries.append(("room", spec, width + more))
    return entries


def _plan_band(plan: _Planner, layout: _Layout, canvas: _FloorCanvas, f: int, side: int, band_box: _Box,
               stair_rooms: dict[int, _PlacedRoom]) -> None:
    """Paint band ``side`` of floor ``f``: its staircase and rooms, with their doors to the corridor and,
    by chance, between neighbouring rooms."""
    rng, dims = plan.rng, plan.dims
    cat, room, reserved = canvas.plan.cat, canvas.plan.room, canvas.reserved
    c = layout.c_start
    previous: _PlacedRoom | None = None
    for kind, what, width in _band_entries(plan, layout, f, side):
        box = _Box(band_box.r0, band_box.r1, c, c + width)
        c += width + plan.inner
        if isinstance(what, int):  # a staircase slot: the floor it climbs from
            placed = _place_stairs(plan, cat, room, reserved, box, side, f, what, layout.stair_ids,
                                   stair_rooms)
        else:
            placed = _PlacedRoom(canvas.next_room_id, what.category, f, box, what.objects)
            canvas.next_room_id += 1
            cat[box.slices()] = CatCode.GROUND
            room[box.slices()] = placed.id
            canvas.plan.rooms.append(placed)
            if rng.random() < dims.corridor_door_probability:
                _open_to_corridor(plan, cat, room, reserved, box, side, placed.id, canvas.corridor_id)
            beside_room = previous is not None and previous.category != "staircase"
            if beside_room and rng.random() < dims.internal_door_probability:
                assert previous is not None
                r0, r1 = plan.door_span(box.r0, box.r1)
                opening = _Box(r0, r1, previous.box.c1, box.c0)
                _paint_door(cat, room, opening, previous.id, placed.id, split_rows=False)
                _reserve_front(reserved, opening, 0, plan.door + 1)
        if kind == "stairs":
            _open_to_corridor(plan, cat, room, reserved, box, side, placed.id, canvas.corridor_id)
        previous = placed


def _open_to_corridor(
    plan: _Planner,
    cat: np.ndarray,
    room: np.ndarray,
    reserved: np.ndarray,
    box: _Box,
    side: int,
    room_id: int,
    corridor_id: int,
) -> None:
    c0, c1 = plan.door_span(box.c0, box.c1)
    if side == 0:  # top band: the corridor is below the room
        opening = _Box(box.r1, box.r1 + plan.inner, c0, c1)
        _paint_door(cat, room, opening, room_id, corridor_id, split_rows=True)
    else:
        opening = _Box(box.r0 - plan.inner, box.r0, c0, c1)
        _paint_door(cat, room, opening, corridor_id, room_id, split_rows=True)
    _reserve_front(reserved, opening, plan.door + 1, 1)


def _place_stairs(
    plan: _Planner,
    cat: np.ndarray,
    room: np.ndarray,
    reserved: np.ndarray,
    box: _Box,
    side: int,
    floor: int,
    k: int,
    stair_ids: list[int],
    stair_rooms: dict[int, _PlacedRoom],
) -> _PlacedRoom:
    """Paint staircase ``k`` on ``floor`` (its lower part if ``floor == k``, else its upper part)."""
    stair_id = stair_ids[k]
    placed = stair_rooms.setdefault(k, _PlacedRoom(stair_id, "staircase", k, box))
    if floor != k:
        placed.upper_box = box
    cat[box.slices()] = CatCode.GROUND
    room[box.slices()] = stair_id
    landing = min(plan.landing, box.r1 - box.r0 - 1)
    # The landing lies on the corridor side: below the steps in the top band, above them in the bottom one.
    if side == 0:
        steps = _Box(box.r0, box.r1 - landing, box.c0, box.c1)
    else:
        steps = _Box(box.r0 + landing, box.r1, box.c0, box.c1)
    cat[steps.slices()] = CatCode.STAIRS_UP if floor == k else CatCode.STAIRS_DOWN
    reserved[box.slices()] = True
    return placed


def _landing_portal(box: _Box, side: int, landing: int) -> tuple[int, int]:
    """Centre of the landing (the ground strip between the steps and the door)."""
    rows = (box.r1 - landing, box.r1) if side == 0 else (box.r0, box.r0 + landing)
    return ((rows[0] + rows[1] - 1) // 2, (box.c0 + box.c1 - 1) // 2)


def _assemble(
    name: str,
    plans: list[_FloorPlan],
    stair_rooms: dict[int, _PlacedRoom],
    plan: _Planner,
    cell_m: float,
    rng: np.random.Generator,
    dims: Dimensions,
    robot_radius_m: float | None,
    reach_radius_m: float | None,
) -> Building:
    rows, cols = plans[0].cat.shape
    gaps = rng.uniform(*dims.floor_gap_m, size=max(0, len(plans) - 1))
    ground_z = np.concatenate([[0.0], np.cumsum(gaps)])
    frame = _Frame((-rows * cell_m / 2.0, -cols * cell_m / 2.0), cell_m, ground_z)
    all_rooms = sorted((r for fp in plans for r in fp.rooms), key=lambda r: r.id)
    uuids = _Uuids.of(all_rooms, len(plans))
    rooms = _scene_rooms(all_rooms, plans, uuids, frame)
    _add_objects(all_rooms, plans, rooms, uuids, frame)
    floors = [
        Floor(
            index=f,
            name=chr(ord("A") + f),
            uuid=uuids.floor[f],
            origin_m=frame.origin_m,
            resolution_m=(cell_m, cell_m),
            ground_z_m=float(frame.ground_z[f]),
            cat_map=fp.cat,
            room_map=fp.room,
            rooms={r.id: rooms[r.id] for r in sorted(fp.rooms, key=lambda r: r.id)},
        )
        for f, fp in enumerate(plans)
    ]
    _link_stairs(floors, stair_rooms, plan, uuids, frame)
    return Building(
        id=1,
        uuid=1,
        name=name,
        floors=floors,
        robot_radius_m=robot_radius_m,
        reach_radius_m=reach_radius_m,
    )


@dataclass(frozen=True)
class _Frame:
    """Grid cells to metres: the origin (metres, of cell (0, 0)), the cell size and each floor's height."""

    origin_m: tuple[float, float]
    cell_m: float
    ground_z: np.ndarray

    def xy(self, row: float, col: float) -> tuple[float, float]:
        """The metric point of a (fractional) cell position."""
        return self.origin_m[0] + row * self.cell_m, self.origin_m[1] + col * self.cell_m


@dataclass
class _Uuids:
    """uuids as the authors assign them: building 1, rooms in id order with each floor's uuid right after
    its first room, then objects (``next`` is the next free one)."""

    room: dict[int, int]
    floor: dict[int, int]
    next: int

    @classmethod
    def of(cls, all_rooms: list[_PlacedRoom], num_floors: int) -> _Uuids:
        made = cls({}, {}, 2)
        for placed in all_rooms:
            made.room[placed.id] = made.take()
            if placed.floor not in made.floor:
                made.floor[placed.floor] = made.take()
        for f in range(num_floors):  # a floor holding no room of its own (impossible here; uuids unique)
            if f not in made.floor:
                made.floor[f] = made.take()
        return made

    def take(self) -> int:
        self.next += 1
        return self.next - 1


def _scene_rooms(all_rooms: list[_PlacedRoom], plans: list[_FloorPlan], uuids: _Uuids,
                 frame: _Frame) -> dict[int, Room]:
    """The scene's rooms (no objects yet), with their connections and door cells, by id."""
    doors = [door_cells(fp.room, fp.cat) for fp in plans]
    connected: dict[int, set[int]] = {r.id: set() for r in all_rooms} | connections(doors)
    half_h = 1.4
    rooms: dict[int, Room] = {}
    cell_m = frame.cell_m
    for placed in all_rooms:
        box = placed.box
        x, y = frame.xy((box.r0 + box.r1) / 2.0, (box.c0 + box.c1) / 2.0)
        rooms[placed.id] = Room(
            id=placed.id,
            uuid=uuids.room[placed.id],
            name=placed.category,
            floor=placed.floor,
            location_m=np.array([x, y, frame.ground_z[placed.floor] + half_h]),
            size_m=np.array([(box.r1 - box.r0) * cell_m, (box.c1 - box.c0) * cell_m, 2 * half_h]),
            grid_min=(box.r0, box.c0),
            grid_max=(box.r1 - 1, box.c1 - 1),
            connected_room_ids=tuple(sorted(connected[placed.id])),
            connected_room_uuids=tuple(uuids.room[i] for i in sorted(connected[placed.id])),
            door_cells={
                b: cells for floor_doors in doors for (a, b), cells in floor_doors.items() if a == placed.id
            },
        )
    return rooms


def _add_objects(all_rooms: list[_PlacedRoom], plans: list[_FloorPlan], rooms: dict[int, Room],
                 uuids: _Uuids, frame: _Frame) -> None:
    """Give every placed object its id and uuid (room by room), paint it into its floor's category raster
    and add it to its room."""
    next_object_id = 1
    cell_m = frame.cell_m
    for placed in all_rooms:
        for obj_name, obox in placed.placed_objects:
            height = OBJECT_SIZES_M[obj_name][2]
            x, y = frame.xy((obox.r0 + obox.r1) / 2.0, (obox.c0 + obox.c1) / 2.0)
            obj = SceneObject(
                id=next_object_id,
                uuid=uuids.take(),
                name=obj_name,
                room_id=placed.id,
                room_uuid=uuids.room[placed.id],
                location_m=np.array([x, y, frame.ground_z[placed.floor] + height / 2.0]),
                size_m=np.array([(obox.r1 - obox.r0) * cell_m, (obox.c1 - obox.c0) * cell_m, height]),
                grid_min=(obox.r0, obox.c0),
                grid_max=(obox.r1 - 1, obox.c1 - 1),
            )
            plans[placed.floor].cat[obox.slices()] = obj.id
            rooms[placed.id].objects[obj.id] = obj
            next_object_id += 1


def _link_stairs(floors: list[Floor], stair_rooms: dict[int, _PlacedRoom], plan: _Planner, uuids: _Uuids,
                 frame: _Frame) -> None:
    """The stairs between floors k and k + 1: portals on the landings; cost = 1.5 x the real 3-D distance
    (two flights of a U-shaped stair), which exceeds the distance in the heuristic frame (whose floor gap
    is the smallest one)."""
    cell_m, ground_z = frame.cell_m, frame.ground_z
    for k, stair in sorted(stair_rooms.items()):
        side_lower = 0 if k % 2 == 0 else 1
        landing = min(plan.landing, stair.box.r1 - stair.box.r0 - 1)
        lower = _landing_portal(stair.box, side_lower, landing)
        upper = _landing_portal(stair.upper_box or stair.box, side_lower, landing)
        d_xy = np.hypot((lower[0] - upper[0]) * cell_m, (lower[1] - upper[1]) * cell_m)
        cost = 1.5 * float(np.hypot(d_xy, ground_z[k + 1] - ground_z[k]))
        uuid = uuids.room[stair.id]
        floors[k].up_stairs = StairsEnd(room_id=stair.id, room_uuid=uuid, portal=lower, cost_m=cost)
        floors[k + 1].down_stairs = StairsEnd(room_id=stair.id, room_uuid=uuid, portal=upper, cost_m=cost)


# --- public entry points -----------------------------------------------------------------------------


def building_from_specs(
    floor_specs: Sequence[Sequence[RoomSpec]],
    *,
    cell_m: float = 0.05,
    seed: int | np.random.Generator = 0,
    name: str = "synthetic",
    dims: Dimensions | None = None,
    robot_radius_m: float | None = None,
    reach_radius_m: float | None = None,
) -> Building:
    """A building with exactly the given ordinary rooms per floor (corridors and staircases are added).

    ``floor_specs[f]`` lists floor ``f``'s rooms; each floor also gets a corridor, and consecutive floors
    a staircase. Room ids run floor by floor: the corridor, the rooms in placement order (which may
    differ from the listed order: rooms are balanced over the two sides of the corridor), then the
    staircase going up from that floor. The layout (widths, doors, object positions)
    is drawn from ``seed``.

    Raises
    ------
    SceneError
        for no floors, a non-positive cell size, a listed corridor/staircase, or an unknown object class.
    """
    return _build(name, floor_specs, cell_m, seed, dims or Dimensions(), robot_radius_m, reach_radius_m)


def generate_building(
    *,
    num_floors: int = 2,
    rooms_per_floor: int = 4,
    num_objects: int = 12,
    cell_m: float = 0.05,
    seed: int = 0,
    name: str | None = None,
    robot_radius_m: float | None = 0.15,
    reach_radius_m: float | None = 0.6,
) -> Building:
    """A random house of ``num_floors`` floors with ``rooms_per_floor`` ordinary rooms each.

    Categories are drawn from :data:`ROOM_OBJECTS` (the ground floor favours kitchen / living / dining
    rooms, upper floors bedrooms and bathrooms); ``num_objects`` objects of classes fitting their room
    are spread over the rooms (fewer may fit in small rooms: the result can hold fewer objects). Sizes
    are in metres; the grid cell is ``cell_m`` metres square.

    Raises
    ------
    SceneError
        for fewer than 1 floor, fewer than 1 room per floor, or a negative object count.
    """
    if num_floors < 1 or rooms_per_floor < 1 or num_objects < 0:
        raise SceneError(
            f"synthetic building needs >= 1 floor, >= 1 room per floor and >= 0 objects "
            f"(got {num_floors}, {rooms_per_floor}, {num_objects})"
        )
    rng = np.random.default_rng(seed)
    ground = ["kitchen", "living_room", "dining_room", "bathroom", "lobby", "utility_room"]
    upper = ["bedroom", "bathroom", "bedroom", "home_office", "bedroom", "utility_room"]
    categories = [
        [
            (ground if f == 0 else upper)[i] if i < 6 else str(rng.choice(list(ROOM_OBJECTS)))
            for i in range(rooms_per_floor)
        ]
        for f in range(num_floors)
    ]
    flat = [(f, i) for f in range(num_floors) for i in range(rooms_per_floor)]
    objects: dict[tuple[int, int], list[str]] = {key: [] for key in flat}
    for n in range(num_objects):
        f, i = flat[int(rng.integers(len(flat)))] if n >= len(flat) else flat[n]
        choices = ROOM_OBJECTS[categories[f][i]]
        objects[(f, i)].append(choices[len(objects[(f, i)]) % len(choices)])
    specs = [
        [RoomSpec(categories[f][i], tuple(objects[(f, i)])) for i in range(rooms_per_floor)]
        for f in range(num_floors)
    ]
    return _build(
        name or f"synthetic-{seed}", specs, cell_m, rng, Dimensions(), robot_radius_m, reach_radius_m
    )
