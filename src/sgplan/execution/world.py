"""A building as scene changes leave it: :class:`SceneState` applies a scene change
(:mod:`sgplan.execution.changes`), checked against the building with a specific error when it cannot
apply, and says what it changed.

Two layers make the current building. The *scene* is the building's own category maps and objects, as
loaded and then edited by object moves, additions and removals and by newer scene graphs (permanent).
The *blocks* are areas and closed doors laid over it (reversible: an unblock or an open door lifts them):
a block turns every free ground cell of its area into a wall while it stands, whatever the scene puts
there meanwhile. :attr:`SceneState.building` is the scene with the blocks laid over it, an ordinary
:class:`~sgplan.scene.model.Building` (what a fresh plan of the changed building reads).

States are values: :meth:`SceneState.apply` returns a new state (floor rasters copied on write) and a
:class:`SceneDelta` naming the cells whose category changed and the objects whose footprint or room did.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from sgplan.english import a_or_an
from sgplan.errors import SceneError
from sgplan.execution.areas import (
    area_cells,
    boundary_cells,
    cells_box,
    fill_from_nearest,
    footprint_cells,
)
from sgplan.execution.changes import (
    AddObject,
    Area,
    Block,
    Change,
    CloseDoor,
    MoveObject,
    NewSceneGraph,
    OpenDoor,
    RemoveObject,
    Unblock,
)
from sgplan.scene.lookup import find_object, find_room, object_phrase, room_phrase
from sgplan.scene.model import Building, CatCode, Floor, Room, SceneObject

MAX_OBJECT_ID = int(np.iinfo(np.int16).max)
"""Object ids are stored in the int16 category maps."""


@dataclass(frozen=True, eq=False)
class BlockRecord:
    """A standing block: its name, floor and cells (flat positions), and for a closed door the two rooms'
    ids (ascending)."""

    name: str
    floor: int
    cells: np.ndarray
    door: tuple[int, int] | None = None


@dataclass(frozen=True)
class SceneDelta:
    """What one change did.

    Attributes
    ----------
    description:
        the change in words, entities named as people name them.
    cells:
        floor -> flat positions (``row * cols + col``, ascending) whose category in
        :attr:`SceneState.building` changed.
    objects:
        uuids of the objects moved, added or removed, and of those whose footprint gained or lost a cell
        (their reach regions changed).
    """

    description: str
    cells: dict[int, np.ndarray] = field(default_factory=dict)
    objects: frozenset[int] = frozenset()

    @property
    def num_cells(self) -> int:
        return sum(int(c.size) for c in self.cells.values())


def _named(change: Change) -> str:
    return change.kind.replace("_", " ")


@dataclass(frozen=True)
class SceneState:
    """The building after the changes applied so far (see the module).

    Attributes
    ----------
    base:
        the building as loaded.
    building:
        the current building: the scene with the blocks laid over it.
    scene_cats:
        per floor, the scene's category map (no blocks).
    blocks:
        the standing blocks, oldest first.
    made:
        blocks made so far (names the next unnamed block).
    """

    base: Building
    building: Building
    scene_cats: tuple[np.ndarray, ...]
    blocks: tuple[BlockRecord, ...] = ()
    made: int = 0

    @classmethod
    def of(cls, building: Building) -> SceneState:
        """The state of ``building`` before any change."""
        return cls(building, building, tuple(floor.cat_map for floor in building.floors))

    def apply(self, change: Change) -> tuple[SceneState, SceneDelta]:
        """This state after ``change``, and what it changed. Costs a copy of each floor raster it changes
        and work over the cells it touches.

        Raises
        ------
        SceneError
            when the change cannot apply, saying why: an unknown or ambiguous room or object, no door
            between the rooms (or it is closed / open already), an area off the map or holding no free
            cell, an object moved onto a wall, another object, a blocked area or out of the rooms.
        """
        try:
            return _APPLY[type(change)](self, change)
        except SceneError as error:
            raise SceneError(f"{_named(change)}: {error}") from None

    # -- the layers --------------------------------------------------------------------------------

    def scene(self) -> Building:
        """The building without the blocks: the scene's category maps and the current objects."""
        floors = [replace(floor, cat_map=cat) for floor, cat in zip(self.building.floors, self.scene_cats)]
        return replace(self.building, floors=floors)

    def blocked(self, floor: int, blocks: Iterable[BlockRecord] | None = None) -> np.ndarray:
        """``(rows, cols)`` bool: the cells of ``floor`` under some block (of ``blocks``, default the
        standing ones)."""
        mask = np.zeros(self.base.grid_shape, dtype=bool)
        for block in self.blocks if blocks is None else blocks:
            if block.floor == floor:
                mask.reshape(-1)[block.cells] = True
        return mask

    def _with(self, scene_cats: dict[int, np.ndarray] | None = None,
              blocks: tuple[BlockRecord, ...] | None = None,
              objects: dict[int, SceneObject | None] | None = None, description: str = "",
              made: int | None = None, floors: Iterable[int] = ()) -> tuple[SceneState, SceneDelta]:
        """The state with these layers replaced (``objects``: uuid -> the object as it is now, ``None``
        for removed), and the delta over the touched ``floors`` (those of the new rasters and of the
        blocks that changed, plus ``floors``)."""
        cats = list(self.scene_cats)
        for f, cat in (scene_cats or {}).items():
            cats[f] = cat
        blocks = self.blocks if blocks is None else blocks
        touched = set(floors) | set(scene_cats or {}) | {b.floor for b in set(blocks) ^ set(self.blocks)}
        building = _rebuild(self.building, objects or {})
        new_floors = list(building.floors)
        delta_cells: dict[int, np.ndarray] = {}
        footprints: set[int] = set()  # ids of the objects whose footprint lost or gained a cell
        for f in sorted(touched):
            effective = cats[f].copy()
            effective[self.blocked(f, blocks) & (cats[f] == CatCode.GROUND)] = CatCode.WALL
            changed = np.flatnonzero(effective != building.floors[f].cat_map)
            if changed.size:
                delta_cells[f] = changed.astype(np.int64)
                values = np.concatenate([effective.reshape(-1)[changed],
                                         building.floors[f].cat_map.reshape(-1)[changed]])
                footprints |= set(np.unique(values[values > 0]).tolist())
                new_floors[f] = replace(new_floors[f], cat_map=effective)
        if delta_cells:
            building = replace(building, floors=new_floors)
        state = SceneState(self.base, building, tuple(cats), blocks, self.made if made is None else made)
        # An object's reach follows its footprint: a moved object's, and a neighbour's that the cells it
        # left were filled from (a cup leaves table).
        uuids = set(objects or {})
        for owner in (self.building, building):
            uuids |= {o.uuid for o in owner.objects() if o.id in footprints}
        return state, SceneDelta(description, delta_cells, frozenset(uuids))

    # -- rooms and objects, checked ----------------------------------------------------------------

    def _floor(self, index: int) -> Floor:
        if not 0 <= index < self.building.num_floors:
            raise SceneError(f"floor {index} does not exist (floors 0..{self.building.num_floors - 1})")
        return self.building.floors[index]

    def _free_for_object(self, floor: int, cells: np.ndarray, cat: np.ndarray, what: str) -> None:
        """Refuse a footprint that leaves the grid's rooms or covers anything but free ground."""
        room_map = self.building.floors[floor].room_map.reshape(-1)
        flat = cat.reshape(-1)
        blocked = self.blocked(floor).reshape(-1)
        cols = cat.shape[1]
        for cell in cells:
            row, col = divmod(int(cell), cols)
            value = int(flat[cell])
            if room_map[cell] <= 0:
                raise SceneError(f"{what} would leave the rooms at cell ({row}, {col}) of floor {floor}")
            if value > 0:
                other = self.building.object(id=value)
                raise SceneError(f"{what} would overlap {object_phrase(self.building, other)} at cell "
                                 f"({row}, {col})")
            if value != CatCode.GROUND:
                raise SceneError(f"{what} would stand in a {CatCode(value).name.lower().replace('_', ' ')} "
                                 f"at cell ({row}, {col}) of floor {floor}")
            if blocked[cell]:
                names = [b.name for b in self.blocks if b.floor == floor and cell in set(b.cells.tolist())]
                raise SceneError(f"{what} would stand in the blocked area {', '.join(names)} at cell "
                                 f"({row}, {col}) of floor {floor}")

    def _room_at(self, floor: int, xy: tuple[float, float], what: str) -> tuple[Room, tuple[int, int]]:
        """The room holding metric point ``xy`` of ``floor`` and the point's cell."""
        plan = self._floor(floor)
        row, col = plan.xy_to_cell(*xy)
        if not (0 <= row < plan.shape[0] and 0 <= col < plan.shape[1]):
            raise SceneError(f"{what}: ({xy[0]:g}, {xy[1]:g}) m lies off floor {floor}'s map "
                             f"({plan.extent_text()})")
        room_id = int(plan.room_map[row, col])
        if room_id <= 0:
            raise SceneError(f"{what}: ({xy[0]:g}, {xy[1]:g}) m on floor {floor} lies in no room")
        room = self.building.room(id=room_id)
        if room.floor != floor:
            raise SceneError(f"{what}: ({xy[0]:g}, {xy[1]:g}) m on floor {floor} lies on the stairs of "
                             f"{room_phrase(room)}")
        return room, (row, col)


def _rebuild(building: Building, objects: dict[int, SceneObject | None]) -> Building:
    """``building`` with each object of ``objects`` (by uuid) put in its room, or taken out (``None``);
    rooms and floors that do not change are shared."""
    if not objects:
        return building
    rooms: dict[int, Room] = {}  # room id -> the room with its new objects

    def room_of(room_id: int) -> Room:
        if room_id not in rooms:
            old = building.room(id=room_id)
            rooms[room_id] = replace(old, objects=dict(old.objects))
        return rooms[room_id]

    for uuid, obj in objects.items():
        if building.has_object(uuid):
            old = building.object(uuid=uuid)
            del room_of(old.room_id).objects[old.id]
        if obj is not None:
            room_of(obj.room_id).objects[obj.id] = obj
    floors = []
    for floor in building.floors:
        changed = {rid: room for rid, room in rooms.items() if rid in floor.rooms}
        floors.append(replace(floor, rooms={rid: changed.get(rid, room) for rid, room in floor.rooms.items()})
                      if changed else floor)
    return replace(building, floors=floors)


# -- doors -----------------------------------------------------------------------------------------


def _door_name(a: Room, b: Room) -> str:
    first, second = sorted((a, b), key=lambda r: r.id)
    return f"door {first.key}/{second.key}"


def _door_rooms(state: SceneState, rooms: tuple[str, str]) -> tuple[Room, Room, str]:
    a, b = (find_room(state.building, name) for name in rooms)
    if a.id == b.id:
        raise SceneError(f"{rooms[0]!r} and {rooms[1]!r} are the same room, {room_phrase(a)}")
    return a, b, f"the door between {room_phrase(a)} and {room_phrase(b)}"


def _close_door(state: SceneState, change: CloseDoor) -> tuple[SceneState, SceneDelta]:
    a, b, what = _door_rooms(state, change.rooms)
    name = _door_name(a, b)
    if any(block.name == name for block in state.blocks):
        raise SceneError(f"{what} is closed already")
    new = []
    for f, floor in enumerate(state.building.floors):
        cells = boundary_cells(floor.room_map, a.id, b.id)
        if (state.scene_cats[f].reshape(-1)[cells] == CatCode.GROUND).any():
            new.append(BlockRecord(name, f, cells, (min(a.id, b.id), max(a.id, b.id))))
    if not new:
        raise SceneError(f"there is no door between {room_phrase(a)} and {room_phrase(b)}: they share no "
                         "boundary with free ground on either side")
    state, delta = state._with(blocks=state.blocks + tuple(new))
    return state, replace(delta, description=f"closed {what} ({delta.num_cells} cells)")


def _open_door(state: SceneState, change: OpenDoor) -> tuple[SceneState, SceneDelta]:
    a, b, what = _door_rooms(state, change.rooms)
    name = _door_name(a, b)
    kept = tuple(block for block in state.blocks if block.name != name)
    if len(kept) == len(state.blocks):
        closed = sorted({block.name for block in state.blocks if block.door is not None})
        raise SceneError(f"{what} is not closed (closed doors: {', '.join(closed) or 'none'})")
    state, delta = state._with(blocks=kept)
    return state, replace(delta, description=f"opened {what} ({delta.num_cells} cells)")


# -- blocks ----------------------------------------------------------------------------------------


def _area(state: SceneState, area: Area) -> np.ndarray:
    """The cells of ``area``, refusing an area that misses the floor's map."""
    floor = state._floor(area.floor)
    cells = area_cells(floor, area)
    if cells.size == 0:
        raise SceneError(f"{area.describe()} lies outside floor {area.floor}'s map ({floor.extent_text()})")
    return cells


def _block(state: SceneState, change: Block) -> tuple[SceneState, SceneDelta]:
    cells = _area(state, change.area)
    name = change.name or f"block {state.made + 1}"
    if any(block.name == name for block in state.blocks):
        raise SceneError(f"a block named {name!r} stands already; unblock it first or choose another name")
    free = state.scene_cats[change.area.floor].reshape(-1)[cells] == CatCode.GROUND
    if not free.any():
        raise SceneError(f"{change.area.describe()} holds no free ground (only walls, objects or "
                         "outside cells): check the coordinates")
    record = BlockRecord(name, change.area.floor, cells)
    state, delta = state._with(blocks=state.blocks + (record,), made=state.made + 1)
    return state, replace(delta, description=f"blocked {name!r}: {change.area.describe()} "
                                             f"({delta.num_cells} cells)")


def _unblock(state: SceneState, change: Unblock) -> tuple[SceneState, SceneDelta]:
    if change.name is not None:
        kept = tuple(block for block in state.blocks if block.name != change.name or block.door is not None)
        if len(kept) == len(state.blocks):
            names = [block.name for block in state.blocks if block.door is None]
            raise SceneError(f"no block is named {change.name!r} (blocks: {', '.join(names) or 'none'})")
        what = f"{change.name!r}"
    else:
        assert change.area is not None
        cells = _area(state, change.area)
        kept = tuple(
            block if block.door is not None or block.floor != change.area.floor
            else replace(block, cells=np.setdiff1d(block.cells, cells, assume_unique=True))
            for block in state.blocks
        )
        if all(a.cells.size == b.cells.size for a, b in zip(kept, state.blocks)):
            raise SceneError(f"no block covers {change.area.describe()}")
        kept = tuple(block for block in kept if block.cells.size)
        what = change.area.describe()
    state, delta = state._with(blocks=kept, floors=[b.floor for b in state.blocks])
    return state, replace(delta, description=f"unblocked {what} ({delta.num_cells} cells)")


# -- objects ---------------------------------------------------------------------------------------


def _placed(state: SceneState, obj: SceneObject, cells: np.ndarray, floor: int, xy: tuple[float, float],
            cat: np.ndarray, what: str, above_floor_m: float) -> SceneObject:
    """``obj`` standing on ``cells`` of ``floor`` (checked free in ``cat``, then drawn there), its centre
    at ``xy`` and ``above_floor_m`` over the floor."""
    room, _ = state._room_at(floor, xy, what)
    state._free_for_object(floor, cells, cat, what)
    cat.reshape(-1)[cells] = obj.id
    lo, hi = cells_box(cells, cat.shape[1])
    location = np.array([xy[0], xy[1], state.building.floors[floor].ground_z_m + above_floor_m])
    return replace(obj, room_id=room.id, room_uuid=room.uuid, location_m=location, grid_min=lo, grid_max=hi)


def _move_object(state: SceneState, change: MoveObject) -> tuple[SceneState, SceneDelta]:
    obj = find_object(state.building, change.object)
    old_floor = state.building.room(id=obj.room_id).floor
    floor = old_floor if change.floor is None else change.floor
    state._floor(floor)
    phrase = object_phrase(state.building, obj)
    cats = {old_floor: state.scene_cats[old_floor].copy()}
    cells = footprint_cells(cats[old_floor], obj)
    if cells.size == 0:
        raise SceneError(f"{phrase} has no footprint on floor {old_floor}'s map to move")
    fill_from_nearest(cats[old_floor], cells)
    cats.setdefault(floor, state.scene_cats[floor].copy())
    plan = state.building.floors[floor]
    row, col = plan.xy_to_cell(*change.to_xy_m)
    centre = np.divmod(cells, plan.shape[1])
    d_row, d_col = row - round(float(centre[0].mean())), col - round(float(centre[1].mean()))
    rows, cols = centre[0] + d_row, centre[1] + d_col
    if not ((rows >= 0) & (rows < plan.shape[0]) & (cols >= 0) & (cols < plan.shape[1])).all():
        raise SceneError(f"{phrase} moved to ({change.to_xy_m[0]:g}, {change.to_xy_m[1]:g}) m would leave "
                         f"floor {floor}'s map ({plan.extent_text()})")
    above_m = float(obj.location_m[2]) - state.building.floors[old_floor].ground_z_m
    moved = _placed(state, obj, np.sort(rows * plan.shape[1] + cols), floor, change.to_xy_m, cats[floor],
                    f"{phrase} moved to ({change.to_xy_m[0]:g}, {change.to_xy_m[1]:g}) m", above_m)
    state, delta = state._with(scene_cats=cats, objects={obj.uuid: moved})
    room = state.building.room(id=moved.room_id)
    return state, replace(delta, description=f"moved {phrase} to ({change.to_xy_m[0]:g}, "
                                             f"{change.to_xy_m[1]:g}) m in {room_phrase(room)}")


def _add_object(state: SceneState, change: AddObject) -> tuple[SceneState, SceneDelta]:
    plan = state._floor(change.floor)
    (x, y), (sx, sy) = change.at_xy_m, change.size_m
    cells = area_cells(plan, Area(change.floor, box_m=(x - sx / 2, y - sy / 2, x + sx / 2, y + sy / 2)))
    what = f"{a_or_an(change.category)} of {sx:g} x {sy:g} m at ({x:g}, {y:g}) m"
    if cells.size == 0:
        raise SceneError(f"{what} covers no cell of floor {change.floor}'s map ({plan.extent_text()})")
    ids = [o.id for o in state.building.objects()] + [0]
    if max(ids) >= MAX_OBJECT_ID:
        raise SceneError(f"the building has object ids up to {max(ids)}; no id is left in the category maps")
    uuids = [1, *(f.uuid for f in state.building.floors), *(r.uuid for r in state.building.rooms()),
             *(o.uuid for o in state.building.objects())]
    obj = SceneObject(id=max(ids) + 1, uuid=max(uuids) + 1, name=change.category, room_id=-1, room_uuid=-1,
                      location_m=np.array([x, y, change.height_m / 2]),
                      size_m=np.array([sx, sy, change.height_m]), grid_min=(0, 0), grid_max=(0, 0))
    cat = state.scene_cats[change.floor].copy()
    placed = _placed(state, obj, cells, change.floor, (x, y), cat, what, change.height_m / 2)
    state, delta = state._with(scene_cats={change.floor: cat}, objects={obj.uuid: placed})
    return state, replace(delta, description=f"added {object_phrase(state.building, placed)}")


def _remove_object(state: SceneState, change: RemoveObject) -> tuple[SceneState, SceneDelta]:
    obj = find_object(state.building, change.object)
    phrase = object_phrase(state.building, obj)
    floor = state.building.room(id=obj.room_id).floor
    cat = state.scene_cats[floor].copy()
    fill_from_nearest(cat, footprint_cells(cat, obj))
    state, delta = state._with(scene_cats={floor: cat}, objects={obj.uuid: None})
    return state, replace(delta, description=f"removed {phrase}")


def _scene_graph(state: SceneState, change: NewSceneGraph) -> tuple[SceneState, SceneDelta]:
    from sgplan.api import load_scene
    from sgplan.execution.diff import diff_buildings

    newer = load_scene(change.scene)
    diff = diff_buildings(state.scene(), newer, change.tolerance_m)
    objects: dict[int, SceneObject | None] = {uuid: None for uuid in diff.removed}
    objects.update({uuid: newer.object(uuid=uuid) for uuid in diff.changed if newer.has_object(uuid)})
    cats = {f: floor.cat_map for f, floor in enumerate(newer.floors)}
    state, delta = state._with(scene_cats=cats, objects=objects)
    return state, replace(delta, description=f"newer scene graph {change.scene}: {diff.describe(newer)}")


_APPLY: dict[type, Any] = {
    CloseDoor: _close_door, OpenDoor: _open_door, Block: _block, Unblock: _unblock,
    MoveObject: _move_object, AddObject: _add_object, RemoveObject: _remove_object,
    NewSceneGraph: _scene_graph,
}
