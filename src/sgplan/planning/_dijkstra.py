"""Multi-source Dijkstra over the compact cell graph (numba), with predecessors and label runs.

The graph is the one the search moves on (:mod:`sgplan.planning.cells`): 8-connected steps between
traversable cells (move ``k`` of cell ``u`` leads to ``cell_at[cell_pos[u] + step_offset[k]]``, -1: none)
and, optionally, stairs between portals. A run covers a contiguous range of cell indices ``[lo, hi)``
(one floor, or the whole building) and writes LOCAL arrays of length ``hi - lo``:

- ``dist``: metres to the nearest source, valid where ``pred > 0``;
- ``pred`` (uint8): :data:`PRED_NONE` = not reached, :data:`PRED_SOURCE` = a source, ``PRED_STEP + k`` = the
  next cell on a shortest path towards the sources is this cell's neighbour by move ``k`` of
  :data:`sgplan.planning.cells.STEPS` (:func:`next_cell`), :data:`PRED_STAIRS` = reached by a stairs move
  (which one is not kept: only whole-graph runs take stairs, and they read whether a cell was reached).
  A move code instead of the next cell's index: a byte per cell instead of four, in every composite
  action map. Arrays start as zeros, so unreached parts of big lazily-allocated arrays are never written
  (and never cost memory);
- ``order``: local indices in settling order, returned count of settled cells.

A run may be confined to one room (``stop_room >= 0``): it then never steps into a cell of another room
(the sources themselves may lie outside it, e.g. the door cells of a neighbouring room), so it computes
the shortest paths that stay inside the room, and it ends early once a given number of the room's cells
have been settled. Composite actions are only taken from inside their room, and a path inside the room is
a sequence of real moves at their real cost, so the search stays exact; the run costs the room's cells,
not the floor's (the reference planner confines its maps to a box around the room likewise).

The priority queue is not a heap but a ring of buckets of width ``delta`` = the smallest edge cost (times
``1 - 1e-9``, a margin far above float64 rounding): no edge leads from a cell of the lowest bucket to
another cell of that bucket, so all its cells are final and may be settled in any order (Dial's
algorithm with buckets no wider than the shortest edge). Settling a bucket in insertion order keeps
consecutive cells close in memory, which on large grids is most of the time (faster than a heap, whose
exact distance order scatters the reads along the whole wavefront; measured in
benchmarks/results/comment_measurements.md). Steps reach at most ``max step / delta + 1`` buckets
ahead, so a small ring suffices; stairs moves, with arbitrary and rare costs, wait in a small heap
(:mod:`sgplan.planning._heap`) and join their bucket when it comes up. The
distances are the same float64 sums a heap-based Dijkstra computes (the order in which stairs entries of
equal keys join a bucket can change the settling order and the move codes of equal-cost ties, never a
distance; only whole-building runs take stairs, and they keep the distances alone).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from sgplan.planning._heap import HREC, grown, hpop, hpush

PRED_NONE, PRED_SOURCE, PRED_STEP, PRED_STAIRS = 0, 1, 2, 10
"""``pred`` codes (module docstring): not reached, a source, ``PRED_STEP + k`` a step by move k, stairs."""


@njit(cache=True, inline="always")
def next_cell(cell_at, cell_pos, step_offset, x, code):
    """The next cell (global index) after cell ``x`` towards the sources, given ``x``'s ``pred`` code (a
    step code: ``PRED_STEP <= code < PRED_STAIRS``)."""
    return cell_at[cell_pos[x] + step_offset[code - PRED_STEP]]


@njit(cache=True, nogil=True)
def _ring_grow(keys, values):
    """Copies of the bucket arrays ``(B, cap)`` with twice the capacity (each bucket's entries kept)."""
    nb, cap = keys.shape
    new_keys = np.empty((nb, 2 * cap), dtype=keys.dtype)
    new_values = np.empty((nb, 2 * cap), dtype=values.dtype)
    for b in range(nb):
        for j in range(cap):
            new_keys[b, j] = keys[b, j]
            new_values[b, j] = values[b, j]
    return new_keys, new_values


@njit(cache=True, nogil=True)
def dijkstra(
    cell_at, cell_pos, step_offset, step_cost, stairs_first, stairs_from, stairs_to, stairs_cost,
    lo, hi, use_stairs, sources, cell_room, stop_room, stop_count, dist, pred, order,
):
    """Fill ``dist`` / ``pred`` / ``order`` (local, see the module docstring); returns cells settled.

    ``sources`` are global cell indices in ``[lo, hi)``; those off the graph (masked out of ``cell_at``, see
    :mod:`sgplan.execution.graph`) are left out. With ``stop_room >= 0`` the run never enters a
    cell whose ``cell_room`` differs from ``stop_room`` (sources excepted) and stops early after
    ``stop_count`` cells of that room are settled; with ``stop_room < 0`` it covers ``[lo, hi)`` to
    exhaustion (``cell_room`` is then not read). Every edge cost must be positive (the cell graph checks
    its stairs).
    """
    n = hi - lo
    shortest = step_cost.min()
    if use_stairs and stairs_cost.shape[0] > 0:
        shortest = min(shortest, stairs_cost.min())
    delta = shortest * (1.0 - 1e-9)
    num_buckets = 1  # a power of two (a mask, not a division, picks the slot), at least the reach + 2
    while num_buckets < int(step_cost.max() / delta) + 2:
        num_buckets *= 2
    cap = 1024
    while cap < sources.shape[0]:
        cap *= 2
    bkeys = np.empty((num_buckets, cap), dtype=np.float64)
    bvals = np.empty((num_buckets, cap), dtype=np.int32)
    bcount = np.zeros(num_buckets, dtype=np.int64)
    sbuf = np.empty(64 * HREC, dtype=np.int64)  # the stairs heap (sgplan.planning._heap), ties all 0
    sbuff = sbuf.view(np.float64)
    # Scalars shared with _settle: [current bucket, position in it, entries in the ring, stairs heap
    # size, cells settled, cells of stop_room settled].
    state = np.zeros(6, dtype=np.int64)
    for s in sources:
        local = s - lo
        if pred[local] == PRED_SOURCE or cell_at[cell_pos[s]] != s:  # twice, or masked off the graph
            continue
        dist[local] = 0.0
        pred[local] = PRED_SOURCE
        bkeys[0, bcount[0]] = 0.0
        bvals[0, bcount[0]] = local
        bcount[0] += 1
    state[2] = bcount[0]
    # _settle returns when a bucket or the stairs heap may overflow; they grow here, outside its loop (an
    # array variable re-bound inside a hot numba loop costs atomic reference counting on every iteration).
    while _settle(
        cell_at, cell_pos, step_offset, step_cost, stairs_first, stairs_from, stairs_to, stairs_cost,
        lo, n, use_stairs, cell_room,
        stop_room, stop_count, dist, pred, order, delta, bkeys, bvals, bcount, sbuff, sbuf, state,
    ):
        if bcount.max() + 16 > bkeys.shape[1]:
            bkeys, bvals = _ring_grow(bkeys, bvals)
        if (state[3] + 16) * HREC > sbuf.shape[0]:
            sbuf = grown(sbuf, state[3])
            sbuff = sbuf.view(np.float64)
    return state[4]


@njit(cache=True, nogil=True)
def _settle(
    cell_at, cell_pos, step_offset, step_cost, stairs_first, stairs_from, stairs_to, stairs_cost,
    lo, n, use_stairs, cell_room,
    stop_room, stop_count, dist, pred, order, delta, bkeys, bvals, bcount, sbuff, sbuf, state,
):
    """The loop of :func:`dijkstra`; returns True when a queue needs more room first, False when the run
    is over.

    No "settled" flags: entries are pushed only on a strict improvement, so a cell has at most one entry
    with key ``dist[cell]`` (the rest are stale, ``key > dist``), and a settled cell is never improved
    (every later key plus an edge exceeds its distance).

    One function: the bucket walk, the stairs merge and the relaxation share the ring, the stairs heap and
    six counters, kept in locals for the whole run (written back to ``state`` on return); a helper per
    settled cell would take a dozen arrays, each reference-counted on every call, which numba does not
    prune in this loop (as in the search, :mod:`sgplan.planning._search`).
    """
    num_buckets, cap = bkeys.shape
    mask = num_buckets - 1
    # Bucket of a key: key * (1 / delta) rounds differently from key / delta only within ~1e-16 of a
    # bucket boundary, far inside the 1e-9 margin of delta below the shortest edge, so two cells sharing
    # a bucket still cannot improve each other.
    inv_delta = 1.0 / delta
    cur, pos, pending, ssize = state[0], state[1], state[2], state[3]
    settled, room_settled = state[4], state[5]
    n_stairs = stairs_from.shape[0]
    limit = cap - 8  # a settled cell pushes at most 8 step entries
    stopped = False
    grow = False
    while True:
        slot = cur & mask
        # Stairs entries whose bucket has come up join it (they are never earlier than the current one).
        while ssize > 0 and int(sbuff[0] / delta) <= cur and bcount[slot] < limit:
            bkeys[slot, bcount[slot]] = sbuff[0]
            bvals[slot, bcount[slot]] = sbuf[2]
            bcount[slot] += 1
            pending += 1
            ssize = hpop(sbuff, sbuf, 0, ssize)
        full = False
        for b in range(num_buckets):
            full |= bcount[b] > limit
        while pos < bcount[slot]:
            if full or (ssize + 8) * HREC > sbuf.shape[0]:
                break
            d = bkeys[slot, pos]
            u = bvals[slot, pos]
            pos += 1
            pending -= 1
            if d > dist[u]:
                continue
            order[settled] = u
            settled += 1
            gu = u + lo
            if stop_room >= 0 and cell_room[gu] == stop_room:
                room_settled += 1
                if room_settled >= stop_count:
                    stopped = True
                    break
            pu = cell_pos[gu]
            for k in range(8):
                v = cell_at[pu + step_offset[k]] - lo
                if v < 0 or v >= n or (stop_room >= 0 and cell_room[v + lo] != stop_room):
                    continue
                nd = d + step_cost[k]
                dv = dist[v]
                # dist 0 marks sources and unreached cells (pred 0): pred is read only for those.
                if nd < dv or (dv == 0.0 and pred[v] == PRED_NONE):
                    dist[v] = nd
                    pred[v] = PRED_STEP + 7 - k  # back to u: the opposite move (STEPS[7 - k] = -STEPS[k])
                    b = max(int(nd * inv_delta), cur) & mask
                    bkeys[b, bcount[b]] = nd
                    bvals[b, bcount[b]] = v
                    bcount[b] += 1
                    full |= bcount[b] > limit
                    pending += 1
            if use_stairs:
                j = stairs_first[gu]
                while j >= 0 and j < n_stairs and stairs_from[j] == gu:
                    v = stairs_to[j] - lo
                    if 0 <= v < n and cell_at[cell_pos[v + lo]] == v + lo:  # a portal off the graph: no
                        nd = d + stairs_cost[j]
                        dv = dist[v]
                        if nd < dv or (dv == 0.0 and pred[v] == PRED_NONE):
                            dist[v] = nd
                            pred[v] = PRED_STAIRS
                            ssize = hpush(sbuff, sbuf, 0, ssize, nd, 0.0, v)
                    j += 1
        if stopped:
            grow = False
            break
        if pos < bcount[slot] or (ssize > 0 and int(sbuff[0] / delta) <= cur):
            grow = True  # stopped for room (in the bucket loop or the stairs merge)
            break
        # The bucket is exhausted: on to the next non-empty one.
        bcount[slot] = 0
        pos = 0
        if pending == 0:
            if ssize == 0:
                grow = False
                break
            cur = max(cur + 1, int(sbuff[0] / delta))
        else:
            cur += 1
    state[0], state[1], state[2], state[3] = cur, pos, pending, ssize
    state[4], state[5] = settled, room_settled
    return grow


@njit(cache=True, nogil=True)
def flood(cell_at, cell_pos, step_offset, stairs_first, stairs_from, stairs_to, starts, seen):
    """Mark in ``seen`` (bool, all cells) every cell reachable from the cells ``starts`` by steps and stairs,
    without passing through cells already marked (a flood that grows a marked region from some of its
    neighbours). Returns the cells marked."""
    stack = np.empty(cell_pos.shape[0], dtype=np.int32)
    top = 0
    for start in starts:
        if not seen[start]:
            seen[start] = True
            stack[top] = start
            top += 1
    marked = top
    n_stairs = stairs_from.shape[0]
    while top > 0:
        top -= 1
        u = stack[top]
        pu = cell_pos[u]
        for k in range(8):
            v = cell_at[pu + step_offset[k]]
            if v >= 0 and not seen[v]:
                seen[v] = True
                stack[top] = v
                top += 1
                marked += 1
        j = stairs_first[u]
        while j >= 0 and j < n_stairs and stairs_from[j] == u:
            v = stairs_to[j]
            if not seen[v]:
                seen[v] = True
                stack[top] = v
                top += 1
                marked += 1
            j += 1
    return marked


@njit(cache=True, nogil=True)
def label_runs(cell_at, cell_pos, step_offset, pred, n, cell_label, lo, run, stack):
    """``run[x] = j + 1`` where local ``j`` is the last cell of the same-label stretch that starts at ``x``
    and follows ``pred`` towards the sources, for every reached ``x < n`` (``run`` all zeros before; a run
    of steps only, as every map's is). Lets an action's automaton run skip repeated labels.

    Needs only ``pred`` (not the settling order, so a map kept for other labellings costs nothing more):
    each chain is walked up to a cell whose run is known, then filled back down. ``stack`` is scratch of
    at least ``n`` int32. A pass over ``n`` cells; the unreached ones are a read each."""
    for x in range(n):
        if pred[x] == PRED_NONE or run[x] != 0:
            continue
        top = 0
        y = x
        while run[y] == 0:
            stack[top] = y
            top += 1
            p = pred[y]
            if p == PRED_SOURCE:
                break
            y = next_cell(cell_at, cell_pos, step_offset, y + lo, p) - lo
        while top > 0:
            top -= 1
            u = stack[top]
            p = pred[u]
            if p == PRED_SOURCE:
                run[u] = u + 1
            else:
                w = next_cell(cell_at, cell_pos, step_offset, u + lo, p) - lo
                run[u] = run[w] if cell_label[w + lo] == cell_label[u + lo] else u + 1
