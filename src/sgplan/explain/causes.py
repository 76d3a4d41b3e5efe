"""Why a place the mission needs cannot be used, said in words: no door to it, no room for the robot in it,
a way in too narrow for this robot (with the largest robot radius that would get through), or no way at
all.

The radius is found by building the occupancy grid at smaller radii (the authors' inflation, as
:func:`sgplan.scene.grid.build_occupancy_grid` does for a plan) and bisecting, only when a mission has
already failed: a few grid builds, a fraction of a second on a Gibson scene.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Sequence

import numpy as np

from sgplan.explain.referents import Referent
from sgplan.scene.grid import OccupancyGrid, build_occupancy_grid
from sgplan.scene.model import Building

RADIUS_STEP_M = 0.005
"""The precision of the radius said back: the bisection stops when the bracket is this narrow."""


def start_component(grid: OccupancyGrid, start: tuple[int, int, int], allowed: np.ndarray) -> np.ndarray:
    """``allowed`` cells connected to ``start`` by 8-connected moves and stairs links (bool raster)."""
    return component_of(connected_components(grid, allowed), start)


def component_of(components: np.ndarray, start: tuple[int, int, int]) -> np.ndarray:
    """The cells of ``start``'s component in a :func:`connected_components` raster (bool raster; only
    ``start`` itself when it lies outside every component)."""
    row, col, floor = start
    target = components[floor, row, col]
    if target == 0:
        area = np.zeros(components.shape, dtype=bool)
        area[floor, row, col] = True
        return area
    return components == target


def connected_components(grid: OccupancyGrid, allowed: np.ndarray) -> np.ndarray:
    """``(floors, rows, cols)`` int64: 0 outside ``allowed``, else an id shared by exactly the ``allowed``
    cells connected by 8-connected moves and ``grid``'s stairs links."""
    from scipy import ndimage  # ~0.3 s to import: only when a start's reach is in question

    parts, offset = [], 0
    for f in range(allowed.shape[0]):
        lab, count = ndimage.label(allowed[f], structure=np.ones((3, 3), bool))
        parts.append(np.where(lab > 0, lab + offset, 0))
        offset += count
    component = np.concatenate([[0], np.arange(1, offset + 1)])  # union-find parents over component ids

    def root(x: int) -> int:
        while component[x] != x:
            component[x] = component[component[x]]
            x = int(component[x])
        return x

    for link in grid.stairs:
        a = int(parts[link.lower_floor][link.lower_cell])
        b = int(parts[link.upper_floor][link.upper_cell])
        if a and b:
            component[root(a)] = root(b)
    roots = np.array([root(i) for i in range(offset + 1)])
    return np.stack([roots[p] for p in parts])


_KEPT_COMPONENTS = 8
"""How many :func:`components_without` rasters are kept (the last used): a served scene's missions avoid
a few room sets, each raster one int per cell of the grid."""
_components_kept: OrderedDict[tuple[int, tuple[int, ...]], tuple[OccupancyGrid, np.ndarray]] = OrderedDict()
_components_lock = threading.Lock()


def components_without(grid: OccupancyGrid, room_ids: Sequence[int]) -> np.ndarray:
    """:func:`connected_components` of ``grid``'s traversable cells outside the rooms ``room_ids``, kept
    for the last few (grid, rooms) asked: a warm service's checks of one mission from many starts label
    the grid once. Keyed by the grid object itself (a grid is never changed once built) and the room set."""
    key = (id(grid), tuple(sorted(set(room_ids))))
    with _components_lock:
        kept = _components_kept.get(key)
        if kept is not None and kept[0] is grid:
            _components_kept.move_to_end(key)
            return kept[1]
    components = connected_components(grid, grid.traversable & ~np.isin(grid.room_map, key[1]))
    components.flags.writeable = False  # shared between callers
    with _components_lock:
        _components_kept[key] = (grid, components)
        _components_kept.move_to_end(key)
        while len(_components_kept) > _KEPT_COMPONENTS:
            _components_kept.popitem(last=False)
    return components


def _largest_radius(
    building: Building, below_m: float, works: Callable[[OccupancyGrid], bool]
) -> float | None:
    """The largest robot radius below ``below_m`` (within :data:`RADIUS_STEP_M`) whose grid ``works``;
    ``None`` when not even a point robot's does. Assumes a smaller robot fits wherever a larger one does."""
    if not works(build_occupancy_grid(building, 0.0)):
        return None
    low, high = 0.0, below_m
    while high - low > RADIUS_STEP_M:
        middle = (low + high) / 2
        if works(build_occupancy_grid(building, middle)):
            low = middle
        else:
            high = middle
    return low


def _doors(building: Building, entity: Referent) -> str | None:
    """``it has no door to any other room`` when the entity's room (or the room holding the object) has
    no connection in the scene graph."""
    key = entity.key if entity.kind == "room" else entity.room_key
    if key is None or not key.startswith("room_"):
        return None
    room = building.room(uuid=int(key[5:]))
    if room.connected_room_ids:
        return None
    return "it has no door to any other room" if entity.kind == "room" else f"its room {key} has no door"


def _metres(radius_m: float) -> str:
    return f"{np.floor(radius_m * 1000) / 1000:g} m"


def why_no_free_cell(building: Building, grid: OccupancyGrid, entity: Referent, holds: np.ndarray) -> str:
    """Why no cell where ``entity``'s proposition ``holds`` (a ``(floors, rows, cols)`` bool raster) is
    free for the grid's robot, and the largest robot radius that fits there."""
    radius = grid.robot_radius_m
    where = f"in {entity.phrase()}" if entity.kind == "room" else f"within reach of {entity.phrase()}"
    parts = [f"no cell {where} is free for a robot of radius {radius:g} m"]
    fits = _largest_radius(building, radius, lambda g: bool((holds & g.traversable).any()))
    parts.append("not even for a point robot" if fits is None else f"a robot of radius up to {_metres(fits)} "
                 "would fit")
    door = _doors(building, entity)
    return "; ".join(parts + ([door] if door else []))


def why_unreachable(building: Building, grid: OccupancyGrid, start: tuple[int, int, int], entity: Referent,
                    holds: np.ndarray) -> str:
    """Why no cell where ``entity``'s proposition ``holds`` is reachable from ``start``: no door, and
    the largest robot radius that would get there (or none)."""
    radius = grid.robot_radius_m

    def reaches(g: OccupancyGrid) -> bool:
        return bool((holds & start_component(g, start, g.traversable)).any())

    where = entity.phrase() if entity.kind == "room" else f"the places within reach of {entity.phrase()}"
    parts = [f"{where} cannot be reached from the start by a robot of radius {radius:g} m"]
    door = _doors(building, entity)
    if door:
        parts.append(door)
    largest = _largest_radius(building, radius, reaches)
    parts.append("no free passage leads there at any robot radius" if largest is None else
                 f"the way in lets a robot of radius up to {_metres(largest)} through")
    return "; ".join(parts)


def missing_from_start(grid: OccupancyGrid, labels: np.ndarray, start: tuple[int, int, int],
                       aps: Sequence[str]) -> list[int]:
    """The indices of the propositions that hold on some traversable cell but on none reachable from
    ``start`` (no room forbidden)."""
    free = labels[grid.traversable]
    near = labels[start_component(grid, start, grid.traversable)]
    anywhere = int(np.bitwise_or.reduce(free)) if free.size else 0
    reached = int(np.bitwise_or.reduce(near)) if near.size else 0
    return [i for i in range(len(aps)) if anywhere >> i & 1 and not reached >> i & 1]
