"""Loader for the authors' scene folder: ``building.yaml`` + ``cat_maps/`` + ``room_maps/``.

Folder layout (reference-algorithm.md §1.1-1.3; the format is documented in docs/formats.md)::

    <Scene>/building.yaml            floors -> rooms -> objects, grid geometry, doors, stairs
    <Scene>/cat_maps/<k>.png         8-bit grayscale, value = semantic code + 5 (object id, CatCode)
    <Scene>/room_maps/<k>.png        8-bit grayscale, value = room id + 5 (NO_ROOM = -5)
    <Scene>/initial_positions.yaml   optional: list of [row, col, floor] start cells
    <Scene>/radius_config.bash       optional: ROBOT_RADIUS=<m> and OBJECT_REACH_RADIUS=<m>

The two lists ``connected_room_ids`` and ``connected_room_uuids`` of a room hold the same rooms in
unrelated orders; the loader keeps the ids' order and looks the uuids up through the ids (after checking
that both lists name the same set of rooms).
"""

from __future__ import annotations

import os
import re
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from sgplan.errors import SceneError
from sgplan.limits import MAX_GRID_CELLS, MAX_REACH_RADIUS_M, MAX_ROBOT_RADIUS_M
from sgplan.safeio import check_regular_file, load_yaml, quote, read_text
from sgplan.scene.fields import Fields, is_int
from sgplan.scene.model import Building, Floor, Room, SceneObject, StairsEnd

BUILDING_FILE = "building.yaml"
INITIAL_POSITIONS_FILE = "initial_positions.yaml"
RADIUS_CONFIG_FILE = "radius_config.bash"

PNG_OFFSET = 5
"""Stored PNG value minus this is the semantic value (the authors' ``+ SOC.NA`` with ``NA = -5``)."""


def load_authors_scene(path: str | Path) -> Building:
    """Load one scene folder of the authors' data (e.g. ``.../gibson-3dsg/Benevolence``) with its rasters.

    Parameters
    ----------
    path:
        The scene folder, or its ``building.yaml``.

    Returns
    -------
    Building
        Floors ``0..n-1`` with decoded ``int16`` rasters (PNG value - 5), rooms, objects, doors, stairs;
        ``robot_radius_m`` / ``reach_radius_m`` / ``initial_cells`` from the optional files.

    Raises
    ------
    SceneError
        The path does not exist, ``building.yaml`` or a map is missing or unreadable, a field is missing or
        of the wrong type, a map does not match ``grid_map_size``, a room's ``parent_id`` is not its floor,
        a map holds an id the YAML does not declare, or references between nodes do not resolve. The
        message names the file and the floor / room / object and field at fault.
    """
    return load_authors_scene_with_inputs(path)[0]


def load_authors_scene_with_inputs(path: str | Path) -> tuple[Building, list[Path]]:
    """:func:`load_authors_scene`, and every file it read or looked for: ``building.yaml``, the maps, and
    the optional files (listed whether present or not), for :mod:`sgplan.scene.cache` to hash."""
    folder, yaml_path = locate(path)
    document = _read_yaml(yaml_path)
    top = Fields(document, yaml_path, "building")
    floors_data = top.mapping("floors", allow_null=False)
    num_floors = top.integer("num_floors", len(floors_data))
    if num_floors < 1 or set(floors_data) != set(range(num_floors)):
        raise top.error(
            f"field 'floors' must be keyed 0..{num_floors - 1} (num_floors = {num_floors}), "
            f"got keys {quote(list(floors_data))}"
        )
    floor_fields = [Fields(floors_data[k], yaml_path, f"floor {k}") for k in range(num_floors)]
    shape = _common_grid_shape(floor_fields)

    floors = [_read_floor(f, k, num_floors, shape) for k, f in enumerate(floor_fields)]
    room_uuid_by_id = {room.id: room.uuid for floor in floors for room in floor.rooms.values()}
    for floor, fields in zip(floors, floor_fields):
        _link_rooms(floor, fields, room_uuid_by_id, yaml_path, shape)
        floor.up_stairs = _read_stairs(fields, "up", room_uuid_by_id, shape)
        floor.down_stairs = _read_stairs(fields, "down", room_uuid_by_id, shape)
    _check_stairs_pairs(floors, yaml_path)
    inputs = [yaml_path, folder / RADIUS_CONFIG_FILE, folder / INITIAL_POSITIONS_FILE]
    for floor, fields in zip(floors, floor_fields):
        inputs += _read_rasters(folder, fields, floor, shape)

    robot_radius_m, reach_radius_m = _read_radius_config(folder / RADIUS_CONFIG_FILE)
    initial_cells = _read_initial_positions(folder / INITIAL_POSITIONS_FILE, num_floors, shape)
    building_id, uuid, name = top.integer("id"), top.integer("uuid"), top.text("name")
    try:
        building = Building(
            id=building_id,
            uuid=uuid,
            name=name,
            floors=floors,
            source=folder,
            robot_radius_m=robot_radius_m,
            reach_radius_m=reach_radius_m,
            initial_cells=initial_cells,
        )
    except SceneError as error:  # the model's own checks (unique ids / uuids) know no file
        raise SceneError(str(error), yaml_path) from None
    return building, inputs


def is_authors_scene(path: str | Path) -> bool:
    """True if ``path`` is a folder holding ``building.yaml`` or is such a file."""
    path = Path(path)
    return (path.is_dir() and (path / BUILDING_FILE).is_file()) or (
        path.is_file() and path.name == BUILDING_FILE
    )


# -- files ---------------------------------------------------------------------------------------------


def locate(path: str | Path) -> tuple[Path, Path]:
    """The scene folder and its ``building.yaml`` for ``path`` (either of them); SceneError if neither."""
    path = Path(path).expanduser()
    if not path.exists():
        raise SceneError("scene path does not exist", path)
    if path.is_file():
        if path.name != BUILDING_FILE:
            raise SceneError(f"not an authors' scene: expected a folder holding {BUILDING_FILE}", path)
        return path.parent, path
    yaml_path = path / BUILDING_FILE
    if not yaml_path.is_file():
        raise SceneError(f"scene folder has no {BUILDING_FILE}", path)
    return path, yaml_path


def _read_yaml(path: Path) -> Any:
    return load_yaml(path, SceneError, "YAML file")


def _optional_file(path: Path) -> bool:
    """Whether the optional file ``path`` is present; something else under its name is an error."""
    if not os.path.lexists(path):
        return False
    check_regular_file(path, SceneError, "file")
    return True


def _read_png(path: Path, fields: Fields, key: str, shape: tuple[int, int]) -> np.ndarray:
    """Decode one 8-bit grayscale map to ``int16`` semantic values (stored value - 5)."""
    if not os.path.lexists(path):
        raise fields.error(f"field {key!r} names {path}, which does not exist")
    size = check_regular_file(path, SceneError, "map")
    from PIL import Image  # only when a map is decoded (a cached scene needs none)

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            image = Image.open(path)
        with image:
            if image.mode != "L":
                raise SceneError(f"map must be an 8-bit grayscale PNG (mode L), got mode {image.mode}", path)
            # The header size is checked before decoding, so a wrong (or huge) map costs nothing.
            if (image.height, image.width) != shape:
                raise SceneError(
                    f"map is {image.height}x{image.width} (rows x cols) but {fields.entity} has "
                    f"grid_map_size {shape[0]}x{shape[1]}",
                    path,
                )
            stored = np.asarray(image, dtype=np.uint8)
    except SceneError:
        raise
    except (Image.DecompressionBombError, Image.DecompressionBombWarning) as error:
        raise SceneError(
            f"refusing to decode the map ({size:,} bytes): {quote(str(error), 200)}", path
        ) from None
    except (OSError, SyntaxError, ValueError, MemoryError) as error:
        raise SceneError(f"cannot decode map ({size:,} bytes): {quote(str(error), 200)}", path) from None
    return stored.astype(np.int16) - PNG_OFFSET


def _read_radius_config(path: Path) -> tuple[float | None, float | None]:
    """``ROBOT_RADIUS`` and ``OBJECT_REACH_RADIUS`` (m) from the bash file, parsed, never executed."""
    if not _optional_file(path):
        return None, None
    values: dict[str, float] = {}
    limits = {"ROBOT_RADIUS": MAX_ROBOT_RADIUS_M, "OBJECT_REACH_RADIUS": MAX_REACH_RADIUS_M}
    assignment = re.compile(r"^\s*(?:export\s+)?(ROBOT_RADIUS|OBJECT_REACH_RADIUS)=(.*)$")
    for number, line in enumerate(read_text(path, SceneError, "radius file", 2**20).splitlines(), 1):
        match = assignment.match(line)
        if match is None:
            continue
        name, text = match.group(1), match.group(2).split("#")[0].strip().strip("'\"")
        try:
            value = float(text)
        except ValueError:
            message = f"line {number}: {name} must be a number of metres, got {quote(text)}"
            raise SceneError(message, path) from None
        if not 0 < value <= limits[name]:
            raise SceneError(
                f"line {number}: {name} must be a positive number of metres, at most {limits[name]:g}, got "
                f"{quote(text)}",
                path,
            )
        values[name] = value
    return values.get("ROBOT_RADIUS"), values.get("OBJECT_REACH_RADIUS")


def _read_initial_positions(
    path: Path, num_floors: int, shape: tuple[int, int]
) -> list[tuple[int, int, int]]:
    """The optional start cells ``(row, col, floor)``; each must lie on the grid of an existing floor."""
    if not _optional_file(path):
        return []
    document = _read_yaml(path)
    if document is None:
        return []
    if not isinstance(document, list):
        raise SceneError("must be a list of [row, col, floor] triples", path)
    cells = []
    for index, item in enumerate(document):
        if not (isinstance(item, list) and len(item) == 3 and all(is_int(v) for v in item)):
            raise SceneError(f"entry {index} must be [row, col, floor] integers, got {quote(item)}", path)
        row, col, floor = (int(v) for v in item)
        if not (0 <= floor < num_floors and 0 <= row < shape[0] and 0 <= col < shape[1]):
            raise SceneError(
                f"entry {index} {quote(item)} is off the grid ({shape[0]}x{shape[1]} cells, {num_floors} "
                "floors)",
                path,
            )
        cells.append((row, col, floor))
    return cells


# -- nodes ---------------------------------------------------------------------------------------------


def _common_grid_shape(floor_fields: list[Fields]) -> tuple[int, int]:
    shapes = []
    for fields in floor_fields:
        rows, cols = fields.int_list("grid_map_size", 2)
        if rows < 1 or cols < 1 or rows * cols > MAX_GRID_CELLS:
            raise fields.error(
                f"field 'grid_map_size' must be positive and at most {MAX_GRID_CELLS:,} cells, got "
                f"{[rows, cols]}"
            )
        shapes.append((rows, cols))
    if len(set(shapes)) != 1:
        raise floor_fields[0].error(f"all floors must share one grid_map_size, got {quote(shapes)}")
    return shapes[0]


def _read_floor(fields: Fields, index: int, num_floors: int, shape: tuple[int, int]) -> Floor:
    if fields.integer("id") != index:
        raise fields.error(f"field 'id' is {quote(fields.raw('id'))} but the floor is keyed {index}")
    resolution = fields.vector("grid_map_resolution", 2)
    if not (resolution > 0).all():
        raise fields.error(f"field 'grid_map_resolution' must be positive, got {resolution.tolist()}")
    origin = fields.vector("grid_map_origin", 2)
    floor = Floor(
        index=index,
        name=str(fields.raw("name", chr(ord("A") + index))),
        uuid=fields.integer("uuid"),
        origin_m=(float(origin[0]), float(origin[1])),
        resolution_m=(float(resolution[0]), float(resolution[1])),
        ground_z_m=fields.number("ground_z"),
        cat_map=np.zeros((0, 0), np.int16),
        room_map=np.zeros((0, 0), np.int16),
    )
    for key, data in fields.mapping("rooms").items():
        room_fields = Fields(data, fields.path, f"room {key} (floor {index})")
        room = _read_room(room_fields, key, floor, num_floors, shape)
        floor.rooms[room.id] = room
    return floor


def _read_room(fields: Fields, key: object, floor: Floor, num_floors: int, shape: tuple[int, int]) -> Room:
    room_id = fields.integer("id")
    if room_id != key or room_id <= 0:
        raise fields.error(f"field 'id' is {room_id} but the room is keyed {quote(key)} (ids are positive)")
    parent = fields.integer("parent_id")
    if parent != floor.index:
        raise fields.error(
            f"parent_id {parent} does not name its floor {floor.index}"
            + ("" if 0 <= parent < num_floors else f" (unknown floor: floors are 0..{num_floors - 1})")
        )
    if fields.integer("parent_uuid", floor.uuid) != floor.uuid:
        raise fields.error(f"parent_uuid {fields.raw('parent_uuid')} is not floor {floor.index}'s uuid")
    room = Room(
        id=room_id,
        uuid=fields.integer("uuid"),
        name=fields.text("name"),
        floor=floor.index,
        location_m=fields.vector("location", 3),
        size_m=fields.vector("size", 3),
        grid_min=_grid_cell(fields, "grid_map_min", shape),
        grid_max=_grid_cell(fields, "grid_map_max", shape),
    )
    for object_key, data in fields.mapping("objects").items():
        entity = f"object {object_key} (room {room_id})"
        obj = _read_object(Fields(data, fields.path, entity), object_key, room, shape)
        room.objects[obj.id] = obj
    return room


def _read_object(fields: Fields, key: object, room: Room, shape: tuple[int, int]) -> SceneObject:
    object_id = fields.integer("id")
    if object_id != key or object_id <= 0:
        raise fields.error(
            f"field 'id' is {object_id} but the object is keyed {quote(key)} (ids are positive)"
        )
    if fields.integer("parent_id") != room.id:
        raise fields.error(f"parent_id {fields.raw('parent_id')} is not its room {room.id}")
    if fields.integer("parent_uuid", room.uuid) != room.uuid:
        raise fields.error(f"parent_uuid {fields.raw('parent_uuid')} is not room {room.id}'s {room.uuid}")
    return SceneObject(
        id=object_id,
        uuid=fields.integer("uuid"),
        name=fields.text("name"),
        room_id=room.id,
        room_uuid=room.uuid,
        location_m=fields.vector("location", 3),
        size_m=fields.vector("size", 3),
        grid_min=_grid_cell(fields, "grid_map_min", shape),
        grid_max=_grid_cell(fields, "grid_map_max", shape),
        action_affordance=fields.strings("action_affordance"),
    )


def _grid_cell(fields: Fields, key: str, shape: tuple[int, int]) -> tuple[int, int]:
    row, col = fields.cell(key)
    if not (0 <= row < shape[0] and 0 <= col < shape[1]):
        raise fields.error(f"field {key!r} {[row, col]} is off the {shape[0]}x{shape[1]} grid")
    return (row, col)


def _link_rooms(
    floor: Floor, fields: Fields, room_uuid_by_id: Mapping[int, int], path: Path, shape: tuple[int, int]
) -> None:
    """Fill connections (uuids resolved through ids) and door cells of every room of ``floor``."""
    rooms_data = fields.mapping("rooms")
    for key, room in floor.rooms.items():
        room_fields = Fields(rooms_data[key], path, f"room {room.id} (floor {floor.index})")
        ids = room_fields.int_list("connected_room_ids", allow_null=True)
        unknown = [i for i in ids if i not in room_uuid_by_id]
        if unknown:
            raise room_fields.error(f"connected_room_ids names unknown room id(s) {quote(unknown)}")
        uuids = [room_uuid_by_id[i] for i in ids]
        listed = room_fields.int_list("connected_room_uuids", allow_null=True)
        if sorted(listed) != sorted(uuids):
            raise room_fields.error(
                f"connected_room_uuids {quote(sorted(listed))} are not the uuids {quote(sorted(uuids))} of "
                f"connected_room_ids {quote(ids)}"
            )
        room.connected_room_ids = tuple(ids)
        room.connected_room_uuids = tuple(uuids)
        for neighbour, cells in room_fields.mapping("door_grids").items():
            if not is_int(neighbour) or neighbour not in room_uuid_by_id:
                raise room_fields.error(f"door_grids names unknown room id {quote(neighbour)}")
            room.door_cells[int(neighbour)] = _door_cells(room_fields, int(neighbour), cells, shape)


def _door_cells(fields: Fields, neighbour: int, cells: object, shape: tuple[int, int]) -> np.ndarray:
    """An ``(n, 2)`` int32 array of ``[row, col]`` door cells, each on the grid."""
    try:
        array = np.array(cells if cells is not None else [], dtype=np.int64).reshape(-1, 2)
        valid = isinstance(cells, list) and all(
            isinstance(c, list) and len(c) == 2 and all(is_int(v) for v in c) for c in cells
        )
    except (TypeError, ValueError):
        valid = False
    if not valid:
        raise fields.error(f"door_grids[{neighbour}] must be a list of [row, col] integer pairs")
    off = (array < 0).any(axis=1) | (array[:, 0] >= shape[0]) | (array[:, 1] >= shape[1])
    if off.any():
        raise fields.error(f"door_grids[{neighbour}] cell {array[off][0].tolist()} is off the grid")
    return array.astype(np.int32)


def _read_stairs(
    fields: Fields, direction: str, room_uuid_by_id: Mapping[int, int], shape: tuple[int, int]
) -> StairsEnd | None:
    """The floor's ``up`` or ``down`` staircase end, or ``None`` when ``<direction>_stairs_id`` is -1."""
    room_id = fields.integer(f"{direction}_stairs_id", -1)
    if room_id == -1:
        return None
    if room_id not in room_uuid_by_id:
        raise fields.error(f"{direction}_stairs_id {room_id} is not a room of the building")
    uuid = room_uuid_by_id[room_id]
    if fields.integer(f"{direction}_stairs_uuid", uuid) != uuid:
        raise fields.error(
            f"{direction}_stairs_uuid {fields.raw(f'{direction}_stairs_uuid')} is not room {room_id}'s {uuid}"
        )
    if fields.raw(f"{direction}_stairs_portal", None) is None:
        raise fields.error(f"{direction}_stairs_id is {room_id} but {direction}_stairs_portal is missing")
    cost = fields.number(f"{direction}_stairs_cost")
    if cost <= 0:
        raise fields.error(f"{direction}_stairs_cost must be positive metres, got {cost}")
    return StairsEnd(
        room_id=room_id,
        room_uuid=uuid,
        portal=_grid_cell(fields, f"{direction}_stairs_portal", shape),
        cost_m=cost,
    )


def _check_stairs_pairs(floors: list[Floor], path: Path) -> None:
    """Floor k's up stairs and floor k+1's down stairs must be the same staircase at the same cost."""
    for lower, upper in zip(floors, [*floors[1:], None]):
        up, down = lower.up_stairs, upper.down_stairs if upper is not None else None
        if (up is None) != (down is None) or (
            up is not None and down is not None and (up.room_id != down.room_id or up.cost_m != down.cost_m)
        ):
            raise SceneError(
                f"floor {lower.index}'s up stairs ({_stairs_text(up)}) do not match floor "
                f"{lower.index + 1}'s down stairs ({_stairs_text(down)})",
                path,
            )
    if floors[0].down_stairs is not None:
        raise SceneError("floor 0 has down stairs but there is no floor below it", path)


def _stairs_text(end: StairsEnd | None) -> str:
    return "none" if end is None else f"room {end.room_id}, cost {end.cost_m} m"


def _read_rasters(folder: Path, fields: Fields, floor: Floor, shape: tuple[int, int]) -> list[Path]:
    """Decode the floor's maps into it and check them: every id they store must be declared. Returns the
    two map files."""
    cat_path, room_path = folder / fields.text("cat_map"), folder / fields.text("room_map")
    floor.cat_map = _read_png(cat_path, fields, "cat_map", shape)
    floor.room_map = _read_png(room_path, fields, "room_map", shape)
    objects, rooms = floor.undeclared_map_ids()
    for ids, kind, key in ((objects, "object", "cat_map"), (rooms, "room", "room_map")):
        if ids:
            raise SceneError(
                f"holds {kind} id(s) {ids} that floor {floor.index} of building.yaml does not declare",
                folder / fields.text(key),
            )
    return [cat_path, room_path]
