"""Metric waypoints of a planned path, and a simplified variant with fewer points.

A path is the planner's ``(n, 4)`` ``[row, col, floor, q]`` rows (:class:`sgplan.planning.amra.SearchResult`).
A :class:`Waypoint` is one cell of it in metres: ``x``, ``y`` (the cell centre, see
:mod:`sgplan.scene.model` for the axes) and ``z`` (the floor's ground height), with the room it lies in
and the path cost up to it.

:func:`simplify_path` drops cells that a straight segment can skip. A segment is kept only if every cell
it crosses (a conservative supercover: corner touches count both side cells) is traversable in the same
occupancy grid -- so the robot keeps the clearance of the inflated grid -- and leaves the automaton in
the state the path had there (each crossed cell's label is a self-loop of that state). Following the
simplified polyline therefore satisfies the mission exactly like the dense path, never costs more (a
straight segment is no longer than the 8-connected steps it replaces), and changes floor only where the
path takes the stairs.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, fields

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building


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
        """The fields by name, in order (every value a plain int, float, str or None: no deep copy needed,
        unlike ``dataclasses.asdict``, which cost ~15 ms for a dense path's ~1,300 waypoints)."""
        return {name: getattr(self, name) for name in _WAYPOINT_FIELDS}


_WAYPOINT_FIELDS = tuple(field.name for field in fields(Waypoint))


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
    rooms = {room.id: room for room in building.rooms()}
    points = []
    for k, (row, col, floor, q), cost_m in zip(index.tolist(), chosen.tolist(), cost.tolist()):
        x_m, y_m, frame_z = grid.cell_xyz(floor, (row, col))
        ground = building.floors[floor].ground_z_m
        room = rooms.get(int(grid.room_map[floor, row, col]))
        points.append(
            Waypoint(
                index=k, x_m=x_m, y_m=y_m, z_m=float(ground) if math.isfinite(ground) else frame_z,
                floor=floor, row=row, col=col, room=room.key if room else None,
                room_name=room.name if room else None, q=q, cost_m=cost_m,
            )
        )
    return points


def crossed_cells(a: tuple[int, int], b: tuple[int, int]) -> np.ndarray:
    """The cells a straight segment between the centres of cells ``a`` and ``b`` passes through, in order,
    ``a`` first and ``b`` last, as ``(k, 2)`` ``(row, col)``.

    Conservative: where the segment passes exactly through a cell corner, both cells beside the corner
    are included (before the diagonal cell), so consecutive cells are always 4- or 8-adjacent and no
    touched cell is left out.

    Exact integer arithmetic (a walk over the grid lines crossed, compiled:
    :func:`sgplan.outputs._segments.walk`).
    """
    from sgplan.outputs._segments import walk

    (r, c), (r1, c1) = (int(a[0]), int(a[1])), (int(b[0]), int(b[1]))
    out = np.empty((2 * (abs(r1 - r) + abs(c1 - c)) + 1, 2), dtype=np.int64)
    return out[:walk(r, c, r1, c1, out)]


def simplify_path(
    path: np.ndarray, grid: OccupancyGrid, labels: np.ndarray, automaton: Automaton
) -> np.ndarray:
    """Indices (ascending, first and last included) of the rows of ``path`` to keep (see the module).

    Greedy: from each kept row, extend the straight segment row by row while it stays valid; every
    segment between two kept rows lies on one floor. ``labels`` is the ``(floors, rows, cols)`` label
    raster the path was planned with and ``automaton`` its DFA.
    """
    from sgplan.outputs._segments import simplify

    rows = np.ascontiguousarray(as_path_array(path))
    if len(rows) <= 2:
        return np.arange(len(rows))
    # Fixed dtypes and layouts: one compiled signature, cached on disk.
    traversable = np.ascontiguousarray(grid.traversable, dtype=np.bool_)
    table = np.ascontiguousarray(automaton.table, dtype=np.int32)
    return simplify(rows, traversable, np.ascontiguousarray(labels, dtype=np.uint32), table)


def densify(path: np.ndarray, keep: np.ndarray, automaton: Automaton, labels: np.ndarray,
            profile_reads_start: bool = True) -> np.ndarray:
    """The cells a robot crosses following the kept rows of ``path`` in straight segments, as a path
    ``(m, 4)`` with automaton states replayed from the labels (for checking a simplified path).

    Stairs legs (floor changes) and single steps are kept as the planner's move; longer segments become
    their :func:`crossed_cells` (side cells of corner touches included, as :func:`simplify_path` checks them).
    """
    rows = as_path_array(path)
    cells = [rows[keep[0], :3]]
    for a, b in itertools.pairwise(keep):
        ra, rb = rows[a], rows[b]
        if ra[2] != rb[2] or max(abs(int(rb[0] - ra[0])), abs(int(rb[1] - ra[1]))) <= 1:
            cells.append(rb[:3])  # the stairs, or the planner's own step (a diagonal step may cut a corner)
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
