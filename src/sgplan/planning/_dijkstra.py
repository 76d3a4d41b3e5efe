"""Multi-source Dijkstra over the compact cell graph (numba), with predecessors and label runs.

The graph is the one the search moves on (:mod:`sgplan.planning.cells`): 8-connected steps between
traversable cells and, optionally, stairs between portals. A run covers a contiguous range of cell
indices ``[lo, hi)`` (one floor, or the whole building) and writes LOCAL arrays of length ``hi - lo``:

- ``dist``: metres to the nearest source, valid where ``pred > 0``;
- ``pred``: 0 = not reached, 1 = a source, ``j + 2`` = the next cell (local index ``j``) on a shortest path
  towards the sources. Arrays start as zeros, so unreached parts of big lazily-allocated arrays are never
  written (and never cost memory);
- ``order``: local indices in settling order, returned count of settled cells.

An optional early stop ends the run once every cell of one room has been settled: composite actions are
only taken from inside their room, so its distances are all that is needed, and they are already exact.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from sgplan.heap import heap_grow, heap_pop, heap_push


@njit(cache=True)
def dijkstra(
    nbr, step_cost, stairs_first, stairs_from, stairs_to, stairs_cost,
    lo, hi, use_stairs, sources, cell_room, stop_room, stop_count, dist, pred, order,
):
    """Fill ``dist`` / ``pred`` / ``order`` (local, see the module docstring); returns cells settled.

    ``sources`` are global cell indices in ``[lo, hi)``. Stops early after ``stop_count`` cells of room
    index ``stop_room`` are settled (``stop_room < 0``: run to exhaustion).
    """
    n = hi - lo
    done = np.zeros(n, dtype=np.bool_)
    cap = max(1024, 4 * sources.shape[0])
    keys = np.empty(cap, dtype=np.float64)
    ties = np.zeros(cap, dtype=np.float64)
    values = np.empty(cap, dtype=np.int64)
    size = np.int64(0)  # typed, not a literal: one compiled heap specialization
    for s in sources:
        local = s - lo
        if pred[local] == 1:
            continue
        dist[local] = 0.0
        pred[local] = 1
        if size + 1 > keys.shape[0]:
            keys, ties, values = heap_grow(keys, ties, values, size)
        size = heap_push(keys, ties, values, size, 0.0, 0.0, local)
    settled = 0
    room_settled = 0
    n_stairs = stairs_from.shape[0]
    while size > 0:
        d = keys[0]
        u = values[0]
        size = heap_pop(keys, ties, values, size)
        if done[u] or d > dist[u]:
            continue
        done[u] = True
        order[settled] = u
        settled += 1
        gu = u + lo
        if stop_room >= 0 and cell_room[gu] == stop_room:
            room_settled += 1
            if room_settled >= stop_count:
                break
        if size + 10 > keys.shape[0]:
            keys, ties, values = heap_grow(keys, ties, values, size)
        for k in range(8):
            v = nbr[gu, k] - lo
            if v < 0 or v >= n or done[v]:
                continue
            nd = d + step_cost[k]
            if pred[v] == 0 or nd < dist[v]:
                dist[v] = nd
                pred[v] = u + 2
                size = heap_push(keys, ties, values, size, nd, 0.0, v)
        if use_stairs:
            j = stairs_first[gu]
            while j >= 0 and j < n_stairs and stairs_from[j] == gu:
                v = stairs_to[j] - lo
                if 0 <= v < n and not done[v]:
                    nd = d + stairs_cost[j]
                    if pred[v] == 0 or nd < dist[v]:
                        dist[v] = nd
                        pred[v] = u + 2
                        if size + 1 > keys.shape[0]:
                            keys, ties, values = heap_grow(keys, ties, values, size)
                        size = heap_push(keys, ties, values, size, nd, 0.0, v)
                j += 1
    return settled


@njit(cache=True)
def label_runs(order, count, pred, cell_label, lo, run):
    """``run[x] = j + 1`` where local ``j`` is the last cell of the same-label stretch that starts at ``x``
    and follows ``pred`` towards the sources. Lets an action's automaton run skip repeated labels."""
    for i in range(count):
        u = order[i]
        p = pred[u]
        if p == 1:
            run[u] = u + 1
        else:
            w = p - 2
            run[u] = run[w] if cell_label[w + lo] == cell_label[u + lo] else u + 1
