"""h_LTL: a consistent lower bound on the cost to finish the mission from a product state (cell, q).

The paper's construction (eq. for g(l, q)) with an exact metric: ``d_l(cell)`` is the exact shortest-path
distance over the search graph (steps and stairs, stairs at their own cost) from the cell to the region
of cells labelled ``l``; ``c(l, l')`` the smallest ``d_l'`` over the cells of ``l``. Then

    G(l, q) = 0                                                        if q is accepting
    G(l, q) = min over l' with T(q, l') != q of  c(l, l') + G(l', T(q, l'))    otherwise
    h(cell, q) = min over l' with T(q, l') != q of  d_l'(cell) + G(l', T(q, l'))

(accepting q: 0; no way to acceptance: inf). Consistency on every move (cell, q) -> (cell', q'), cost w:
if q' = q, ``d_l'(cell) <= w + d_l'(cell')`` (triangle inequality of an exact graph distance); if
q' != q, the label l* of cell' leaves q, so ``h(cell, q) <= d_l*(cell) + G(l*, q') <= w + G(l*, q')`` and
``G(l*, q') <= h(cell', q')`` because ``d_l''(cell') >= c(l*, l'')``. Composite actions are sequences of
moves, so the bound chains. The maps are float64, so the only slack is float rounding (~1e-15 m).
``h = inf`` proves that no accepting path exists, so the search may drop such states.

Only automaton states reachable from the start state get a row (one float64 map over the cells each), and
a row is filled on first use (:func:`fill_row`): a search touches only a few of the states (3-9 of 8-32
on the Gibson missions), and the rows it never reads cost neither time nor memory (their pages of the
lazily committed ``hmap`` are never written).
"""

from __future__ import annotations

import heapq
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numba import njit

from sgplan.planning._memory import sparse_zeros
from sgplan.planning.cells import CellGraph


@dataclass(eq=False)
class LtlHeuristic:
    """Tabulated h_LTL, rows filled on demand.

    Attributes
    ----------
    q_row:
        ``(Q,)`` int32: the row of ``hmap`` for state q, -1 if q has no map (accepting: h = 0; not
        reachable from the start state or without a way to acceptance: h = inf).
    hmap:
        ``(rows, N)`` float64 metres, lazily committed; row ``r`` is valid once ``ready[r]`` is 1.
    ready:
        ``(rows,)`` uint8.
    dist:
        ``(len(leaving_labels), N)`` float64: exact metres from each cell to each leaving label's region.
    term_ptr, term_label, term_add:
        row ``r`` is ``min over t in term_ptr[r] .. term_ptr[r+1]-1 of dist[term_label[t]] + term_add[t]``.
    accepting:
        ``(Q,)`` bool.
    leaving_labels:
        compact label ids that leave at least one tabulated state (those whose regions were measured).
    """

    q_row: np.ndarray
    hmap: np.ndarray
    ready: np.ndarray
    dist: np.ndarray
    term_ptr: np.ndarray
    term_label: np.ndarray
    term_add: np.ndarray
    accepting: np.ndarray
    leaving_labels: np.ndarray

    def value(self, cell: int, q: int) -> float:
        """h at product state (cell index, q), metres."""
        if self.accepting[q]:
            return 0.0
        row = int(self.q_row[q])
        if row < 0:
            return float("inf")
        if not self.ready[row]:
            fill_row(self.hmap, self.ready, self.dist, self.term_ptr, self.term_label, self.term_add, row)
        return float(self.hmap[row, cell])


@njit(cache=True)
def fill_row(hmap, ready, dist, term_ptr, term_label, term_add, row):
    """Fill ``hmap[row]`` from its terms (see :class:`LtlHeuristic`) and mark it ready."""
    n = hmap.shape[1]
    for c in range(n):
        hmap[row, c] = np.inf
    for t in range(term_ptr[row], term_ptr[row + 1]):
        i = term_label[t]
        add = term_add[t]
        for c in range(n):
            hmap[row, c] = min(hmap[row, c], dist[i, c] + add)
    ready[row] = 1


def reachable_states(trans: np.ndarray, q_start: int) -> np.ndarray:
    """``(Q,)`` bool: states reachable from ``q_start`` in the (compact-label) transition table."""
    seen = np.zeros(trans.shape[0], dtype=bool)
    seen[q_start] = True
    frontier = [q_start]
    while frontier:
        nxt = np.unique(trans[frontier].ravel())
        nxt = nxt[~seen[nxt]]
        seen[nxt] = True
        frontier = list(nxt)
    return seen


def build_ltl_heuristic(
    graph: CellGraph,
    cell_label: np.ndarray,
    trans: np.ndarray,
    accepting: np.ndarray,
    q_start: int,
    reachable: np.ndarray | None = None,
    distances: Callable[[np.ndarray, np.ndarray], object] | None = None,
) -> LtlHeuristic:
    """Tabulate h_LTL for the states reachable from ``q_start``.

    Parameters
    ----------
    graph:
        the cell graph searched.
    cell_label:
        ``(N,)`` compact label id of every cell (every id ``0 .. L-1`` occurs).
    trans:
        ``(Q, L)`` next state per compact label.
    accepting:
        ``(Q,)`` bool.
    q_start:
        the automaton state at the start cell.
    reachable:
        optional ``(N,)`` bool, the cells reachable from the start: label regions are restricted to them
        (the search never leaves them), which tightens h and makes it ``inf`` when a needed label occurs
        only elsewhere.
    distances:
        optional ``distances(cells, out)`` writing into ``out`` ((N,) float64) the exact metres from
        every cell to ``cells`` (sorted cell indices), e.g. kept by a session
        (:mod:`sgplan.planning.shared`); default :meth:`CellGraph.distances`.
    """
    num_states, num_labels = trans.shape
    accepting = np.asarray(accepting, dtype=bool)
    states = np.flatnonzero(reachable_states(trans, q_start) & ~accepting)
    leaves = trans[states] != states[:, None]
    needed = np.flatnonzero(leaves.any(axis=0))

    # Exact distance to each needed label region, and region-to-region lower bounds.
    inside = reachable if reachable is not None else np.ones(graph.num_cells, dtype=bool)
    regions = [np.flatnonzero((cell_label == label) & inside) for label in needed]
    counts = np.zeros(num_labels, dtype=np.int64)
    counts[needed] = [len(r) for r in regions]
    dist = np.empty((len(needed), graph.num_cells), dtype=np.float64)
    for i, cells in enumerate(regions):
        if distances is None:
            graph.distances(cells, out=dist[i])
        else:
            distances(cells, dist[i])
    region_cost = np.full((len(needed), len(needed)), np.inf)
    for i, cells in enumerate(regions):
        for j in range(len(needed)) if cells.size else ():
            region_cost[i, j] = dist[j, cells].min()
    to_go = _backward_costs(trans, accepting, needed, region_cost)

    # A row per state with at least one term (a leaving label whose region is reachable and from whose
    # successor state acceptance is possible): exactly the states whose h is finite somewhere.
    q_row = np.full(num_states, -1, dtype=np.int32)
    term_ptr = [0]
    term_label: list[int] = []
    term_add: list[float] = []
    for q in states:
        terms = [(i, float(to_go[i, trans[q, label]])) for i, label in enumerate(needed)
                 if trans[q, label] != q and counts[label] > 0 and np.isfinite(to_go[i, trans[q, label]])]
        if terms:
            q_row[q] = len(term_ptr) - 1
            term_label += [i for i, _ in terms]
            term_add += [add for _, add in terms]
            term_ptr.append(len(term_label))
    rows = len(term_ptr) - 1
    return LtlHeuristic(
        q_row=q_row,
        hmap=sparse_zeros((rows, graph.num_cells), np.float64),
        ready=np.zeros(rows, dtype=np.uint8),
        dist=dist,
        term_ptr=np.array(term_ptr, dtype=np.int64),
        term_label=np.array(term_label, dtype=np.int64),
        term_add=np.array(term_add, dtype=np.float64),
        accepting=accepting,
        leaving_labels=needed,
    )


def _backward_costs(
    trans: np.ndarray, accepting: np.ndarray, needed: np.ndarray, region_cost: np.ndarray
) -> np.ndarray:
    """``G[i, q]`` of the module docstring for ``l = needed[i]``: Dijkstra backwards over (label, state)."""
    num_states = trans.shape[0]
    to_go = np.full((len(needed), num_states), np.inf)
    to_go[:, accepting] = 0.0
    heap = [(0.0, i, int(q)) for q in np.flatnonzero(accepting) for i in range(len(needed))]
    heapq.heapify(heap)
    all_states = np.arange(num_states)
    while heap:
        value, i, q = heapq.heappop(heap)
        if value > to_go[i, q]:
            continue
        # States p that leave for q on label needed[i]: G(l, p) <= c(l, needed[i]) + G(needed[i], q).
        preds = np.flatnonzero((trans[:, needed[i]] == q) & (all_states != q) & ~accepting)
        for p in preds:
            candidate = region_cost[:, i] + value
            better = np.flatnonzero(candidate < to_go[:, p])
            to_go[better, p] = candidate[better]
            for j in better:
                heapq.heappush(heap, (float(candidate[j]), int(j), int(p)))
    return to_go
