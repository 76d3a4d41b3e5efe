"""An independent check of simplified waypoints, sharing no code with :mod:`sgplan.outputs.waypoints`.

The cells a segment enters are found by brute force over its bounding box with the separating-axis test
(exact integer arithmetic in doubled coordinates, where cell ``(r, c)`` is the open square
``(2r, 2r + 2) x (2c, 2c + 2)`` and its centre ``(2r + 1, 2c + 1)``), not by walking the grid lines. Used
by tests/test_outputs.py and benchmarks/waypoints.py.
"""

from __future__ import annotations

import itertools
from dataclasses import replace

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.outputs.waypoints import leg_costs
from sgplan.planning.checker import check_path
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building, CatCode


def cells_meeting_segment(a: tuple[int, int], b: tuple[int, int]) -> np.ndarray:
    """The cells whose open interior meets the closed segment between the centres of ``a`` and ``b``,
    ordered along the segment (by the projection of their centres), as ``(k, 2)`` ``(row, col)``."""
    p0 = np.array([2 * a[0] + 1, 2 * a[1] + 1], dtype=np.int64)
    p1 = np.array([2 * b[0] + 1, 2 * b[1] + 1], dtype=np.int64)
    d = p1 - p0
    rows = np.arange(min(a[0], b[0]), max(a[0], b[0]) + 1)
    cols = np.arange(min(a[1], b[1]), max(a[1], b[1]) + 1)
    r, c = (v.ravel() for v in np.meshgrid(rows, cols, indexing="ij"))
    # Axes x and y: the bounding boxes overlap with the square's interior.
    overlap = ((np.minimum(p0[0], p1[0]) < 2 * r + 2) & (np.maximum(p0[0], p1[0]) > 2 * r)
               & (np.minimum(p0[1], p1[1]) < 2 * c + 2) & (np.maximum(p0[1], p1[1]) > 2 * c))
    # The segment's normal: some corner strictly on each side of its line (a touched corner is not inside).
    sides = np.stack([d[0] * (2 * c + dc - p0[1]) - d[1] * (2 * r + dr - p0[0])
                      for dr in (0, 2) for dc in (0, 2)])
    across = (sides.min(axis=0) < 0) & (sides.max(axis=0) > 0) if d.any() else np.ones(len(r), bool)
    cells = np.column_stack([r, c])[overlap & across]
    order = np.argsort((2 * cells + 1 - p0) @ d, kind="stable")
    return cells[order]


def _within_tolerance(grid: OccupancyGrid, building: Building, floor: int, cell: tuple[int, int],
                      tolerance_m: float) -> bool:
    """Whether a blocked ``cell`` is free ground of a room within ``tolerance_m`` of a traversable cell
    (by brute force over the window around it)."""
    row, col = cell
    if building.floors[floor].cat_map[row, col] != CatCode.GROUND or grid.room_map[floor, row, col] <= 0:
        return False
    res_r, res_c = grid.resolution_m
    h_r, h_c = int(tolerance_m / res_r) + 1, int(tolerance_m / res_c) + 1
    r0, c0 = max(row - h_r, 0), max(col - h_c, 0)
    rr, cc = np.nonzero(grid.traversable[floor, r0:row + h_r + 1, c0:col + h_c + 1])
    return bool((np.hypot((rr + r0 - row) * res_r, (cc + c0 - col) * res_c) <= tolerance_m).any())


def check_polyline(path: np.ndarray, keep: np.ndarray, grid: OccupancyGrid, labels: np.ndarray,
                   automaton: Automaton, profile: str = "ltlf", *, tolerance_m: float = 0.0,
                   building: Building | None = None) -> list[str]:
    """What is wrong with following the rows ``keep`` of ``path`` in straight segments; empty if nothing.

    Every segment on one floor must enter only traversable cells (or, with ``tolerance_m``, free ground
    of a room within that many metres of one) whose labels are self-loops of the state the path had at
    its first row; a floor change must be the planner's own stairs move; the cells the
    robot crosses, with the automaton replayed over their labels, must pass
    :func:`sgplan.planning.checker.check_path` (legal moves, accepted); and the polyline must be no longer
    than the path.
    """
    path = np.asarray(path, dtype=np.int64)
    problems: list[str] = []
    entered = grid.traversable.copy()  # plus the tolerated cells, for check_path
    crossed = [path[keep[0], :3]]
    for a, b in itertools.pairwise(keep):
        (ra, ca, fa, q), (rb, cb, fb, _) = path[a].tolist(), path[b].tolist()
        if fa != fb:
            if b != a + 1:
                problems.append(f"segment {a}-{b} changes floor without the planner's stairs move")
            crossed.append(path[b, :3])
            continue
        cells = cells_meeting_segment((ra, ca), (rb, cb))
        inner = cells[1:-1]
        blocked = ~grid.traversable[fa, inner[:, 0], inner[:, 1]]
        if tolerance_m > 0 and building is not None:
            tolerated = np.array([_within_tolerance(grid, building, fa, (r, c), tolerance_m)
                                  for r, c in inner[blocked].tolist()], dtype=bool)
            entered[fa, inner[blocked][tolerated, 0], inner[blocked][tolerated, 1]] = True
            blocked[np.flatnonzero(blocked)[tolerated]] = False
        moved = np.asarray(automaton.table)[q, labels[fa, inner[:, 0], inner[:, 1]]] != q
        problems += [f"segment {a}-{b} enters blocked cell {tuple(cell)}" for cell in inner[blocked].tolist()]
        problems += [f"segment {a}-{b} changes state {q} at {tuple(cell)}" for cell in inner[moved].tolist()]
        crossed += [np.array([row, col, fa]) for row, col in cells[1:].tolist()]
    dense = np.array(crossed, dtype=np.int64)
    states = np.empty(len(dense), dtype=np.int64)
    q = automaton.initial
    for k, (row, col, floor) in enumerate(dense.tolist()):
        if k > 0 or profile == "ltlf":
            q = int(automaton.table[q, int(labels[floor, row, col])])
        states[k] = q
    tolerant = replace(grid, traversable=entered)
    check = check_path(np.column_stack([dense, states]), tolerant, labels, automaton, profile)
    problems += list(check.problems)
    polyline_m, path_m = float(leg_costs(path[keep], grid).sum()), float(leg_costs(path, grid).sum())
    if polyline_m > path_m + 1e-9:
        problems.append(f"the polyline is {polyline_m:.4f} m long, more than the path's {path_m:.4f} m")
    return problems
