"""Metric waypoints of a planned path, and a simplified variant with fewer points.

A path is the planner's ``(n, 4)`` ``[row, col, floor, q]`` rows (:class:`sgplan.planning.amra.SearchResult`).
A :class:`Waypoint` is one cell of it in metres: ``x``, ``y`` (the cell centre, see
:mod:`sgplan.scene.model` for the axes) and ``z`` (the floor's ground height), with the room it lies in
and the path cost up to it.

:func:`simplify_path` keeps the corners of the path: from each kept cell, the farthest later cell that a
straight segment reaches. A segment is kept only if the cells whose interior it crosses
(:func:`crossed_cells`, an exact line-of-sight test on the inflated grid) are all traversable in the
occupancy grid the path was planned on, and their labels leave the automaton in the state the path had
there (self-loops). Following the simplified polyline therefore satisfies the mission exactly like the
dense path, never costs more (a straight segment is no longer than the 8-connected steps it replaces),
changes the automaton's state only at kept cells, and changes floor only where the path takes the stairs.

Clearance: a segment lies inside the closed traversable cells, where the robot fits at the cell centre
(the obstacles were inflated by its radius). Where a segment passes exactly through a cell corner it
touches the two cells beside the corner in that one point, which may be blocked, and enters neither --
the planner's own diagonal steps do the same. So with the default ``tolerance_m=0`` a point of the
polyline is at most half a cell diagonal (``hypot(res_x, res_y) / 2``) from a cell centre the robot may
occupy, as on the dense path, and no segment enters a cell the planner could not enter.

Tolerance: a robot's own controller cuts the rounded corners of the inflated obstacles anyway, and a
path that hugs such a corner needs a waypoint every few cells to follow it exactly. With ``tolerance_m``
> 0 a segment may also cross room cells that only the inflation blocked and that lie within
``tolerance_m`` of a traversable cell (:func:`passable_cells`): the robot then keeps a clearance of at
least its radius minus ``tolerance_m`` (and the half cell above). The labels of those cells are checked
like any other, so the mission guarantee is unchanged.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sgplan.errors import OutputError
from sgplan.logic.automaton import Automaton
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building, CatCode


@dataclass(frozen=True)
class Waypoint:
    """One point of a path in metres.

    ``index`` is the row of the dense path it comes from; ``room`` the key ``room_<uuid>`` of the room
    holding the cell (``None`` outside every room, e.g. a stairs portal drawn in no room) and
    ``room_name`` its category; ``q`` the automaton state after the cell; ``cost_m`` the path cost from
    the start to this point along the waypoints' own polyline (metres, stairs at their cost).
    """

    index: int
    x_m: float
    y_m: float
    z_m: float
    floor: int
    row: int
    col: int
    room: str | None
    room_name: str | None
    q: int
    cost_m: float

    def to_dict(self) -> dict[str, object]:
        """The fields by name, in order (every value a plain int, float, str or None: a shallow copy of the
        instance's attributes, which the generated ``__init__`` set in field order, is the record; no deep
        copy as ``dataclasses.asdict`` makes)."""
        return dict(vars(self))


def as_path_array(path: np.ndarray | Sequence[Sequence[int]]) -> np.ndarray:
    """``path`` as an ``(n, 4)`` int64 array; a :class:`ValueError` for any other shape."""
    rows = np.asarray(path, dtype=np.int64)
    if rows.ndim != 2 or rows.shape[1] != 4:
        raise ValueError(f"a path is an (n, 4) array of [row, col, floor, q] rows, got shape {rows.shape}")
    return rows


def _stairs_costs(grid: OccupancyGrid) -> dict[tuple[tuple[int, int, int], tuple[int, int, int]], float]:
    costs = {}
    for link in grid.stairs:
        lower = (link.lower_cell[0], link.lower_cell[1], link.lower_floor)
        upper = (link.upper_cell[0], link.upper_cell[1], link.upper_floor)
        costs[(lower, upper)] = costs[(upper, lower)] = link.cost_m
    return costs


def leg_costs(path: np.ndarray, grid: OccupancyGrid) -> np.ndarray:
    """Metres of each leg between consecutive rows of ``path``: the Euclidean distance between the cell
    centres on one floor, the stairs cost between two floors.

    Raises
    ------
    ValueError
        for a floor change that is not a stairs link of ``grid``.
    """
    rows = as_path_array(path)
    step = np.diff(rows[:, :3], axis=0)
    costs = np.hypot(step[:, 0] * grid.resolution_m[0], step[:, 1] * grid.resolution_m[1])
    stairs = _stairs_costs(grid)
    for k in np.flatnonzero(step[:, 2] != 0):
        a = (int(rows[k, 0]), int(rows[k, 1]), int(rows[k, 2]))
        b = (int(rows[k + 1, 0]), int(rows[k + 1, 1]), int(rows[k + 1, 2]))
        if (a, b) not in stairs:
            raise ValueError(f"path rows {k} {a} and {k + 1} {b} change floor but are not joined by stairs")
        costs[k] = stairs[(a, b)]
    return costs


def path_waypoints(
    path: np.ndarray, grid: OccupancyGrid, building: Building, keep: np.ndarray | None = None
) -> list[Waypoint]:
    """The waypoints of ``path`` (every row, or only the row indices ``keep``, ascending).

    ``z_m`` is the floor's ``ground_z_m`` (the grid's 3-D frame height where the scene has none).
    """
    rows = as_path_array(path)
    index = np.arange(len(rows)) if keep is None else np.asarray(keep, dtype=np.int64)
    chosen = rows[index]
    cost = np.concatenate([[0.0], np.cumsum(leg_costs(chosen, grid))]) if len(chosen) else np.zeros(0)
    row, col, floor = chosen[:, 0], chosen[:, 1], chosen[:, 2]
    # The same float64 operations as OccupancyGrid.cell_xyz, a whole column at once.
    x_m = grid.origin_m[0] + (row + 0.5) * grid.resolution_m[0]
    y_m = grid.origin_m[1] + (col + 0.5) * grid.resolution_m[1]
    ground = np.array([f.ground_z_m for f in building.floors], dtype=np.float64)
    frame = np.asarray(grid.floor_z_m, dtype=np.float64)
    z_m = np.where(np.isfinite(ground), ground, frame[: len(ground)])[floor]
    rooms = {room.id: room for room in building.rooms()}
    room_ids = grid.room_map[floor, row, col].tolist()
    named = {rid: (rooms[rid].key, rooms[rid].name) if rid in rooms else (None, None)
             for rid in set(room_ids)}
    return [
        Waypoint(index=k, x_m=x, y_m=y, z_m=z, floor=f, row=r, col=c, room=named[rid][0],
                 room_name=named[rid][1], q=q, cost_m=cost_m)
        for k, x, y, z, f, r, c, rid, q, cost_m in zip(
            index.tolist(), x_m.tolist(), y_m.tolist(), z_m.tolist(), floor.tolist(), row.tolist(),
            col.tolist(), room_ids, chosen[:, 3].tolist(), cost.tolist())
    ]


def crossed_cells(a: tuple[int, int], b: tuple[int, int]) -> np.ndarray:
    """The cells whose interior the straight segment between the centres of cells ``a`` and ``b`` meets,
    in order, ``a`` first and ``b`` last, as ``(k, 2)`` ``(row, col)``.

    Exact: where the segment passes through a cell corner, the two cells beside it are touched in one
    point and left out, and the next cell is the diagonal one (as for the planner's diagonal step), so
    consecutive cells are always 4- or 8-adjacent. Integer arithmetic (a walk over the grid lines
    crossed, compiled: :func:`sgplan.outputs._segments.walk`).
    """
    from sgplan.outputs._segments import walk

    (r, c), (r1, c1) = (int(a[0]), int(a[1])), (int(b[0]), int(b[1]))
    out = np.empty((abs(r1 - r) + abs(c1 - c) + 1, 2), dtype=np.int64)
    return out[:walk(r, c, r1, c1, out)]


def passable_cells(
    grid: OccupancyGrid, tolerance_m: float = 0.0, building: Building | None = None
) -> np.ndarray:
    """``(floors, rows, cols)`` bool: the cells a simplified segment may cross.

    With ``tolerance_m = 0`` the grid's traversable cells; with ``tolerance_m > 0`` also the free ground
    cells of a room (room id > 0, category GROUND in ``building``) whose centre lies within
    ``tolerance_m`` metres of a traversable cell's centre: cells that only the inflation blocked.

    Raises
    ------
    OutputError
        for a negative or non-finite tolerance, one not below the grid's robot radius (it is clearance
        given up), or a tolerance without the ``building``.
    """
    if not (math.isfinite(tolerance_m) and tolerance_m >= 0):
        raise OutputError(f"waypoint tolerance must be a non-negative number of metres, got {tolerance_m}")
    if tolerance_m == 0:
        return grid.traversable
    if tolerance_m >= grid.robot_radius_m:
        raise OutputError(f"waypoint tolerance {tolerance_m:g} m must be below the robot radius "
                          f"{grid.robot_radius_m:g} m (it is clearance given up)")
    if building is None:
        raise OutputError("a waypoint tolerance needs the building (its free ground cells)")
    from scipy import ndimage

    ground = np.stack([floor.cat_map == CatCode.GROUND for floor in building.floors])
    near = np.stack([
        ndimage.distance_transform_edt(~free, sampling=grid.resolution_m) <= tolerance_m
        for free in grid.traversable
    ])
    return grid.traversable | (near & ground & (grid.room_map > 0))


def simplify_path(
    path: np.ndarray, grid: OccupancyGrid, labels: np.ndarray, automaton: Automaton, *,
    tolerance_m: float = 0.0, building: Building | None = None,
) -> np.ndarray:
    """Indices (ascending, first and last included) of the rows of ``path`` to keep (see the module).

    From each kept row, the farthest row of the same floor and automaton state that a valid segment
    reaches is kept next; every segment between two kept rows lies on one floor. ``labels`` is the
    ``(floors, rows, cols)`` label raster the path was planned with and ``automaton`` its DFA;
    ``tolerance_m`` (metres) lets segments cut the inflation's edge (:func:`passable_cells`, which needs
    the ``building`` then).

    Raises
    ------
    OutputError
        for a tolerance :func:`passable_cells` refuses.
    """
    from sgplan.outputs._segments import simplify

    passable = passable_cells(grid, tolerance_m, building)
    rows = np.ascontiguousarray(as_path_array(path))
    if len(rows) <= 2:
        return np.arange(len(rows))
    # Fixed dtypes and layouts: one compiled signature, cached on disk.
    table = np.ascontiguousarray(automaton.table, dtype=np.int32)
    return simplify(rows, np.ascontiguousarray(passable, dtype=np.bool_),
                    np.ascontiguousarray(labels, dtype=np.uint32), table)


def densify(path: np.ndarray, keep: np.ndarray, automaton: Automaton, labels: np.ndarray,
            profile_reads_start: bool = True) -> np.ndarray:
    """The cells a robot crosses following the kept rows of ``path`` in straight segments, as a path
    ``(m, 4)`` with automaton states replayed from the labels (for checking a simplified path).

    Stairs legs (floor changes) are kept as the planner's move; a segment on one floor becomes its
    :func:`crossed_cells`.
    """
    rows = as_path_array(path)
    cells = [rows[keep[0], :3]]
    for a, b in itertools.pairwise(keep):
        ra, rb = rows[a], rows[b]
        if ra[2] != rb[2]:
            cells.append(rb[:3])
            continue
        for row, col in crossed_cells((int(ra[0]), int(ra[1])), (int(rb[0]), int(rb[1])))[1:]:
            cells.append(np.array([row, col, ra[2]]))
    dense = np.array(cells, dtype=np.int64)
    table = np.asarray(automaton.table)
    states = np.empty(len(dense), dtype=np.int64)
    q = automaton.initial
    for k, (row, col, floor) in enumerate(dense.tolist()):
        if k > 0 or profile_reads_start:
            q = int(table[q, int(labels[floor, row, col])])
        states[k] = q
    return np.column_stack([dense, states])
