"""A ROS map_server map (``map.yaml`` + image) and a rooms file -> a one-floor building.

``map.yaml`` fields (map_server's): ``image`` (path relative to the yaml), ``resolution`` (m/pixel),
``origin`` ``[x, y, yaw]`` (the lower-left pixel's corner; ``yaw`` must be 0), ``negate`` (0/1),
``occupied_thresh``, ``free_thresh`` and ``mode`` (``trinary``, the default; ``scale`` and ``raw``).
A pixel's occupancy is ``p = (255 - v) / 255`` (``v / 255`` when negated; colour pixels are averaged);
``p > occupied_thresh`` is an obstacle (wall), ``p < free_thresh`` is free, anything between is unknown
(outside). In ``raw`` mode the pixel value is the occupancy in percent.

The rooms file (YAML, metres in the map frame)::

    rooms:
      - name: kitchen                       # a category; repeat it for several kitchens
        polygon: [[x, y], [x, y], [x, y], ...]
    objects:                                # optional
      - name: refrigerator
        position: [x, y]                    # a point: the one cell it stands in
      - name: table
        box: {center: [x, y], size: [dx, dy], yaw: 0.0, height: 0.75}   # yaw in radians
        room: kitchen                       # optional: else the room under its centre

Every cell of the map keeps the map's resolution (``--resolution`` is not used: the map has one).
Free cells inside no room polygon stay out of every room, so the robot does not enter them.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from PIL import Image, UnidentifiedImageError

from sgplan.english import count
from sgplan.errors import SceneError
from sgplan.importers.assemble import FloorDraft, ImportResult, ObjectDraft, RoomDraft, Settings, assemble
from sgplan.importers.raster import GridFrame, polygon_area_m2, polygon_mask
from sgplan.scene.fields import is_number
from sgplan.scene.model import NO_ROOM, CatCode

MODES = ("trinary", "scale", "raw")
POINT_OBJECT_M = 1e-3
"""Half size of a point object's box: it covers the one cell its point lies in."""


def is_ros_map(path: Path) -> bool:
    """A ``.yaml`` file with map_server's ``image`` and ``resolution`` fields."""
    if not (path.is_file() and path.suffix.lower() in (".yaml", ".yml")):
        return False
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError):
        return False
    return isinstance(data, dict) and "image" in data and "resolution" in data


def _load_yaml(path: Path, what: str) -> dict[str, Any]:
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise SceneError(f"cannot read the {what}: {error.strerror}", path) from None
    except (UnicodeDecodeError, yaml.YAMLError) as error:
        raise SceneError(f"the {what} is not valid YAML: {error}", path) from None
    if not isinstance(data, dict):
        raise SceneError(f"the {what} must be a YAML mapping", path)
    return data


def _number(data: dict[str, Any], key: str, path: Path, default: float | None = None) -> float:
    value: Any = data.get(key, default)
    if not is_number(value) or not math.isfinite(float(value)):
        raise SceneError(f"field {key!r} must be a number, got {value!r}", path)
    return float(value)


def read_map(path: str | Path) -> tuple[np.ndarray, tuple[float, float], float]:
    """The map as sgplan cell codes ``(rows, cols)`` (row along x, col along y), its origin and resolution.

    Raises :class:`SceneError` for a missing or unreadable image, a bad field, or a rotated origin.
    """
    path = Path(path)
    data = _load_yaml(path, "map file")
    if "image" not in data or not isinstance(data["image"], str):
        raise SceneError("field 'image' (the map image, relative to the yaml) is required", path)
    resolution = _number(data, "resolution", path)
    if resolution <= 0:
        raise SceneError(f"field 'resolution' must be positive metres per pixel, got {resolution}", path)
    origin = data.get("origin")
    if not (isinstance(origin, list) and len(origin) == 3 and all(is_number(v) for v in origin)):
        raise SceneError(f"field 'origin' must be [x, y, yaw], got {origin!r}", path)
    if abs(float(origin[2])) > 1e-9:
        raise SceneError(
            f"origin yaw {origin[2]} is not 0: rotated maps are not supported (rotate the image)", path
        )
    negate = data.get("negate", 0)
    if negate not in (0, 1, True, False):
        raise SceneError(f"field 'negate' must be 0 or 1, got {negate!r}", path)
    occupied = _number(data, "occupied_thresh", path, 0.65)
    free = _number(data, "free_thresh", path, 0.196)
    if not 0 <= free <= occupied <= 1:
        raise SceneError(
            f"thresholds must satisfy 0 <= free_thresh ({free}) <= occupied_thresh ({occupied}) <= 1", path
        )
    mode = data.get("mode", "trinary")
    if mode not in MODES:
        raise SceneError(f"field 'mode' must be one of {', '.join(MODES)}, got {mode!r}", path)
    image_path = (path.parent / data["image"]).expanduser()
    try:
        with Image.open(image_path) as image:
            # map_server averages the colour channels; grey images are read as they are
            grey = image.mode in ("L", "I", "I;16", "F")
            value = np.asarray(image if grey else image.convert("RGB"), dtype=float)
    except FileNotFoundError:
        raise SceneError(f"the map image {image_path} does not exist", path) from None
    except (OSError, UnidentifiedImageError) as error:
        raise SceneError(f"cannot read the map image: {error}", image_path) from None
    if value.ndim == 3:
        value = value.mean(axis=2)
    if mode == "raw":
        occupancy = value / 100.0
    else:
        occupancy = value / 255.0 if negate else (255.0 - value) / 255.0
    codes = np.full(value.shape, CatCode.OUTSIDE, dtype=np.int16)
    codes[occupancy > occupied] = CatCode.WALL
    codes[occupancy < free] = CatCode.GROUND
    # image row 0 is the top (largest y); sgplan rows run along x and columns along y
    return codes[::-1, :].T.copy(), (float(origin[0]), float(origin[1])), resolution


def _points(value: Any, n: int | None, what: str, path: Path) -> np.ndarray:
    if not (
        isinstance(value, list)
        and all(isinstance(p, list) and len(p) == 2 and all(is_number(v) for v in p) for p in value)
    ):
        raise SceneError(f"{what} must be a list of [x, y] points in metres", path)
    points = np.array(value, dtype=float)
    if n is not None and len(points) != n:
        raise SceneError(f"{what} must hold {n} point(s)", path)
    return points


def import_ros_map(
    map_path: str | Path, rooms_path: str | Path, settings: Settings | None = None
) -> ImportResult:
    """The one-floor building of a map_server map and a rooms file (see the module docstring).

    Raises
    ------
    SceneError
        naming the file and the room or object for: a bad map field or image, no rooms, a room without a
        name or with a degenerate polygon (fewer than 3 points, no area, or no cell of the map), a
        malformed object, an object naming a room that does not exist.
    """
    settings = settings or Settings()
    map_path, rooms_path = Path(map_path), Path(rooms_path)
    cat, origin, resolution = read_map(map_path)
    frame = GridFrame(origin, resolution, (int(cat.shape[0]), int(cat.shape[1])))
    spec = _load_yaml(rooms_path, "rooms file")
    entries = spec.get("rooms")
    if not isinstance(entries, list) or not entries:
        raise SceneError("field 'rooms' must be a non-empty list of {name, polygon}", rooms_path)
    room_map = np.full(frame.shape, NO_ROOM, dtype=np.int16)
    rooms: list[RoomDraft] = []
    ids_by_name: dict[str, list[int]] = {}
    notes: list[str] = []
    for k, entry in enumerate(entries):
        label = f"room {k + 1}"
        if not isinstance(entry, dict) or not isinstance(entry.get("name"), str) or not entry["name"].strip():
            raise SceneError(
                f"{label}: needs a 'name' (its category, e.g. kitchen) and a 'polygon'", rooms_path
            )
        name = entry["name"].strip().lower().replace(" ", "_")
        label = f"room {k + 1} ({name})"
        polygon = _points(entry.get("polygon"), None, f"{label}: 'polygon'", rooms_path)
        if len(polygon) < 3 or polygon_area_m2(polygon) < resolution * resolution / 4:
            raise SceneError(
                f"{label}: degenerate polygon ({len(polygon)} points, area {polygon_area_m2(polygon):.3g} "
                "m^2)",
                rooms_path,
            )
        mask = polygon_mask(frame, polygon)
        if not mask.any():
            raise SceneError(
                f"{label}: the polygon covers no cell of the map (is it in the map frame, in metres?)",
                rooms_path,
            )
        overlap = int((mask & (room_map > 0)).sum())
        if overlap:
            notes.append(
                f"{label} overlaps earlier rooms on {count(overlap, 'cell')}; they stay with the earlier "
                "rooms"
            )
        room_map[mask & (room_map <= 0)] = k + 1
        rooms.append(RoomDraft(k + 1, name, 0, _number(entry, "height", rooms_path, 2.5)))
        ids_by_name.setdefault(name, []).append(k + 1)
    outside = int(((cat == CatCode.GROUND) & (room_map <= 0)).sum())
    if outside:
        notes.append(
            f"{count(outside, 'free cell')} of the map {'lies' if outside == 1 else 'lie'} in no room "
            "polygon; the robot will not enter them"
        )
    objects = [
        _object(entry, k, ids_by_name, rooms_path) for k, entry in enumerate(spec.get("objects") or [])
    ]
    floor = FloorDraft("A", 0.0, cat, room_map)
    result = assemble(map_path.stem, frame, [floor], rooms, objects, settings)
    result.notes[:0] = notes
    return result


def _object(entry: Any, k: int, ids_by_name: dict[str, list[int]], path: Path) -> ObjectDraft:
    label = f"object {k + 1}"
    if not isinstance(entry, dict) or not isinstance(entry.get("name"), str) or not entry["name"].strip():
        raise SceneError(f"{label}: needs a 'name' and a 'position' [x, y] or a 'box'", path)
    name = entry["name"].strip().lower()
    label = f"object {k + 1} ({name})"
    if "box" in entry:
        box = entry["box"]
        if not isinstance(box, dict):
            raise SceneError(f"{label}: 'box' must be a mapping {{center, size, yaw, height}}", path)
        center = _points([box.get("center")], 1, f"{label}: box 'center'", path)[0]
        size = _points([box.get("size")], 1, f"{label}: box 'size'", path)[0]
        if (size <= 0).any():
            raise SceneError(f"{label}: box 'size' must be positive metres, got {size.tolist()}", path)
        yaw, height = _number(box, "yaw", path, 0.0), _number(box, "height", path, 0.5)
        half = np.array([size[0] / 2, size[1] / 2, height / 2])
    elif "position" in entry:
        center = _points([entry.get("position")], 1, f"{label}: 'position'", path)[0]
        yaw, height = 0.0, _number(entry, "height", path, 0.5)
        half = np.array([POINT_OBJECT_M, POINT_OBJECT_M, height / 2])
    else:
        raise SceneError(f"{label}: needs a 'position' [x, y] or a 'box'", path)
    room_id = None
    if entry.get("room") is not None:
        room = str(entry["room"]).strip().lower().replace(" ", "_")
        if room not in ids_by_name:
            raise SceneError(f"{label}: room {entry['room']!r} is not in the rooms list", path)
        if len(ids_by_name[room]) == 1:
            room_id = ids_by_name[room][0]
    c, s = math.cos(yaw), math.sin(yaw)
    axes = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return ObjectDraft(name, 0, np.array([center[0], center[1], half[2]]), axes, half, room_id, label)
