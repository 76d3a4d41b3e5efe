"""What a newer scene graph of the same building changes: objects added, removed, moved or reshaped, and
occupancy changed elsewhere (e.g. a mapper's later export).

Objects are matched by uuid (what missions name). Two scenes are "the same building" when they share the
grid frame (floors, shape, origin, resolution) and the rooms (ids, uuids, categories, floors, room maps);
anything else is refused, since a run's cells and rooms would no longer mean the same places.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sgplan.errors import SceneError
from sgplan.execution.areas import footprint_cells
from sgplan.scene.lookup import object_phrase
from sgplan.scene.model import Building, SceneObject


@dataclass(frozen=True)
class SceneDiff:
    """The differences from an older to a newer scene of the same building.

    Attributes
    ----------
    added, removed:
        uuids of the objects only in the newer / older scene.
    moved:
        ``(uuid, metres)`` of the objects in both whose centre moved more than the tolerance.
    changed:
        uuids of every object in both whose id, room, category or footprint cells differ at all (the
        moved ones among them), plus the added ones: those whose reach regions must be recomputed.
    occupancy:
        floor -> cells whose category changed outside every changed object's footprint.
    """

    added: tuple[int, ...]
    removed: tuple[int, ...]
    moved: tuple[tuple[int, float], ...]
    changed: frozenset[int]
    occupancy: dict[int, int]

    def describe(self, newer: Building) -> str:
        """The differences in words, objects named in the newer scene (removed ones by key)."""
        parts = [f"added {object_phrase(newer, newer.object(uuid=u))}" for u in self.added]
        parts += [f"removed object_{u}" for u in self.removed]
        parts += [f"moved {object_phrase(newer, newer.object(uuid=u))} by {m:.2f} m" for u, m in self.moved]
        parts += [f"{n} cells of floor {f} changed" for f, n in sorted(self.occupancy.items()) if n]
        return "; ".join(parts) or "no change"


_ROOMS_STAY = "a run carries on across object and occupancy changes only: start a new run on the newer scene"


def _check_frame(older: Building, newer: Building) -> None:
    if (older.num_floors, older.grid_shape) != (newer.num_floors, newer.grid_shape):
        raise SceneError(f"the newer scene has {newer.num_floors} floors of {newer.grid_shape} cells, the "
                         f"run's {older.num_floors} of {older.grid_shape}: not the same building's frame")
    for old, new in zip(older.floors, newer.floors):
        if not (np.allclose(old.origin_m, new.origin_m) and np.allclose(old.resolution_m, new.resolution_m)):
            raise SceneError(f"floor {old.index} of the newer scene has origin {new.origin_m} m and cells of "
                             f"{new.resolution_m} m, the run's {old.origin_m} and {old.resolution_m}")


def _check_rooms(older: Building, newer: Building) -> None:
    def rooms(b: Building) -> dict[int, tuple[int, str, int]]:
        return {r.id: (r.uuid, r.name, r.floor) for r in b.rooms()}

    old, new = rooms(older), rooms(newer)
    if old != new:
        differ = sorted(set(old.items()) ^ set(new.items()))
        room_id, (uuid, name, floor) = differ[0]
        raise SceneError(f"the newer scene changes the rooms ({len(differ)} differ, e.g. room id {room_id}: "
                         f"{name} room_{uuid} on floor {floor}); {_ROOMS_STAY}")
    for old_floor, new_floor in zip(older.floors, newer.floors):
        cells = int(np.count_nonzero(old_floor.room_map != new_floor.room_map))
        if cells:
            raise SceneError(f"the newer scene's room map of floor {old_floor.index} differs in {cells} "
                             f"cells; {_ROOMS_STAY}")


def _footprint(building: Building, obj: SceneObject) -> tuple[int, np.ndarray]:
    floor = building.room(id=obj.room_id).floor
    return floor, footprint_cells(building.floors[floor].cat_map, obj)


def _same(older: Building, newer: Building, old: SceneObject, new: SceneObject) -> bool:
    if (old.id, old.room_id, old.name) != (new.id, new.room_id, new.name):
        return False
    (f_old, c_old), (f_new, c_new) = _footprint(older, old), _footprint(newer, new)
    return f_old == f_new and np.array_equal(c_old, c_new)


def diff_buildings(older: Building, newer: Building, tolerance_m: float = 0.05) -> SceneDiff:
    """The :class:`SceneDiff` from ``older`` to ``newer``; objects whose centre (``location_m``, x and y)
    moved at most ``tolerance_m`` are not listed as moved (they are still ``changed`` if their footprint
    differs).

    Raises
    ------
    SceneError
        when the two are not scenes of the same building (frame or rooms differ), saying what differs.
    """
    _check_frame(older, newer)
    _check_rooms(older, newer)
    old_objects = {o.uuid: o for o in older.objects()}
    new_objects = {o.uuid: o for o in newer.objects()}
    added = tuple(sorted(set(new_objects) - set(old_objects)))
    removed = tuple(sorted(set(old_objects) - set(new_objects)))
    changed = set(added)
    moved = []
    for uuid in sorted(set(old_objects) & set(new_objects)):
        old, new = old_objects[uuid], new_objects[uuid]
        if _same(older, newer, old, new):
            continue
        changed.add(uuid)
        metres = float(np.hypot(*(new.location_m[:2] - old.location_m[:2])))
        if metres > tolerance_m or _footprint(older, old)[0] != _footprint(newer, new)[0]:
            moved.append((uuid, metres))
    occupancy = {}
    for old_floor, new_floor in zip(older.floors, newer.floors):
        differ = old_floor.cat_map != new_floor.cat_map
        for uuid in changed | set(removed):
            for building, objects in ((older, old_objects), (newer, new_objects)):
                if uuid in objects:
                    floor, cells = _footprint(building, objects[uuid])
                    if floor == old_floor.index:
                        differ.reshape(-1)[cells] = False
        occupancy[old_floor.index] = int(np.count_nonzero(differ))
    return SceneDiff(added, removed, tuple(moved), frozenset(changed), occupancy)
