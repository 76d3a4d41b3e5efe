"""Scene changes as typed values, and their YAML / JSON form (``docs/execution.md``; JSON Schema in
``docs/changes.schema.json``).

A change says what happened to the building while a mission runs: a door closed or opened, an area
blocked or cleared, an object moved, added or removed, or a newer scene graph of the same building
arrived. Rooms and objects are named as people name them (``kitchen``, ``bathroom on floor 1``,
``room_5``; ``object_27``, ``chair in the kitchen``: :mod:`sgplan.scene.lookup`); positions and sizes are
metres in the scene's frame (``x`` along grid rows, ``y`` along columns).

These values only describe; :mod:`sgplan.execution.world` checks them against a building and applies
them. Their mapping form (``to_dict`` / :func:`change_from_dict`) is the one of the changes file::

    version: 1
    changes:
      - {kind: close_door, rooms: [kitchen, corridor on floor 0], when: {after_m: 4.0}}
      - {kind: block, floor: 0, box_m: [2.0, 1.0, 3.0, 1.5], name: trolley}
      - {kind: move_object, object: object_27, to_xy_m: [5.2, 3.1]}

``when`` (a :class:`Trigger`) is read by ``sgplan simulate`` only: after the robot has driven some
metres, on entering a room, or at a waypoint of the current plan.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

from sgplan.errors import SceneError
from sgplan.safeio import load_yaml, quote
from sgplan.scene.fields import Fields, is_int, is_number

FORMAT_VERSION = 1
"""The version of the changes file (``version:``) this module reads and writes."""


def _points(value: Any, fields: Fields, key: str, count: int | None = None) -> tuple[float, ...]:
    """A flat tuple of finite numbers (``count`` of them when given), else a :class:`SceneError`."""
    items = list(value) if isinstance(value, (list, tuple)) else None
    if items is None or (count is not None and len(items) != count) or not all(
        is_number(v) and math.isfinite(float(v)) for v in items
    ):
        size = f"{count} " if count is not None else ""
        raise fields.error(f"field {key!r} must be a list of {size}finite numbers (metres), "
                           f"got {quote(value)}")
    return tuple(float(v) for v in items)


def _box(value: Any, fields: Fields, key: str = "box_m") -> tuple[float, float, float, float]:
    x0, y0, x1, y1 = _points(value, fields, key, 4)
    if not (x0 < x1 and y0 < y1):
        raise fields.error(f"field {key!r} must be [x0, y0, x1, y1] with x0 < x1 and y0 < y1, "
                           f"got {quote(value)}")
    return (x0, y0, x1, y1)


def _polygon(value: Any, fields: Fields) -> tuple[tuple[float, float], ...]:
    rows = list(value) if isinstance(value, (list, tuple)) else []
    if len(rows) < 3:
        raise fields.error(f"field 'polygon_m' must list at least 3 [x, y] vertices, got {quote(value)}")
    vertices = []
    for row in rows:
        x, y = _points(row, fields, "polygon_m", 2)
        vertices.append((x, y))
    return tuple(vertices)


def _floor(fields: Fields, required: bool = True) -> int | None:
    if not required and not fields.has("floor"):
        return None
    floor = fields.integer("floor")
    if floor < 0:
        raise fields.error(f"field 'floor' must be a floor index >= 0, got {floor}")
    return floor


def _name(fields: Fields, key: str, required: bool = True) -> str | None:
    if not required and fields.raw(key, None) is None:
        return None
    text = fields.text(key).strip()
    if not text:
        raise fields.error(f"field {key!r} must not be empty")
    return text


@dataclass(frozen=True)
class Area:
    """A box ``(x0, y0, x1, y1)`` or a polygon of ``(x, y)`` vertices on a floor, metres; it holds the
    cells whose centres lie inside it."""

    floor: int
    box_m: tuple[float, float, float, float] | None = None
    polygon_m: tuple[tuple[float, float], ...] | None = None

    def __post_init__(self) -> None:
        if (self.box_m is None) == (self.polygon_m is None):
            raise SceneError("an area is a box_m or a polygon_m (exactly one)")

    def to_dict(self) -> dict[str, Any]:
        shape = ({"box_m": list(self.box_m)} if self.box_m is not None
                 else {"polygon_m": [list(p) for p in self.polygon_m or ()]})
        return {"floor": self.floor, **shape}

    def describe(self) -> str:
        if self.box_m is not None:
            x0, y0, x1, y1 = self.box_m
            return f"the box x {x0:g}..{x1:g} m, y {y0:g}..{y1:g} m on floor {self.floor}"
        return f"the polygon of {len(self.polygon_m or ())} vertices on floor {self.floor}"

    @classmethod
    def read(cls, fields: Fields) -> Area:
        if fields.has("box_m") == fields.has("polygon_m"):
            raise fields.error("give the area as box_m: [x0, y0, x1, y1] or polygon_m: [[x, y], ...] "
                               "(exactly one)")
        floor = _floor(fields)
        assert floor is not None
        if fields.has("box_m"):
            return cls(floor, box_m=_box(fields.raw("box_m"), fields))
        return cls(floor, polygon_m=_polygon(fields.raw("polygon_m"), fields))


@dataclass(frozen=True)
class CloseDoor:
    """Close the door between two rooms: the cells on both sides of their shared boundary become
    obstacles until an :class:`OpenDoor` of the same rooms."""

    rooms: tuple[str, str]
    kind: ClassVar[str] = "close_door"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "rooms": list(self.rooms)}


@dataclass(frozen=True)
class OpenDoor:
    """Open a door an earlier :class:`CloseDoor` closed."""

    rooms: tuple[str, str]
    kind: ClassVar[str] = "open_door"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "rooms": list(self.rooms)}


@dataclass(frozen=True)
class Block:
    """Make the free cells of an area obstacles (a trolley, a spill, a cordon), under a ``name`` that an
    :class:`Unblock` can use (default: ``block N``, N counting the run's blocks)."""

    area: Area
    name: str | None = None
    kind: ClassVar[str] = "block"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, **self.area.to_dict(), **({"name": self.name} if self.name else {})}


@dataclass(frozen=True)
class Unblock:
    """Clear the blocks named ``name``, or every block's cells inside ``area`` (door closures excepted:
    :class:`OpenDoor` opens them). The scene's own obstacles stay: remove an object to clear one."""

    name: str | None = None
    area: Area | None = None
    kind: ClassVar[str] = "unblock"

    def __post_init__(self) -> None:
        if (self.name is None) == (self.area is None):
            raise SceneError("unblock takes a name or an area (exactly one)")

    def to_dict(self) -> dict[str, Any]:
        target = {"name": self.name} if self.name is not None else (self.area.to_dict() if self.area else {})
        return {"kind": self.kind, **target}


@dataclass(frozen=True)
class MoveObject:
    """Move an object so that its footprint's centre lies at ``to_xy_m`` (metres) on ``floor`` (default:
    its own). It then belongs to the room there."""

    object: str
    to_xy_m: tuple[float, float]
    floor: int | None = None
    kind: ClassVar[str] = "move_object"

    def to_dict(self) -> dict[str, Any]:
        where = {"floor": self.floor} if self.floor is not None else {}
        return {"kind": self.kind, "object": self.object, "to_xy_m": list(self.to_xy_m), **where}


@dataclass(frozen=True)
class AddObject:
    """Add an object of ``category`` with a box footprint of ``size_m`` (along x, y) centred at
    ``at_xy_m`` on ``floor``; it gets the next free id and uuid."""

    category: str
    at_xy_m: tuple[float, float]
    floor: int
    size_m: tuple[float, float]
    height_m: float = 1.0
    kind: ClassVar[str] = "add_object"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "category": self.category, "at_xy_m": list(self.at_xy_m),
                "floor": self.floor, "size_m": list(self.size_m), "height_m": self.height_m}


@dataclass(frozen=True)
class RemoveObject:
    """Remove an object; the cells it covered take the category of the nearest cell it did not cover
    (a chair on the floor leaves floor, a cup on a table leaves table)."""

    object: str
    kind: ClassVar[str] = "remove_object"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "object": self.object}


@dataclass(frozen=True)
class NewSceneGraph:
    """A newer scene graph of the same building (e.g. a mapper's later export): its maps and objects
    replace the current ones, the blocks and closed doors stay. ``scene`` is anything
    :func:`sgplan.load_scene` reads; objects whose centre moved less than ``tolerance_m`` are not reported
    as moved."""

    scene: str
    tolerance_m: float = 0.05
    kind: ClassVar[str] = "scene_graph"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "scene": self.scene, "tolerance_m": self.tolerance_m}


Change = CloseDoor | OpenDoor | Block | Unblock | MoveObject | AddObject | RemoveObject | NewSceneGraph
"""Any scene change."""

CHANGE_KINDS: dict[str, type] = {c.kind: c for c in (CloseDoor, OpenDoor, Block, Unblock, MoveObject,
                                                     AddObject, RemoveObject, NewSceneGraph)}
"""Change classes by their ``kind``."""


@dataclass(frozen=True)
class Trigger:
    """When ``sgplan simulate`` applies a change: once the robot has driven ``after_m`` metres, on
    entering the room ``enter``, or on reaching waypoint ``waypoint`` (an index into the current plan's
    simplified waypoints). Exactly one is set."""

    after_m: float | None = None
    enter: str | None = None
    waypoint: int | None = None

    def __post_init__(self) -> None:
        if sum(v is not None for v in (self.after_m, self.enter, self.waypoint)) != 1:
            raise SceneError("a trigger is one of after_m, enter, waypoint")

    def to_dict(self) -> dict[str, Any]:
        return {k: v for k, v in (("after_m", self.after_m), ("enter", self.enter),
                                  ("waypoint", self.waypoint)) if v is not None}

    def describe(self) -> str:
        if self.after_m is not None:
            return f"after {self.after_m:g} m"
        return f"on entering {self.enter}" if self.enter is not None else f"at waypoint {self.waypoint}"


@dataclass(frozen=True)
class ScheduledChange:
    """A change of a changes file and, for ``sgplan simulate``, when it happens (``None``: at once)."""

    change: Change
    when: Trigger | None = None

    def to_dict(self) -> dict[str, Any]:
        return {**self.change.to_dict(), **({"when": self.when.to_dict()} if self.when else {})}


def _rooms(fields: Fields) -> tuple[str, str]:
    value = fields.raw("rooms")
    if not (isinstance(value, (list, tuple)) and len(value) == 2 and all(isinstance(v, str) and v.strip()
                                                                           for v in value)):
        raise fields.error(f"field 'rooms' must name two rooms, e.g. [kitchen, corridor], got {quote(value)}")
    if value[0].strip() == value[1].strip():
        raise fields.error(f"field 'rooms' names the same room twice ({value[0]!r})")
    return (value[0].strip(), value[1].strip())


def _size(fields: Fields) -> tuple[float, float]:
    sx, sy = _points(fields.raw("size_m"), fields, "size_m", 2)
    if not (sx > 0 and sy > 0):
        raise fields.error(f"field 'size_m' must be two positive lengths, got {quote(fields.raw('size_m'))}")
    return (sx, sy)


def _read_change(fields: Fields, kind: str) -> Change:
    """The change of ``kind`` whose fields are ``fields`` (every field checked; unknown ones refused)."""
    if kind in ("close_door", "open_door"):
        return (CloseDoor if kind == "close_door" else OpenDoor)(_rooms(fields))
    if kind == "block":
        return Block(Area.read(fields), _name(fields, "name", required=False))
    if kind == "unblock":
        if fields.has("name") == (fields.has("box_m") or fields.has("polygon_m")):
            raise fields.error("give the blocks to clear as name: or as an area (box_m / polygon_m with "
                               "floor)")
        if fields.has("name"):
            return Unblock(name=_name(fields, "name"))
        return Unblock(area=Area.read(fields))
    if kind == "move_object":
        x, y = _points(fields.raw("to_xy_m"), fields, "to_xy_m", 2)
        return MoveObject(_name(fields, "object") or "", (x, y), _floor(fields, required=False))
    if kind == "add_object":
        x, y = _points(fields.raw("at_xy_m"), fields, "at_xy_m", 2)
        floor = _floor(fields)
        assert floor is not None
        height = fields.number("height_m", 1.0)
        if height <= 0:
            raise fields.error(f"field 'height_m' must be positive metres, got {height}")
        return AddObject(_name(fields, "category") or "", (x, y), floor, _size(fields), height)
    if kind == "remove_object":
        return RemoveObject(_name(fields, "object") or "")
    tolerance = fields.number("tolerance_m", 0.05)
    if tolerance < 0:
        raise fields.error(f"field 'tolerance_m' must be >= 0 metres, got {tolerance}")
    return NewSceneGraph(_name(fields, "scene") or "", tolerance)


_FIELDS = {
    "close_door": {"rooms"}, "open_door": {"rooms"}, "block": {"floor", "box_m", "polygon_m", "name"},
    "unblock": {"floor", "box_m", "polygon_m", "name"}, "move_object": {"object", "to_xy_m", "floor"},
    "add_object": {"category", "at_xy_m", "floor", "size_m", "height_m"}, "remove_object": {"object"},
    "scene_graph": {"scene", "tolerance_m"},
}


def change_from_dict(data: object, where: str = "change", path: Path | None = None) -> Change:
    """The :data:`Change` of a mapping (its ``kind`` and fields; see the module).

    Raises
    ------
    SceneError
        naming ``where`` (e.g. ``change 3``), the field and what it must be; unknown kinds and fields
        are refused, not ignored.
    """
    fields = Fields(data, path, where)
    kind = fields.text("kind").strip()
    if kind not in CHANGE_KINDS:
        raise fields.error(f"unknown kind {kind!r}; use one of {', '.join(CHANGE_KINDS)}")
    fields.entity = f"{where} ({kind})"
    unknown = sorted(str(k) for k in fields.data if k not in _FIELDS[kind] | {"kind", "when"})
    if unknown:
        raise fields.error(f"unknown field(s) {', '.join(unknown)}; a {kind} takes "
                           f"{', '.join(sorted(_FIELDS[kind]))}")
    return _read_change(fields, kind)


def _trigger(data: object, where: str, path: Path | None) -> Trigger:
    fields = Fields(data, path, f"{where} (when)")
    keys = [k for k in ("after_m", "enter", "waypoint") if fields.has(k)]
    extra = sorted(str(k) for k in fields.data if k not in ("after_m", "enter", "waypoint"))
    if len(keys) != 1 or extra:
        raise fields.error("give exactly one of after_m: METRES, enter: ROOM, waypoint: INDEX")
    if keys[0] == "after_m":
        metres = fields.number("after_m")
        if metres < 0:
            raise fields.error(f"field 'after_m' must be >= 0 metres, got {metres}")
        return Trigger(after_m=metres)
    if keys[0] == "enter":
        return Trigger(enter=_name(fields, "enter"))
    value = fields.raw("waypoint")
    if not is_int(value) or value < 0:
        raise fields.error(f"field 'waypoint' must be a waypoint index >= 0, got {quote(value)}")
    return Trigger(waypoint=int(value))


def scheduled_from_dict(data: object, where: str = "change", path: Path | None = None) -> ScheduledChange:
    """A :class:`ScheduledChange`: the change of ``data`` and its optional ``when``."""
    change = change_from_dict(data, where, path)
    when = data.get("when") if isinstance(data, Mapping) else None
    return ScheduledChange(change, _trigger(when, where, path) if when is not None else None)


def changes_from_document(document: object, path: Path | None = None) -> list[ScheduledChange]:
    """The changes of a changes document (``{version: 1, changes: [...]}``).

    Raises
    ------
    SceneError
        for another shape or version, or a bad change (named by its position, from 1).
    """
    fields = Fields(document, path, "changes file")
    version = fields.integer("version", FORMAT_VERSION)
    if version != FORMAT_VERSION:
        raise fields.error(f"version {version} is not supported (this sgplan reads version {FORMAT_VERSION})")
    extra = sorted(str(k) for k in fields.data if k not in ("version", "changes"))
    if extra:
        raise fields.error(f"unknown field(s) {', '.join(extra)}; a changes file has version and changes")
    items = fields.raw("changes")
    if not isinstance(items, Sequence) or isinstance(items, (str, bytes)):
        raise fields.error(f"field 'changes' must be a list of changes, got {quote(items)}")
    return [scheduled_from_dict(item, f"change {i}", path) for i, item in enumerate(items, 1)]


def read_changes(path: str | Path) -> list[ScheduledChange]:
    """The changes of a YAML or JSON changes file (JSON is YAML).

    Raises
    ------
    SceneError
        an unreadable file, or anything :func:`changes_from_document` refuses.
    """
    path = Path(path)
    return changes_from_document(load_yaml(path, SceneError, "changes file"), path)


def changes_document(changes: Sequence[Change | ScheduledChange]) -> dict[str, Any]:
    """The changes file's document of ``changes`` (:func:`changes_from_document` reads it back)."""
    return {"version": FORMAT_VERSION, "changes": [c.to_dict() for c in changes]}
