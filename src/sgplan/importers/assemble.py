"""From importer drafts to a :class:`~sgplan.scene.model.Building`: objects painted, uuids, doors, starts.

Every importer reduces its source to the same drafts -- per floor a category map and a room map on one
:class:`~sgplan.importers.raster.GridFrame`, rooms by id, objects as oriented 3-D boxes -- and this module
finishes the building the same way for all of them:

- **Objects.** An object *blocks* when its box reaches down to within ``near_floor_m`` of its floor's
  ground and rises above ``min_height_m`` (furniture, appliances; not rugs, not pictures, not lamps
  hanging from the ceiling). Objects are painted largest first, so a small one on top of a large one
  stays visible. A blocking object takes its whole footprint; a non-blocking one only the cells of its
  footprint (grown by :data:`HANG_REACH_CELLS`) that are already obstacles (a picture on a wall, an oven
  in a counter): it never takes free floor away. An object left
  without any cell is dropped, with a note, because nothing could ever reach it.
- **uuids** follow the authors' rule: building 1; rooms in id order, each floor's uuid right after its
  first room; then objects in id order.
- **Doors and connections** come from the rasters (:mod:`sgplan.scene.doors`).
- **Start cells** (``Building.initial_cells``): per room, the free cell of its largest free component
  nearest the component's middle; entrance rooms (lobby, entryway, foyer, entrance) first.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage

from sgplan.english import count, series
from sgplan.errors import SceneError
from sgplan.importers.raster import GridFrame, box_corners, hull_cells
from sgplan.scene.doors import connections, door_cells
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.model import Building, CatCode, Floor, Room, SceneObject

ENTRANCE_NAMES = ("lobby", "entryway", "entrance", "foyer", "entrance_hall")
"""Room categories a robot is likely to start in; their start cells come first."""

HANG_REACH_CELLS = 2
"""A non-blocking object may take obstacle cells up to this many cells (in rows and columns) beyond its
footprint: the wall a picture or a towel hangs on lies just outside the room's floor polygon."""

MAX_ID = int(np.iinfo(np.int16).max)
"""Rasters are int16: room and object ids must fit."""


@dataclass(frozen=True)
class Settings:
    """Choices shared by every importer (lengths in metres)."""

    resolution_m: float = 0.05
    robot_radius_m: float = 0.1
    reach_radius_m: float = 0.5
    near_floor_m: float = 0.3
    """An object whose box starts at most this high above the floor blocks the robot."""
    min_height_m: float = 0.05
    """...provided it rises above this (a rug does not block)."""


@dataclass
class RoomDraft:
    """A room to be: id (> 0, unique), category name, floor index and ceiling height."""

    id: int
    name: str
    floor: int
    height_m: float = 2.5


@dataclass
class ObjectDraft:
    """An object to be: an oriented box (centre ``(3,)``, unit axes as rows ``(3, 3)``, half sizes ``(3,)``).

    ``room_id`` is its room, or ``None`` to take the room under its centre.
    """

    name: str
    floor: int
    center_m: np.ndarray
    axes: np.ndarray
    half_sizes_m: np.ndarray
    room_id: int | None = None
    source: str = ""
    """How the source names it (``object 17``), for notes and errors."""

    def corners(self) -> np.ndarray:
        return box_corners(self.center_m, self.axes, self.half_sizes_m)


@dataclass
class FloorDraft:
    """One floor's rasters (decoded int16 codes) and its ground height."""

    name: str
    ground_z_m: float
    cat_map: np.ndarray
    room_map: np.ndarray


@dataclass
class ImportResult:
    """An imported building and what the user should know about it (one sentence per note)."""

    building: Building
    notes: list[str] = field(default_factory=list)


def blocks(obj: ObjectDraft, ground_z_m: float, settings: Settings) -> bool:
    """Whether the object stands on the floor (see the module docstring)."""
    z = obj.corners()[:, 2]
    return bool(
        z.min() <= ground_z_m + settings.near_floor_m and z.max() >= ground_z_m + settings.min_height_m
    )


def paint_objects(
    frame: GridFrame, floors: Sequence[FloorDraft], objects: Sequence[ObjectDraft], settings: Settings
) -> tuple[list[tuple[ObjectDraft, int]], list[str]]:
    """Paint the objects on their floors' category maps (in place) with ids ``1..n`` in input order.

    Returns the objects kept with their ids, and notes about the ones dropped.
    """
    if len(objects) > MAX_ID:
        raise SceneError(f"{len(objects)} objects do not fit an int16 category map (at most {MAX_ID})")
    footprints = [hull_cells(frame, obj.corners()[:, :2]) for obj in objects]
    standing = [blocks(obj, floors[obj.floor].ground_z_m, settings) for obj in objects]
    reach = np.array(
        [
            (dr, dc)
            for dr in range(-HANG_REACH_CELLS, HANG_REACH_CELLS + 1)
            for dc in range(-HANG_REACH_CELLS, HANG_REACH_CELLS + 1)
        ]
    )
    # Largest first: a smaller object painted later lies on top of (and rarely erases) a larger one.
    for i in sorted(range(len(objects)), key=lambda i: -len(footprints[i])):
        cat = floors[objects[i].floor].cat_map
        cells = footprints[i]
        if not standing[i]:  # on obstacles only, reaching a little beyond its box for the wall it hangs on
            near = np.unique((cells[:, None, :] + reach[None]).reshape(-1, 2), axis=0)
            near = near[frame.contains(near)]
            code = cat[near[:, 0], near[:, 1]]
            cells = near[(code != CatCode.GROUND) & (code != CatCode.OUTSIDE)]
        cat[cells[:, 0], cells[:, 1]] = i + 1
    kept: list[tuple[ObjectDraft, int]] = []
    dropped: list[str] = []
    present = [set(np.unique(f.cat_map[f.cat_map > 0]).tolist()) for f in floors]
    for i, obj in enumerate(objects):
        if i + 1 in present[obj.floor]:
            kept.append((obj, i + 1))
        else:
            dropped.append(f"{obj.name} ({obj.source})" if obj.source else obj.name)
    notes = []
    if dropped:
        notes.append(
            f"{count(len(dropped), 'object')} left out, named as the source names them (they get no "
            "object_<uuid>): they hang above free floor (or are covered by others), so no cell of the map "
            f"holds them: {', '.join(dropped)}"
        )
    return kept, notes


def assemble(
    name: str,
    frame: GridFrame,
    floors: Sequence[FloorDraft],
    rooms: Sequence[RoomDraft],
    objects: Sequence[ObjectDraft],
    settings: Settings,
) -> ImportResult:
    """The building of the drafts (the floors' rasters are modified in place: objects are painted).

    Raises
    ------
    SceneError
        if a room id is not in ``1..32767`` or repeats, a room or object names a floor that does not
        exist, an object names an unknown room, or no room has a free cell.
    """
    _check_drafts(floors, rooms, objects)
    for floor in floors:
        floor.room_map = floor.room_map.astype(np.int16)
        floor.cat_map = floor.cat_map.astype(np.int16)
    objects = _with_rooms(objects, frame, floors, rooms)
    kept, notes = paint_objects(frame, floors, objects, settings)

    ordered = sorted(rooms, key=lambda r: r.id)
    room_uuid, floor_uuid, next_uuid = _uuids(ordered, len(floors))

    doors = [door_cells(f.room_map, f.cat_map) for f in floors]
    connected = connections(doors)
    # bounding boxes of every id in one pass per raster, so no step scans the grid once per room or object
    room_boxes = [ndimage.find_objects(np.maximum(f.room_map, 0)) for f in floors]
    object_boxes = [ndimage.find_objects(np.maximum(f.cat_map, 0)) for f in floors]
    built: dict[int, Room] = {}
    for draft in ordered:
        floor = floors[draft.floor]
        neighbours = sorted(connected.get(draft.id, ()))
        cells = _cells_of(floor.room_map, draft.id, room_boxes[draft.floor])
        built[draft.id] = _room(
            draft, cells, frame, floor.ground_z_m, room_uuid, neighbours, doors[draft.floor]
        )
    _put_objects(kept, built, floors, object_boxes, next_uuid)
    building = Building(
        id=1,
        uuid=1,
        name=name,
        floors=[
            Floor(
                index=k,
                name=draft.name,
                uuid=floor_uuid[k],
                origin_m=frame.origin_m,
                resolution_m=(frame.resolution_m, frame.resolution_m),
                ground_z_m=float(draft.ground_z_m),
                cat_map=draft.cat_map,
                room_map=draft.room_map,
                rooms={r.id: built[r.id] for r in ordered if r.floor == k},
            )
            for k, draft in enumerate(floors)
        ],
        robot_radius_m=settings.robot_radius_m,
        reach_radius_m=settings.reach_radius_m,
    )
    building.initial_cells = start_cells(building, settings.robot_radius_m, room_boxes)
    if not building.initial_cells:
        raise SceneError(
            f"no room of {name!r} has a cell free for a robot of radius {settings.robot_radius_m} m: the "
            "free "
            "space is too narrow or lies outside every room (try a smaller --robot-radius or a finer "
            "--resolution)"
        )
    return ImportResult(building, notes + _building_notes(building, room_boxes, settings.robot_radius_m))


def _put_objects(kept: Sequence[tuple[ObjectDraft, int]], built: dict[int, Room],
                 floors: Sequence[FloorDraft], object_boxes: Sequence[Boxes], first_uuid: int) -> None:
    """Add each kept object (with its id on the category map) to its room, uuids from ``first_uuid``."""
    for uuid, (obj, object_id) in enumerate(kept, start=first_uuid):
        room = built[obj.room_id]  # type: ignore[index]
        cells = _cells_of(floors[obj.floor].cat_map, object_id, object_boxes[obj.floor])
        corners = obj.corners()
        room.objects[object_id] = SceneObject(
            id=object_id,
            uuid=uuid,
            name=obj.name,
            room_id=room.id,
            room_uuid=room.uuid,
            location_m=np.asarray(obj.center_m, dtype=float),
            size_m=corners.max(axis=0) - corners.min(axis=0),
            grid_min=(int(cells[:, 0].min()), int(cells[:, 1].min())),
            grid_max=(int(cells[:, 0].max()), int(cells[:, 1].max())),
        )


def _building_notes(building: Building, room_boxes: Sequence[Boxes], robot_radius_m: float) -> list[str]:
    """Notes on the finished building: rooms without a cell, floors not joined, rooms mostly shut off."""
    notes = []
    empty = [r.key for r in building.rooms()
             if not len(_cells_of(building.floors[r.floor].room_map, r.id, room_boxes[r.floor]))]
    if empty:
        notes.append(f"{series(empty)} {'covers' if len(empty) == 1 else 'cover'} no cell of the grid: "
                     "missions cannot enter them")
    if building.num_floors > 1:
        notes.append(
            f"{building.num_floors} floors, not joined: stairs are not imported, so a path stays on the "
            "floor it starts on"
        )
    return notes + shut_off_notes(building, robot_radius_m)


SHUT_OFF_SHARE = 0.5
"""A room is noted as mostly shut off when more than this share of its free cells lie outside its floor's
largest free area."""


def shut_off_notes(building: Building, robot_radius_m: float) -> list[str]:
    """A note per room whose free cells mostly lie apart from its floor's largest connected free area at
    this robot radius: a wall read where the source has an opening, or a room the robot cannot enter."""
    grid = build_occupancy_grid(building, robot_radius_m)
    notes = []
    for floor in building.floors:
        parts, _ = ndimage.label(grid.traversable[floor.index], structure=np.ones((3, 3), dtype=bool))
        sizes = np.bincount(parts.ravel())
        main = int(np.argmax(sizes[1:])) + 1 if len(sizes) > 1 else 0
        for room in sorted(floor.rooms.values(), key=lambda r: r.id):
            free = parts[floor.room_map == room.id]
            free = free[free > 0]
            apart = int((free != main).sum())
            if len(free) and apart > SHUT_OFF_SHARE * len(free):
                notes.append(
                    f"{room.key} {room.name}: {apart:,} of its {count(len(free), 'free cell')} "
                    f"({100 * apart / len(free):.0f}%) are cut off from the largest free area of floor "
                    f"{floor.index} for a robot of radius {robot_radius_m:g} m, so plans reach little or "
                    "none of it; draw the scene (sgplan inspect SCENE --draw DIR) to see which wall shuts it"
                )
    return notes


def _uuids(ordered: Sequence[RoomDraft], floors: int) -> tuple[dict[int, int], dict[int, int], int]:
    """uuids by the authors' rule: rooms in id order from 2, each floor's right after its first room.

    Returns room id -> uuid, floor index -> uuid, and the first uuid left for the objects.
    """
    next_uuid = 2
    room_uuid: dict[int, int] = {}
    floor_uuid: dict[int, int] = {}
    for draft in ordered:
        room_uuid[draft.id] = next_uuid
        next_uuid += 1
        if draft.floor not in floor_uuid:
            floor_uuid[draft.floor] = next_uuid
            next_uuid += 1
    for index in range(floors):  # a floor without rooms still needs a uuid of its own
        if index not in floor_uuid:
            floor_uuid[index] = next_uuid
            next_uuid += 1
    return room_uuid, floor_uuid, next_uuid


Boxes = list[tuple[slice, slice] | None]
"""``ndimage.find_objects`` of a raster: entry ``k - 1`` bounds the cells holding ``k``."""


def _cells_of(raster: np.ndarray, value: int, boxes: Boxes) -> np.ndarray:
    """The ``(row, col)`` cells ``(n, 2)`` of ``raster`` holding ``value``, looked for inside its box only."""
    box = boxes[value - 1] if value - 1 < len(boxes) else None
    if box is None:
        return np.zeros((0, 2), dtype=np.int64)
    return np.argwhere(raster[box] == value) + (box[0].start, box[1].start)


def _check_drafts(
    floors: Sequence[FloorDraft], rooms: Sequence[RoomDraft], objects: Sequence[ObjectDraft]
) -> None:
    seen: set[int] = set()
    for room in rooms:
        if not 0 < room.id <= MAX_ID or room.id in seen:
            raise SceneError(f"room id {room.id} ({room.name}) is repeated or outside 1..{MAX_ID}")
        if not 0 <= room.floor < len(floors):
            raise SceneError(
                f"room {room.id} ({room.name}) is on floor {room.floor}, but there are {len(floors)} floor(s)"
            )
        seen.add(room.id)
    for obj in objects:
        if not 0 <= obj.floor < len(floors):
            raise SceneError(
                f"object {obj.name} ({obj.source}) is on floor {obj.floor}, but there are {len(floors)} "
                "floor(s)"
            )
        if obj.room_id is not None and obj.room_id not in seen:
            raise SceneError(
                f"object {obj.name} ({obj.source}) names room {obj.room_id}, which does not exist"
            )


def _with_rooms(
    objects: Sequence[ObjectDraft], frame: GridFrame, floors: Sequence[FloorDraft], rooms: Sequence[RoomDraft]
) -> list[ObjectDraft]:
    """The objects, each with a room on its own floor: as given if that fits, else the room nearest its
    centre."""
    nearest: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    out = []
    for obj in objects:
        if obj.room_id is not None and any(r.id == obj.room_id and r.floor == obj.floor for r in rooms):
            out.append(obj)
            continue
        room_map = floors[obj.floor].room_map
        if not (room_map > 0).any():
            raise SceneError(
                f"object {obj.name} ({obj.source}) stands on floor {obj.floor}, which has no room cells"
            )
        if obj.floor not in nearest:  # index of the nearest room cell, for every cell of the floor
            _, index = ndimage.distance_transform_edt(room_map <= 0, return_indices=True)
            nearest[obj.floor] = (index[0], index[1])
        row, col = np.clip(frame.cell_of(obj.center_m[:2])[0], 0, np.array(room_map.shape) - 1)
        rows, cols = nearest[obj.floor]
        room_id = int(room_map[rows[row, col], cols[row, col]])
        out.append(
            ObjectDraft(obj.name, obj.floor, obj.center_m, obj.axes, obj.half_sizes_m, room_id, obj.source)
        )
    return out


def _room(
    draft: RoomDraft,
    cells: np.ndarray,
    frame: GridFrame,
    ground_z_m: float,
    room_uuid: dict[int, int],
    neighbours: list[int],
    doors: dict[tuple[int, int], np.ndarray],
) -> Room:
    res = frame.resolution_m
    if len(cells):
        lo, hi = cells.min(axis=0), cells.max(axis=0)
        middle = frame.origin_m + (cells.mean(axis=0) + 0.5) * res
        extent = (hi - lo + 1) * res
    else:
        lo = hi = np.zeros(2, dtype=np.int64)
        middle, extent = np.zeros(2), np.zeros(2)
    return Room(
        id=draft.id,
        uuid=room_uuid[draft.id],
        name=draft.name,
        floor=draft.floor,
        location_m=np.array([middle[0], middle[1], ground_z_m + draft.height_m / 2.0]),
        size_m=np.array([extent[0], extent[1], draft.height_m]),
        grid_min=(int(lo[0]), int(lo[1])),
        grid_max=(int(hi[0]), int(hi[1])),
        connected_room_ids=tuple(neighbours),
        connected_room_uuids=tuple(room_uuid[i] for i in neighbours),
        door_cells={b: cells_ab for (a, b), cells_ab in doors.items() if a == draft.id},
    )


def start_cells(
    building: Building, robot_radius_m: float, room_boxes: Sequence[Boxes] | None = None
) -> list[tuple[int, int, int]]:
    """One start cell ``(row, col, floor)`` per room that has a free cell, entrance rooms first.

    The cell is the free cell of the room's largest 8-connected free component nearest the mean of that
    component: "the middle of the room" where the robot fits. ``room_boxes`` (per floor,
    ``ndimage.find_objects`` of its room map) only saves the search; it is computed when omitted.
    """
    grid = build_occupancy_grid(building, robot_radius_m)
    if room_boxes is None:
        room_boxes = [ndimage.find_objects(np.maximum(f.room_map, 0)) for f in building.floors]
    eight = np.ones((3, 3), dtype=bool)
    rooms = sorted(building.rooms(), key=lambda r: (r.name.lower() not in ENTRANCE_NAMES, r.floor, r.id))
    starts = []
    for room in rooms:
        boxes = room_boxes[room.floor]
        box = boxes[room.id - 1] if room.id - 1 < len(boxes) else None
        if box is None:
            continue
        free = grid.traversable[room.floor][box] & (grid.room_map[room.floor][box] == room.id)
        labels, count = ndimage.label(free, structure=eight)
        if count == 0:
            continue
        largest = 1 + int(np.argmax(np.bincount(labels.ravel())[1:]))
        cells = np.argwhere(labels == largest)
        best = cells[np.argmin(((cells - cells.mean(axis=0)) ** 2).sum(axis=1))]
        starts.append((int(best[0]) + box[0].start, int(best[1]) + box[1].start, room.floor))
    return starts
