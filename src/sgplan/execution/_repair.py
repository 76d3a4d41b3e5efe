"""Repairing a distance field after the graph or its targets changed, locally (numba).

A field holds, for every cell, its distance to a target region in whole units over moves whose costs are
whole units (:func:`sgplan.planning.ltl_heuristic.unit_field`), ``UNREACHED`` where no target can be
reached. When some cells leave or join the graph (a door closes, a block is lifted) or the target region
(an object moves), :func:`repair_field` brings the field to the new graph and targets, touching only the
cells whose distance changes and their neighbours -- the classic two-phase update of dynamic shortest
paths (Ramalingam and Reps):

1. **Invalidate.** A cell keeps its old distance if some neighbour still supports it: a neighbour in the
   graph, not invalidated, whose old distance plus the move's cost equals the cell's old distance (a
   shortest path through it still exists). Cells are examined in increasing old distance, starting from
   the changed cells and the neighbours of the cells that left the graph; a cell without support is
   invalidated and the cells it may have supported (its neighbours whose old distance is exactly its own
   plus the move) are examined in turn. Distances are whole numbers, so "equals" is exact.
2. **Recompute.** The invalidated cells and the changed cells still in the graph are given the best
   distance their neighbours offer (0 for a target) and a Dijkstra from them lowers every distance that a
   new path shortens -- through joined cells, new targets, or back into the invalidated cells. Only the
   cells that can lower a neighbour start it.

A cell that leaves the graph keeps its last distance (nothing reads a masked cell); when it joins again it
is examined in phase 1 like every changed cell (kept only if a neighbour supports its distance), so a door
closed and opened again costs a scan of its cells, not a Dijkstra over them, when nothing else changed.

The result equals a full recomputation of the field on the new graph; the tests compare the two on random
buildings and changes.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from sgplan.planning._heap import HREC, hpop, hpush

UNREACHED = np.int64(np.iinfo(np.uint32).max)

EXACT, LOWER_BOUND, RECOMPUTE = 0, 1, 2
"""What :func:`repair_field` made of a field."""

_PENDING, _KEPT, _LOST, _TARGET = 1, 2, 3, 4
"""Phase-1 marks of a cell: waiting to be examined, keeps its distance, invalidated, a target now."""


@njit(cache=True, inline="always")
def _in_graph(cell_at, cell_pos, c):
    return cell_at[cell_pos[c]] == c


@njit(cache=True, inline="always")
def _neighbours(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from, stairs_to,
                stairs_units, x, out_cell, out_cost):
    """Fill ``out_cell`` / ``out_cost`` with the graph neighbours of cell ``x`` (which need not be in the
    graph itself) and the moves' costs; returns how many."""
    count = 0
    pos = cell_pos[x]
    for k in range(8):
        y = cell_at[pos + step_offset[k]]
        if y >= 0:
            out_cell[count] = y
            out_cost[count] = step_units[k]
            count += 1
    j = stairs_first[x]
    while 0 <= j < stairs_from.shape[0] and stairs_from[j] == x:
        y = stairs_to[j]
        if _in_graph(cell_at, cell_pos, y):
            out_cell[count] = y
            out_cost[count] = stairs_units[j]
            count += 1
        j += 1
    return count


@njit(cache=True)
def repair_field(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from, stairs_to,
                 stairs_units, cell_mask, target, dist, exact, seeds, max_lost, max_lowered, counts):
    """Repair ``dist`` (uint32 units, in place) for the graph of ``cell_at`` and the targets ``{c in the
    graph: cell_mask[c] == target}``, given ``seeds``: every cell whose graph or target membership changed
    since ``dist`` was right, or a lower bound (more cells do no harm). ``step_units`` / ``stairs_units``
    are the moves' costs in whole units (int64, >= 1). ``exact``: whether ``dist`` was the exact field of
    the graph before (else a lower bound, 1-Lipschitz over its moves).

    Returns :data:`EXACT` (``dist`` is the field of the new graph and targets); :data:`LOWER_BOUND` when
    ``dist`` was not exact or more than ``max_lost`` cells would have to be invalidated: phase 1 is then
    skipped and only phase 2 runs, which leaves every distance a lower bound that is still 1-Lipschitz
    over the moves (what h_LTL's consistency needs), exact where it did not grow; or :data:`RECOMPUTE`
    when phase 2 would lower more than ``max_lowered`` cells or some distance does not fit below
    ``UNREACHED``: ``dist`` is then half-done and must be recomputed. ``counts[0]`` / ``counts[1]``
    receive the cells invalidated / lowered.

    Cost: the cells examined and lowered (at most the two limits) and their neighbours, times the log of
    the heap.
    """
    n = cell_pos.shape[0]
    mark = np.zeros(n, dtype=np.uint8)
    # Room for every push, so the heap never grows (an array re-bound in these loops would cost atomic
    # reference counts on every iteration): phase 1 pushes a cell at most once, phase 2 the lost cells, the
    # seeds and each lowering. Lazily committed: only the part used costs memory.
    capacity = max(n, max_lost + seeds.shape[0] + max_lowered) + 16
    heap = np.empty(capacity * HREC, dtype=np.int64)
    near = np.empty(8 + stairs_from.shape[0], dtype=np.int64)
    cost = np.empty(8 + stairs_from.shape[0], dtype=np.int64)
    # Phase 1 is skipped when more reachable cells left the graph than may be invalidated (each of them
    # loses its distance).
    gone = 0
    for s in seeds:
        if not _in_graph(cell_at, cell_pos, s) and dist[s] != UNREACHED:
            gone += 1
    lost = np.empty(max(1, min(max_lost, n)), dtype=np.int64)
    num_lost = -1
    if exact and gone <= max_lost:
        num_lost = _invalidate(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from,
                               stairs_to, stairs_units, cell_mask, target, dist, seeds, max_lost, mark, heap,
                               near, cost, lost)
    outcome = EXACT if num_lost >= 0 else LOWER_BOUND
    num_lost = max(num_lost, 0)
    counts[0] = num_lost
    finished = _lower(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from, stairs_to,
                      stairs_units, cell_mask, target, dist, seeds, max_lowered, heap, near, cost,
                      lost[:num_lost], counts)
    return outcome if finished else RECOMPUTE


@njit(cache=True)
def _invalidate(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from, stairs_to,
                stairs_units, cell_mask, target, dist, seeds, max_lost, mark, heap, near, cost, lost):
    """Phase 1 of :func:`repair_field`: mark the cells that no neighbour supports any more ``_LOST`` and
    list them in ``lost``, in increasing old distance from the seeds; returns how many, or -1 when more
    than ``max_lost`` would be (then every old distance stays, as a lower bound)."""
    keys = heap.view(np.float64)  # the same memory: keys and ties as floats (sgplan.planning._heap)
    size = 0
    for s in seeds:
        if _in_graph(cell_at, cell_pos, s):
            if cell_mask[s] == target:
                mark[s] = _TARGET
            elif dist[s] != UNREACHED and mark[s] == 0:
                mark[s] = _PENDING
                size = hpush(keys, heap, 0, size, np.float64(dist[s]), 0.0, s)
        elif dist[s] != UNREACHED:
            mark[s] = _LOST
            count = _neighbours(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from,
                                stairs_to, stairs_units, s, near, cost)
            for i in range(count):
                y = near[i]
                if mark[y] == 0 and dist[y] != UNREACHED:
                    mark[y] = _PENDING
                    size = hpush(keys, heap, 0, size, np.float64(dist[y]), 0.0, y)
    num_lost = 0
    while size > 0:
        x = heap[2]
        size = hpop(keys, heap, 0, size)
        if mark[x] != _PENDING:
            continue
        dx = np.int64(dist[x])
        count = _neighbours(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from, stairs_to,
                            stairs_units, x, near, cost)
        supported = False
        for i in range(count):
            y = near[i]
            if mark[y] != _LOST and dist[y] != UNREACHED and np.int64(dist[y]) + cost[i] == dx:
                supported = True
                break
        if supported:
            mark[x] = _KEPT
            continue
        mark[x] = _LOST
        if num_lost >= max_lost:  # too much to invalidate: keep the old distances as lower bounds
            return -1
        lost[num_lost] = x
        num_lost += 1
        for i in range(count):
            y = near[i]
            if mark[y] == 0 and dist[y] != UNREACHED and np.int64(dist[y]) == dx + cost[i]:
                mark[y] = _PENDING
                size = hpush(keys, heap, 0, size, np.float64(dist[y]), 0.0, y)
    return num_lost


@njit(cache=True)
def _lower(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from, stairs_to, stairs_units,
           cell_mask, target, dist, seeds, max_lowered, heap, near, cost, lost, counts):
    """Phase 2 of :func:`repair_field`: the ``lost`` cells (made ``UNREACHED``) and the seeds take the best
    distance their neighbours offer, then a Dijkstra from them lowers every distance a new path shortens.
    ``counts[1]`` receives the cells lowered; returns False when it gave up (more than ``max_lowered``, or
    a distance that does not fit below ``UNREACHED``), True when done."""
    keys = heap.view(np.float64)
    size = 0
    for i in range(lost.shape[0]):
        dist[lost[i]] = UNREACHED
    lowered = 0
    for phase in range(2):
        total = lost.shape[0] if phase == 0 else seeds.shape[0]
        for i in range(total):
            x = lost[i] if phase == 0 else seeds[i]
            if not _in_graph(cell_at, cell_pos, x):
                continue
            count = _neighbours(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from,
                                stairs_to, stairs_units, x, near, cost)
            best = np.int64(0) if cell_mask[x] == target else UNREACHED
            for j in range(count):
                dy = np.int64(dist[near[j]])
                if dy != UNREACHED and dy + cost[j] < best:
                    best = dy + cost[j]
            if best < np.int64(dist[x]):
                dist[x] = best
            dx = np.int64(dist[x])
            if dx == UNREACHED:
                continue
            for j in range(count):  # queued only if it can lower a neighbour (a rejoined cell often cannot)
                if dx + cost[j] < np.int64(dist[near[j]]):
                    size = hpush(keys, heap, 0, size, np.float64(dx), 0.0, x)
                    break
    while size > 0:
        key = keys[0]
        x = heap[2]
        size = hpop(keys, heap, 0, size)
        dx = np.int64(dist[x])
        if np.float64(dx) < key:
            continue
        count = _neighbours(cell_at, cell_pos, step_offset, step_units, stairs_first, stairs_from, stairs_to,
                            stairs_units, x, near, cost)
        for i in range(count):
            y = near[i]
            nd = dx + cost[i]
            if nd < np.int64(dist[y]):
                if nd >= UNREACHED or lowered >= max_lowered:
                    counts[1] = lowered
                    return False
                dist[y] = nd
                lowered += 1
                size = hpush(keys, heap, 0, size, np.float64(nd), 0.0, y)
    counts[1] = lowered
    return True
