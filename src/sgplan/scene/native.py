"""sgplan's own scene format: a JSON graph plus a compressed ``.npz`` of the cell data.

A scene is a folder::

    <scene>/scene.json     the graph (format "sgplan-scene", version 1): building, floors, rooms, objects,
                           connections, stairs, robot/reach radii, initial cells
    <scene>/rasters.npz    cat_map_<k>, room_map_<k> (int16, decoded values) and door_cells (int32,
                           rows [room_id, neighbour_id, row, col]); absent when the building has no rasters

The complete field list is in docs/formats.md. The npz holds only plain arrays and is read with
``allow_pickle=False``. Reading validates the document like the authors' loader does and raises
:class:`~sgplan.errors.SceneError` naming the file, entity and field.
"""

from __future__ import annotations

import json
import math
import zipfile
import zlib
from pathlib import Path
from typing import Any

import numpy as np

from sgplan.errors import SceneError
from sgplan.files import write_file_atomically, write_text_atomically
from sgplan.limits import MAX_GRID_CELLS, MAX_REACH_RADIUS_M, MAX_ROBOT_RADIUS_M
from sgplan.safeio import check_regular_file, load_json, quote
from sgplan.scene.fields import Fields, is_int
from sgplan.scene.model import Building, Floor, Room, SceneObject, StairsEnd

GRAPH_FILE = "scene.json"
RASTER_FILE = "rasters.npz"
FORMAT_NAME = "sgplan-scene"
FORMAT_VERSION = 1


# -- writing -------------------------------------------------------------------------------------------


def write_native_scene(building: Building, folder: str | Path) -> Path:
    """Write ``building`` to ``folder`` (created if needed) as ``scene.json`` + ``rasters.npz``.

    Returns the folder. Floors without rasters (``has_maps`` False) are written with ``grid_shape``
    ``[0, 0]``; the npz is written only if some floor has rasters or some room has door cells.
    """
    folder = Path(folder).expanduser()
    folder.mkdir(parents=True, exist_ok=True)
    arrays: dict[str, np.ndarray] = {}
    for floor in building.floors:
        if floor.has_maps:
            arrays[f"cat_map_{floor.index}"] = floor.cat_map.astype(np.int16)
            arrays[f"room_map_{floor.index}"] = floor.room_map.astype(np.int16)
    doors = [
        np.column_stack([np.full((len(cells), 2), (room.id, neighbour)), cells])
        for room in building.rooms()
        for neighbour, cells in room.door_cells.items()
    ]
    if doors:
        arrays["door_cells"] = np.concatenate(doors).astype(np.int32)
    document = {
        "format": FORMAT_NAME,
        "version": FORMAT_VERSION,
        "rasters": RASTER_FILE if arrays else None,
        "building": {
            "id": building.id,
            "uuid": building.uuid,
            "name": building.name,
            "robot_radius_m": building.robot_radius_m,
            "reach_radius_m": building.reach_radius_m,
            "initial_cells": [list(cell) for cell in building.initial_cells],
        },
        "floors": [_floor_document(floor) for floor in building.floors],
    }
    raster_path = folder / RASTER_FILE
    # Rasters first, each file replaced whole: an interrupted write leaves the earlier scene readable.
    if arrays:
        # numpy's stubs fear an array named allow_pickle; ours are cat_map_<k>, room_map_<k>, door_cells...
        write_file_atomically(raster_path, lambda tmp: np.savez_compressed(tmp, **arrays))  # type: ignore[arg-type]
    text = json.dumps(document, indent=1, allow_nan=False, default=_plain_number)
    write_text_atomically(folder / GRAPH_FILE, text + "\n")
    if not arrays and raster_path.exists():
        raster_path.unlink()  # a stale file from an earlier write would contradict "rasters": null
    return folder


def _plain_number(value: object) -> int | float:
    """JSON for numpy scalars (ids, cells and sizes built with numpy arithmetic); anything else is refused."""
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    raise TypeError(f"{type(value).__name__} {value!r} is not JSON serialisable")


def _floor_document(floor: Floor) -> dict[str, Any]:
    return {
        "index": floor.index,
        "name": floor.name,
        "uuid": floor.uuid,
        "grid_shape": list(floor.shape),
        "origin_m": list(floor.origin_m),
        "resolution_m": list(floor.resolution_m),
        "ground_z_m": floor.ground_z_m if math.isfinite(floor.ground_z_m) else None,
        "up_stairs": _stairs_document(floor.up_stairs),
        "down_stairs": _stairs_document(floor.down_stairs),
        "rooms": [_room_document(room) for room in floor.rooms.values()],
    }


def _stairs_document(end: StairsEnd | None) -> dict[str, Any] | None:
    if end is None:
        return None
    return {
        "room_id": end.room_id,
        "room_uuid": end.room_uuid,
        "portal": list(end.portal),
        "cost_m": end.cost_m,
    }


def _room_document(room: Room) -> dict[str, Any]:
    return {
        "id": room.id,
        "uuid": room.uuid,
        "name": room.name,
        "location_m": room.location_m.tolist(),
        "size_m": room.size_m.tolist(),
        "grid_min": list(room.grid_min),
        "grid_max": list(room.grid_max),
        "connected_room_ids": list(room.connected_room_ids),
        "connected_room_uuids": list(room.connected_room_uuids),
        "objects": [
            {
                "id": obj.id,
                "uuid": obj.uuid,
                "name": obj.name,
                "location_m": obj.location_m.tolist(),
                "size_m": obj.size_m.tolist(),
                "grid_min": list(obj.grid_min),
                "grid_max": list(obj.grid_max),
                "action_affordance": list(obj.action_affordance),
            }
            for obj in room.objects.values()
        ],
    }


# -- reading -------------------------------------------------------------------------------------------


def is_native_scene(path: str | Path) -> bool:
    """True if ``path`` is a folder holding ``scene.json`` or is a ``scene.json`` / ``*.json`` file."""
    path = Path(path)
    return (path.is_dir() and (path / GRAPH_FILE).is_file()) or (path.is_file() and path.suffix == ".json")


def read_native_scene(path: str | Path) -> Building:
    """Read a scene written by :func:`write_native_scene` (the folder or its ``scene.json``).

    Raises
    ------
    SceneError
        Missing or unreadable files, another format or a newer version, a missing or mistyped field, a
        raster of the wrong shape or dtype, ids in a raster that the graph does not declare, references
        that do not resolve. The message names the file and the entity and field.
    """
    path = Path(path).expanduser()
    if not path.exists():
        raise SceneError("scene path does not exist", path)
    graph_path = path / GRAPH_FILE if path.is_dir() else path
    if not (graph_path.exists() or graph_path.is_symlink()):
        raise SceneError(f"scene folder has no {GRAPH_FILE}", path)
    document = load_json(graph_path, SceneError, "scene file")
    top = Fields(document, graph_path, "scene")
    if top.raw("format", None) != FORMAT_NAME or not is_int(top.raw("version", None)):
        raise top.error(f"not an {FORMAT_NAME} document (fields 'format' and 'version' are required)")
    if top.integer("version") > FORMAT_VERSION:
        raise top.error(f"version {top.integer('version')} is newer than this sgplan reads, {FORMAT_VERSION}")

    info = Fields(top.raw("building"), graph_path, "building")
    floors_data = top.raw("floors")
    if not isinstance(floors_data, list) or not floors_data:
        raise top.error("field 'floors' must be a non-empty list")
    floors_and_shapes = [
        _read_floor(Fields(data, graph_path, f"floor {k}"), k) for k, data in enumerate(floors_data)
    ]
    floors = [floor for floor, _ in floors_and_shapes]
    arrays = _read_arrays(graph_path, top)
    for floor, shape in floors_and_shapes:
        _attach_rasters(floor, shape, arrays, graph_path)
    room_ids = {room.id for floor in floors for room in floor.rooms.values()}
    _attach_doors(floors, arrays.get("door_cells"), room_ids, graph_path)

    robot, reach = (info.raw(key, None) for key in ("robot_radius_m", "reach_radius_m"))
    cells = info.raw("initial_cells", [])
    if not isinstance(cells, list) or not all(
        isinstance(c, list) and len(c) == 3 and all(is_int(v) for v in c) for c in cells
    ):
        raise info.error("field 'initial_cells' must be a list of [row, col, floor] integer triples")
    try:
        building = Building(
            id=info.integer("id"),
            uuid=info.integer("uuid"),
            name=info.text("name"),
            floors=floors,
            source=graph_path.parent,
            robot_radius_m=None if robot is None else _radius(info, "robot_radius_m", MAX_ROBOT_RADIUS_M,
                                                              zero=True),
            reach_radius_m=None if reach is None else _radius(info, "reach_radius_m", MAX_REACH_RADIUS_M),
            initial_cells=[(c[0], c[1], c[2]) for c in cells],
        )
    except SceneError as error:
        if error.path is not None:
            raise
        raise SceneError(str(error), graph_path) from None
    _check_references(building, graph_path)
    return building


def _radius(fields: Fields, key: str, maximum: float, *, zero: bool = False) -> float:
    """A radius in metres in (0, ``maximum``] (``[0, maximum]`` with ``zero``: a point robot), the bounds
    the command line puts on the same option."""
    value = fields.number(key)
    if not (value >= 0 if zero else value > 0) or not value <= maximum:
        low = ">= 0" if zero else "> 0"
        raise fields.error(
            f"field {key!r} must be a radius in metres {low} and <= {maximum:g}, got {value:g}"
        )
    return value


def _read_floor(fields: Fields, position: int) -> tuple[Floor, tuple[int, int]]:
    """The floor (rasters still empty) and its declared ``grid_shape``."""
    if fields.integer("index") != position:
        raise fields.error(f"field 'index' is {fields.raw('index')} but the floor is at position {position}")
    origin = fields.vector("origin_m", 2)
    resolution = fields.vector("resolution_m", 2)
    ground = fields.raw("ground_z_m", None)
    rows, cols = fields.int_list("grid_shape", 2)
    if rows * cols > MAX_GRID_CELLS:
        raise fields.error(f"grid_shape {[rows, cols]} has more than {MAX_GRID_CELLS:,} cells")
    if rows < 0 or cols < 0 or ((rows == 0) != (cols == 0)) or (rows > 0 and not (resolution > 0).all()):
        raise fields.error(f"grid_shape {[rows, cols]} with resolution_m {resolution.tolist()} is not a grid")
    floor = Floor(
        index=position,
        name=fields.text("name"),
        uuid=fields.integer("uuid"),
        origin_m=(float(origin[0]), float(origin[1])),
        resolution_m=(float(resolution[0]), float(resolution[1])),
        ground_z_m=float("nan") if ground is None else fields.number("ground_z_m"),
        cat_map=np.zeros((0, 0), np.int16),
        room_map=np.zeros((0, 0), np.int16),
        up_stairs=_read_stairs(fields, "up_stairs"),
        down_stairs=_read_stairs(fields, "down_stairs"),
    )
    rooms = fields.raw("rooms")
    if not isinstance(rooms, list):
        raise fields.error("field 'rooms' must be a list")
    for data in rooms:
        room = _read_room(Fields(data, fields.path, f"room (floor {position})"), position)
        if room.id in floor.rooms:
            raise fields.error(f"room id {room.id} appears twice")
        floor.rooms[room.id] = room
    return floor, (rows, cols)


def _read_stairs(fields: Fields, key: str) -> StairsEnd | None:
    data = fields.raw(key, None)
    if data is None:
        return None
    stairs = Fields(data, fields.path, f"{fields.entity} {key}")
    cost = stairs.number("cost_m")
    if cost <= 0:
        raise stairs.error(f"field 'cost_m' must be positive metres, got {cost}")
    return StairsEnd(
        room_id=stairs.integer("room_id"),
        room_uuid=stairs.integer("room_uuid"),
        portal=stairs.cell("portal"),
        cost_m=cost,
    )


def _read_room(fields: Fields, floor: int) -> Room:
    fields.entity = f"room {fields.integer('id')} (floor {floor})"
    ids = fields.int_list("connected_room_ids")
    uuids = fields.int_list("connected_room_uuids")
    if len(ids) != len(uuids):
        raise fields.error("connected_room_ids and connected_room_uuids must have the same length")
    room = Room(
        id=fields.integer("id"),
        uuid=fields.integer("uuid"),
        name=fields.text("name"),
        floor=floor,
        location_m=fields.vector("location_m", 3),
        size_m=fields.vector("size_m", 3),
        grid_min=fields.cell("grid_min"),
        grid_max=fields.cell("grid_max"),
        connected_room_ids=tuple(ids),
        connected_room_uuids=tuple(uuids),
    )
    objects = fields.raw("objects")
    if not isinstance(objects, list):
        raise fields.error("field 'objects' must be a list")
    for data in objects:
        obj_fields = Fields(data, fields.path, f"object (room {room.id})")
        obj_fields.entity = f"object {obj_fields.integer('id')} (room {room.id})"
        obj = SceneObject(
            id=obj_fields.integer("id"),
            uuid=obj_fields.integer("uuid"),
            name=obj_fields.text("name"),
            room_id=room.id,
            room_uuid=room.uuid,
            location_m=obj_fields.vector("location_m", 3),
            size_m=obj_fields.vector("size_m", 3),
            grid_min=obj_fields.cell("grid_min"),
            grid_max=obj_fields.cell("grid_max"),
            action_affordance=obj_fields.strings("action_affordance"),
        )
        if obj.id in room.objects:
            raise fields.error(f"object id {obj.id} appears twice")
        room.objects[obj.id] = obj
    return room


def _read_arrays(graph_path: Path, top: Fields) -> dict[str, np.ndarray]:
    name = top.raw("rasters", None)
    if name is None:
        return {}
    if not isinstance(name, str) or Path(name).name != name:
        raise top.error(f"field 'rasters' must be a file name beside {GRAPH_FILE}, got {quote(name)}")
    path = graph_path.parent / name
    if not path.exists():
        raise top.error(f"field 'rasters' names {path}, which does not exist")
    check_regular_file(path, SceneError, "raster archive")
    try:
        with np.load(path, allow_pickle=False) as archive:
            return {key: archive[key] for key in archive.files}
    except (OSError, ValueError, EOFError, zipfile.BadZipFile, zlib.error, MemoryError) as error:
        message = f"not a readable npz of plain arrays (corrupt or truncated): {quote(str(error), 200)}"
        raise SceneError(message, path) from None


def _attach_rasters(
    floor: Floor, shape: tuple[int, int], arrays: dict[str, np.ndarray], graph_path: Path
) -> None:
    if shape == (0, 0):
        return
    for attribute in ("cat_map", "room_map"):
        key = f"{attribute}_{floor.index}"
        raster = arrays.get(key)
        if raster is None:
            raise SceneError(f"has no array {key!r} for floor {floor.index}", graph_path.parent / RASTER_FILE)
        if raster.dtype != np.int16 or raster.shape != shape:
            raise SceneError(
                f"array {key!r} is {raster.dtype} {raster.shape}, expected int16 {shape} "
                f"(floor {floor.index} grid_shape)",
                graph_path.parent / RASTER_FILE,
            )
        setattr(floor, attribute, raster)
    objects, rooms = floor.undeclared_map_ids()
    for ids, kind in ((objects, "object"), (rooms, "room")):
        if ids:
            raise SceneError(
                f"floor {floor.index}'s rasters hold {kind} id(s) {ids} that {GRAPH_FILE} does not declare",
                graph_path.parent / RASTER_FILE,
            )


def _attach_doors(
    floors: list[Floor], doors: np.ndarray | None, room_ids: set[int], graph_path: Path
) -> None:
    if doors is None:
        return
    path = graph_path.parent / RASTER_FILE
    if doors.dtype != np.int32 or doors.ndim != 2 or doors.shape[1] != 4:
        raise SceneError(f"array 'door_cells' is {doors.dtype} {doors.shape}, expected int32 (n, 4)", path)
    rooms = {room.id: room for floor in floors for room in floor.rooms.values()}
    for room_id, neighbour in _first_appearance(doors[:, :2]):
        if room_id not in rooms or neighbour not in room_ids:
            raise SceneError(f"array 'door_cells' names unknown room id {room_id} or {neighbour}", path)
        room = rooms[room_id]
        cells = doors[(doors[:, 0] == room_id) & (doors[:, 1] == neighbour), 2:]
        rows, cols = floors[room.floor].shape
        if ((cells < 0) | (cells >= (rows, cols))).any():
            raise SceneError(f"door cells of room {room_id} towards room {neighbour} are off the grid", path)
        room.door_cells[neighbour] = np.ascontiguousarray(cells)


def _first_appearance(pairs: np.ndarray) -> list[tuple[int, int]]:
    """The distinct rows of ``pairs`` in order of first appearance (the writer's dict order)."""
    _, first = np.unique(pairs, axis=0, return_index=True)
    return [(int(pairs[i, 0]), int(pairs[i, 1])) for i in sorted(first)]


def _check_references(building: Building, graph_path: Path) -> None:
    """Connections and stairs must name rooms of the building with matching uuids."""
    for room in building.rooms():
        for room_id, uuid in zip(room.connected_room_ids, room.connected_room_uuids):
            if not building.has_room(uuid) or building.room(uuid=uuid).id != room_id:
                raise SceneError(
                    f"room {room.id}: connection (id {room_id}, uuid {uuid}) does not name a room", graph_path
                )
    for floor in building.floors:
        for end in (floor.up_stairs, floor.down_stairs):
            if end is None:
                continue
            if not building.has_room(end.room_uuid) or building.room(uuid=end.room_uuid).id != end.room_id:
                raise SceneError(
                    f"floor {floor.index}: stairs (room id {end.room_id}, uuid {end.room_uuid}) "
                    "do not name a room",
                    graph_path,
                )
            (row, col), (rows, cols) = end.portal, floor.shape
            if not (0 <= row < rows and 0 <= col < cols):
                message = f"floor {floor.index}: stairs portal {[row, col]} is off the grid"
                raise SceneError(message, graph_path)
