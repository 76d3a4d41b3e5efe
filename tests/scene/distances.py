"""Exact shortest distances over an occupancy grid with stairs (multi-source Dijkstra, numba-compiled).

Moves follow :mod:`sgplan.scene.grid`: 8-connected steps into traversable cells, costing ``res_x``,
``res_y`` or ``hypot(res_x, res_y)`` metres, no corner-cutting check (as in the authors' planner), and
stairs moves between the two portal cells of a :class:`~sgplan.scene.grid.StairsLink` at its cost, in
either direction. Source cells start at distance 0 even when they are not traversable themselves (the
authors never check the start cell); moves out of them follow the usual rules.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from numba import njit

from sgplan.errors import PlanningError
from sgplan.planning._heap import HREC, grown, hpop, hpush
from sgplan.scene.grid import OccupancyGrid

GridCell3 = tuple[int, int, int]
"""A cell ``(row, col, floor)``, the order used by the authors' start positions."""


@njit(cache=True)
def _dijkstra(traversable, rows, cols, sources, res_x, res_y, link_a, link_b, link_cost):
    """Distances (metres) from the nearest source to every cell of the flat ``traversable`` array."""
    n = traversable.shape[0]
    plane = rows * cols
    dist = np.full(n, np.inf)
    done = np.zeros(n, dtype=np.bool_)
    heap = np.empty((1024 + sources.shape[0]) * HREC, dtype=np.int64)
    keys = heap.view(np.float64)
    size = np.int64(0)  # typed, not a literal: one compiled heap specialization
    for s in sources:
        if dist[s] > 0.0:
            dist[s] = 0.0
            size = hpush(keys, heap, 0, size, 0.0, 0.0, s)
    diagonal = np.sqrt(res_x * res_x + res_y * res_y)
    while size > 0:
        d, cell = keys[0], heap[2]
        size = hpop(keys, heap, 0, size)
        if done[cell]:
            continue
        done[cell] = True
        if (size + 8 + link_a.shape[0]) * HREC > heap.shape[0]:
            heap = grown(heap, size)
            keys = heap.view(np.float64)
        rem = cell % plane
        r = rem // cols
        c = rem % cols
        for dr in range(-1, 2):
            nr = r + dr
            if nr < 0 or nr >= rows:
                continue
            for dc in range(-1, 2):
                if dr == 0 and dc == 0:
                    continue
                nc = c + dc
                if nc < 0 or nc >= cols:
                    continue
                nxt = cell + dr * cols + dc
                if not traversable[nxt] or done[nxt]:
                    continue
                step = diagonal if (dr != 0 and dc != 0) else (res_x if dr != 0 else res_y)
                nd = d + step
                if nd < dist[nxt]:
                    dist[nxt] = nd
                    size = hpush(keys, heap, 0, size, nd, 0.0, nxt)
        for k in range(link_a.shape[0]):
            if link_a[k] == cell:
                other = link_b[k]
            elif link_b[k] == cell:
                other = link_a[k]
            else:
                continue
            nd = d + link_cost[k]
            if not done[other] and nd < dist[other]:
                dist[other] = nd
                size = hpush(keys, heap, 0, size, nd, 0.0, other)
    return dist


def grid_distances(grid: OccupancyGrid, sources: Iterable[GridCell3]) -> np.ndarray:
    """Exact shortest distance in metres from the nearest of ``sources`` to every cell.

    Parameters
    ----------
    grid:
        the occupancy grid (traversability and stairs).
    sources:
        cells ``(row, col, floor)``; at least one.

    Returns
    -------
    numpy.ndarray
        ``(floors, rows, cols)`` float64; ``inf`` where no path exists (e.g. every obstacle cell).

    Raises
    ------
    PlanningError
        if there is no source or a source lies outside the grid.

    Example
    -------
    >>> dist = grid_distances(grid, [(400, 900, 1)])   # doctest: +SKIP
    >>> dist[1, 450, 200]                               # doctest: +SKIP
    """
    floors, rows, cols = grid.shape
    flat_sources = []
    for cell in sources:
        row, col, floor = (int(v) for v in cell)
        if not (0 <= floor < floors and 0 <= row < rows and 0 <= col < cols):
            raise PlanningError(
                f"source cell (row {row}, col {col}, floor {floor}) lies outside the grid of "
                f"{floors} floor(s) x {rows} x {cols} cells",
                status="invalid-start",
            )
        flat_sources.append((floor * rows + row) * cols + col)
    if not flat_sources:
        raise PlanningError("grid_distances needs at least one source cell")
    link_a = np.array(
        [(s.lower_floor * rows + s.lower_cell[0]) * cols + s.lower_cell[1] for s in grid.stairs],
        dtype=np.int64,
    )
    link_b = np.array(
        [(s.upper_floor * rows + s.upper_cell[0]) * cols + s.upper_cell[1] for s in grid.stairs],
        dtype=np.int64,
    )
    link_cost = np.array([s.cost_m for s in grid.stairs], dtype=np.float64)
    dist = _dijkstra(
        np.ascontiguousarray(grid.traversable).ravel(),
        rows,
        cols,
        np.array(flat_sources, dtype=np.int64),
        float(grid.resolution_m[0]),
        float(grid.resolution_m[1]),
        link_a,
        link_b,
        link_cost,
    )
    return dist.reshape(floors, rows, cols)
