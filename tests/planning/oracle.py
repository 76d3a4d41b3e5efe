"""An exact product-graph Dijkstra, written independently of sgplan.planning, as the tests' oracle.

Nodes are (cell, automaton state); edges are the 8-connected occupancy moves between traversable cells
(Euclidean step cost) and the stairs moves between portals (link cost); entering a cell reads its label.
Plain heapq over Python ints: meant for small buildings (up to ~1e5 product states).
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.scene.grid import OccupancyGrid

_STEPS = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)]


def optimal_cost(
    grid: OccupancyGrid,
    labels: np.ndarray,
    automaton: Automaton,
    start: tuple[int, int, int],
    profile: str = "ltlf",
    start_state: int | None = None,
) -> float:
    """Minimum cost (metres) of a path from ``start`` = (row, col, floor) accepted by the automaton.

    ``inf`` when no such path exists. Under ``"ltlf"`` the start cell's label is read first; under
    ``"authors"`` it is not. ``start_state``: the automaton state at ``start`` with its label already read
    (a mission resumed part-way); the profile then plays no part.
    """
    _, rows, cols = grid.traversable.shape
    res_x, res_y = grid.resolution_m
    row0, col0, floor0 = start
    table = automaton.table
    q0 = (
        int(start_state) if start_state is not None
        else int(table[automaton.initial, int(labels[floor0, row0, col0])]) if profile == "ltlf"
        else automaton.initial
    )

    stairs: dict[tuple[int, int, int], list[tuple[tuple[int, int, int], float]]] = {}
    for link in grid.stairs:
        low = (link.lower_floor, *link.lower_cell)
        up = (link.upper_floor, *link.upper_cell)
        stairs.setdefault(low, []).append((up, link.cost_m))
        stairs.setdefault(up, []).append((low, link.cost_m))

    best: dict[tuple[int, int, int, int], float] = {(floor0, row0, col0, q0): 0.0}
    heap = [(0.0, floor0, row0, col0, q0)]
    while heap:
        cost, f, r, c, q = heapq.heappop(heap)
        if cost > best[(f, r, c, q)]:
            continue
        if automaton.accepting[q]:
            return cost
        moves = [((f, r + dr, c + dc), math.hypot(dr * res_x, dc * res_y)) for dr, dc in _STEPS]
        moves += stairs.get((f, r, c), [])
        for (nf, nr, nc), step in moves:
            if not (0 <= nr < rows and 0 <= nc < cols and grid.traversable[nf, nr, nc]):
                continue
            nq = int(table[q, int(labels[nf, nr, nc])])
            key = (nf, nr, nc, nq)
            new = cost + step
            if new < best.get(key, math.inf):
                best[key] = new
                heapq.heappush(heap, (new, nf, nr, nc, nq))
    return math.inf
