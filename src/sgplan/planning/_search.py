"""The compiled core of AMRA*: successor generation over the hierarchical domain and the search loop.

Product state ``s = cell * Q + q`` (int64); heaps, INCONS and parent pointers hold these numbers.

Search memory is paged and sparse in automaton states (what a search touches, not cells x Q): a page
holds the records of ``PAGE`` consecutive cells in ONE automaton state, ``ptab[q, cell >> PAGE_BITS]``
is its slot in the pool (-1 until a successor first lands there), and pages are handed out in the order
the search first touches them. A record is three 8-byte words read and written together (one cache
line instead of one per array): ``g`` (float64 metres), ``parent`` (product state, -1 at the start) and
``meta`` = ``action + 1`` (bits 0-31, 0 = never reached) | closed bit per level (bits 32-39) | the
iteration those closed bits belong to (bits 40-62), which clears every closed set between iterations
in O(1).

Action codes stored with each state's parent: 0..7 an occupancy step (``cells.STEPS`` index), 8 stairs,
``ACT_MAP + k`` composite action family ``k`` (``PlanningDomain.maps[k]``).

Heaps (one per queue, all in one flat buffer) store entries of three words too, ``(key, g, state)``:
the same buffer is passed twice, as float64 and as int64 views. They are 4-ary (half the depth of a
binary heap; a node's children share one or two cache lines), ordered by key, ties by larger g first
(deeper states first: shorter weighted searches, bounds unchanged), lazy (stale entries are skipped
when they reach the top).

The loop is re-entrant: :func:`improve_path` returns after a budget of expansions (so the Python driver
can check the clock and report progress) or when a heap, INCONS or the page pool needs more room; all
state lives in arrays.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba import njit

from sgplan.planning._dijkstra import dijkstra, label_runs
from sgplan.planning.ltl_heuristic import fill_row

FOUND, EXHAUSTED, BUDGET, GROW = 0, 1, 2, 3
ACT_STAIRS = 8
ACT_MAP = 16
ALL_LEVELS = 0x1F  # closed bits of levels 0 (anchor) .. 4
INF = np.inf

PAGE_BITS = 9
PAGE = 1 << PAGE_BITS  # cells per page (records of one automaton state)
PAGE_MASK = PAGE - 1
REC = 3  # words per record and per heap entry
ARITY = 4  # heap fan-out
FILL_FRACTION = 4  # an h_LTL row is filled after (cells / FILL_FRACTION) evaluations (see h_ltl)
LOW32 = 0xFFFFFFFF
# iscal slots
I_GOAL, I_ROBIN, I_NINCONS, I_ITER, I_PAGES = 0, 1, 2, 3, 4

SearchState = namedtuple(
    "SearchState", "ptab pool poolf hbuf hbuff hsize incons fscal iscal expansions h_evals"
)
"""Search memory (see the module docstring). ``ptab (Q, pages per state)`` int64 page slots;
``pool`` int64 ``(slots * PAGE * REC,)`` records, ``poolf`` its float64 view; ``hbuf`` int64
``(K * capacity * REC,)`` one heap per queue (queue ``i`` at entry offset ``i * capacity``), ``hbuff``
its float64 view, ``hsize (K,)``; ``incons`` int64 states; ``fscal = [goal_g, w1, w2]``;
``iscal = [goal_state, round_robin, n_incons, iteration, pages used]``; ``expansions (K,)``;
``h_evals (rows,)`` h_LTL values computed per unfilled row (:func:`h_ltl`)."""


@njit(cache=True)
def build_map(G, A, M, k):
    """Exact shortest paths of composite action family ``k`` (multi-source Dijkstra on its floor)."""
    f = A.map_floor[k]
    lo = G.floor_offset[f]
    hi = G.floor_offset[f + 1]
    src = A.map_src[A.map_src_ptr[k] : A.map_src_ptr[k + 1]]
    count = dijkstra(
        G.nbr,
        G.step_cost,
        G.stairs_first,
        G.stairs_from,
        G.stairs_to,
        G.stairs_cost,
        lo,
        hi,
        np.bool_(False),
        src,
        G.cell_room,
        A.map_stop_room[k],
        A.map_stop_count[k],
        M.dist[k],
        M.pred[k],
        M.order,
    )
    label_runs(M.order, count, M.pred[k], G.cell_label, lo, M.run[k])
    M.done[k] = 1


@njit(cache=True)
def build_all_maps(G, A, M):
    """Build every action family not built yet."""
    for k in range(M.done.shape[0]):
        if M.done[k] == 0:
            build_map(G, A, M, np.int64(k))


# The hot path (successors, heuristics, expansion, heap tops) takes plain arrays, never the named tuples:
# numba increfs/decrefs every array of a tuple passed to a helper, and in the branchy search loop those
# atomic reference counts are not pruned -- they were ~40 % of the search time. The tuple-level entry
# points (improve_path, start_iteration, successors, h_llm) unpack once and call the array-level cores.


@njit(cache=True)
def ensure_maps(G, A, M, c, level, max_level):
    """Build (once) every composite action map that expanding cell ``c`` at ``level`` may follow."""
    room = G.cell_room[c]
    if max_level >= 2 and (level == 0 or level == 2) and G.in_object_region[c] and room >= 0:
        for t in range(A.room_obj_ptr[room], A.room_obj_ptr[room + 1]):
            if M.done[A.room_obj_map[t]] == 0:
                build_map(G, A, M, np.int64(A.room_obj_map[t]))
    if max_level >= 3 and (level == 0 or level == 3) and room >= 0:
        for t in range(A.room_room_ptr[room], A.room_room_ptr[room + 1]):
            if M.done[A.room_room_map[t]] == 0:
                build_map(G, A, M, np.int64(A.room_room_map[t]))
    if max_level >= 4 and (level == 0 or level == 4):
        f = G.cell_floor[c]
        for k in (A.floor_up_map[f], A.floor_down_map[f]):
            if k >= 0 and M.done[k] == 0:
                build_map(G, A, M, np.int64(k))


@njit(cache=True, inline="always")
def maps_ready(done, cell_room, cell_floor, in_object_region, room_obj_ptr, room_obj_map, room_room_ptr,
               room_room_map, floor_up_map, floor_down_map, c, level, max_level):
    """Whether every map :func:`ensure_maps` would build for (c, level) is built already."""
    if max_level < 2 or level == 1:
        return True
    room = cell_room[c]
    if (level == 0 or level == 2) and in_object_region[c] and room >= 0:
        for t in range(room_obj_ptr[room], room_obj_ptr[room + 1]):
            if done[room_obj_map[t]] == 0:
                return False
    if max_level >= 3 and (level == 0 or level == 3) and room >= 0:
        for t in range(room_room_ptr[room], room_room_ptr[room + 1]):
            if done[room_room_map[t]] == 0:
                return False
    if max_level >= 4 and (level == 0 or level == 4):
        f = cell_floor[c]
        if (floor_up_map[f] >= 0 and done[floor_up_map[f]] == 0) or (
            floor_down_map[f] >= 0 and done[floor_down_map[f]] == 0
        ):
            return False
    return True


@njit(cache=True, inline="always")
def step_successors(
    nbr,
    step_cost,
    stairs_first,
    stairs_from,
    stairs_to,
    stairs_cost,
    cell_label,
    trans,
    c,
    q,
    out_c,
    out_q,
    out_cost,
    out_act,
):
    """Write the occupancy successors of (c, q) (8 steps, stairs) into the ``out_*`` buffers; returns
    their number. Successor q may be dead; the caller filters."""
    n = 0
    for k in range(8):
        v = nbr[c, k]
        if v >= 0:
            out_c[n] = v
            out_q[n] = trans[q, cell_label[v]]
            out_cost[n] = step_cost[k]
            out_act[n] = k
            n += 1
    j = stairs_first[c]
    while j >= 0 and j < stairs_from.shape[0] and stairs_from[j] == c:
        v = stairs_to[j]
        out_c[n] = v
        out_q[n] = trans[q, cell_label[v]]
        out_cost[n] = stairs_cost[j]
        out_act[n] = ACT_STAIRS
        n += 1
        j += 1
    return n


@njit(cache=True)
def map_successors(
    floor_offset,
    cell_floor,
    cell_label,
    cell_room,
    in_object_region,
    room_obj_ptr,
    room_obj_map,
    room_room_ptr,
    room_room_map,
    floor_up_map,
    floor_down_map,
    map_floor,
    map_exit_cell,
    map_exit_cost,
    dist,
    pred,
    run,
    trans,
    accepting,
    dead,
    idempotent,
    c,
    q0,
    level,
    max_level,
    n,
    out_c,
    out_q,
    out_cost,
    out_act,
):
    """Append the composite-action successors of (c, q0) at ``level`` (levels 2..max_level; 0 = all of
    them) to the ``out_*`` buffers after the first ``n``; returns the new count. The maps involved must be
    built (:func:`ensure_maps`).

    Following action family ``k`` from ``c``: unavailable if ``c`` is a target already, cannot reach one,
    or the automaton dies on the way. The automaton reads every cell after ``c`` up to the end (for a
    floor action also the far portal); it stops early, at that cell and cost, when it accepts. With an
    idempotent table (T(T(q,l),l) = T(q,l)) a stretch of equal labels is read once.

    One flat loop, no helper calls: numba reference-counts the arrays passed to helpers, which in this
    loop cost more than the work itself.
    """
    room = cell_room[c]
    f = cell_floor[c]
    n_obj = 0
    if max_level >= 2 and (level == 0 or level == 2) and in_object_region[c] and room >= 0:
        n_obj = room_obj_ptr[room + 1] - room_obj_ptr[room]
    n_room = 0
    if max_level >= 3 and (level == 0 or level == 3) and room >= 0:
        n_room = room_room_ptr[room + 1] - room_room_ptr[room]
    n_floor = 2 if max_level >= 4 and (level == 0 or level == 4) else 0
    for t in range(n_obj + n_room + n_floor):
        if t < n_obj:
            k = room_obj_map[room_obj_ptr[room] + t]
        elif t < n_obj + n_room:
            k = room_room_map[room_room_ptr[room] + t - n_obj]
        elif t == n_obj + n_room:
            k = floor_up_map[f]
        else:
            k = floor_down_map[f]
        if k < 0:
            continue
        lo = floor_offset[map_floor[k]]
        p = pred[k, c - lo]
        if p <= 1:
            continue
        total = dist[k, c - lo]
        q = q0
        x = p - 2
        end = -1
        cost = 0.0
        while True:
            q = trans[q, cell_label[x + lo]]
            if accepting[q]:
                end = x + lo
                cost = total - dist[k, x]
                break
            if dead[q]:
                break
            y = run[k, x] - 1 if idempotent else x
            py = pred[k, y]
            if py == 1:
                end = y + lo
                cost = total
                if map_exit_cell[k] >= 0:
                    q = trans[q, cell_label[map_exit_cell[k]]]
                    end = -1 if dead[q] else map_exit_cell[k]
                    cost = total + map_exit_cost[k]
                break
            x = py - 2
        if end >= 0:
            out_c[n] = end
            out_q[n] = q
            out_cost[n] = cost
            out_act[n] = ACT_MAP + k
            n += 1
    return n


@njit(cache=True)
def successors(G, A, M, L, c, q, level, max_level, out_c, out_q, out_cost, out_act):
    """Write the successors of (c, q) at ``level`` (0 = anchor: union of levels 1..max_level) into the
    ``out_*`` buffers, building the maps they need first; returns their number. Successor q may be dead."""
    ensure_maps(G, A, M, c, level, max_level)
    n = 0
    if level <= 1:
        n = step_successors(G.nbr, G.step_cost, G.stairs_first, G.stairs_from, G.stairs_to, G.stairs_cost,
                            G.cell_label, L.trans, c, q, out_c, out_q, out_cost, out_act)
    if max_level >= 2 and level != 1:
        n = map_successors(
            G.floor_offset,
            G.cell_floor,
            G.cell_label,
            G.cell_room,
            G.in_object_region,
            A.room_obj_ptr,
            A.room_obj_map,
            A.room_room_ptr,
            A.room_room_map,
            A.floor_up_map,
            A.floor_down_map,
            A.map_floor,
            A.map_exit_cell,
            A.map_exit_cost,
            M.dist,
            M.pred,
            M.run,
            L.trans,
            L.accepting,
            L.dead,
            L.idempotent[0],
            c,
            q,
            level,
            max_level,
            n,
            out_c,
            out_q,
            out_cost,
            out_act,
        )
    return n


@njit(cache=True, inline="always")
def h_ltl(hmap, h_ready, h_dist, h_ptr, h_label, h_add, h_evals, fill_after, row, c):
    """h_LTL at cell ``c`` in the automaton state of tabulated row ``row`` (>= 0).

    A filled row is read; otherwise the value is computed from the row's terms (min over its leaving
    labels of the exact distance plus the cost to go after it, the same float operations as
    :func:`~sgplan.planning.ltl_heuristic.fill_row`, so the same bits), and the row is filled once the
    search has evaluated it ``fill_after`` times: a search that meets a state on a few cells pays a few
    reads instead of a pass over every cell, one that floods it pays at most twice the fill.
    """
    if h_ready[row] == 1:
        return hmap[row, c]
    h_evals[row] += 1
    if h_evals[row] > fill_after:
        fill_row(hmap, h_ready, h_dist, h_ptr, h_label, h_add, row)
        return hmap[row, c]
    h = INF
    for t in range(h_ptr[row], h_ptr[row + 1]):
        h = min(h, h_dist[h_label[t], c] + h_add[t])
    return h


@njit(cache=True, inline="always")
def h_llm_core(cell_room, cell_xyz, accepting, llm_sum, llm_target, llm_valid, c, q):
    if accepting[q]:
        return 0.0
    room = cell_room[c]
    if room < 0 or not llm_valid[room, q]:
        return 0.0
    dx = cell_xyz[c, 0] - llm_target[room, q, 0]
    dy = cell_xyz[c, 1] - llm_target[room, q, 1]
    dz = cell_xyz[c, 2] - llm_target[room, q, 2]
    return llm_sum[room, q] + np.sqrt(dx * dx + dy * dy + dz * dz)


@njit(cache=True)
def h_llm(G, L, c, q):
    """h_LLM at (cell c, state q), metres (0 where guidance has nothing)."""
    return h_llm_core(G.cell_room, G.cell_xyz, L.accepting, L.llm_sum, L.llm_target, L.llm_valid, c, q)


@njit(cache=True, inline="always")
def in_level(cell_room, in_object_region, c, level):
    if level == 2:
        return in_object_region[c]
    if level == 3:
        return cell_room[c] >= 0
    return True


# ---- records ---------------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def rec_find(ptab, c, q):
    """Word offset of state (c, q)'s record in the pool, -1 if its page was never touched."""
    p = ptab[q, c >> PAGE_BITS]
    if p < 0:
        return -1
    return (p * PAGE + (c & PAGE_MASK)) * REC


@njit(cache=True, inline="always")
def rec_touch(ptab, iscal, c, q):
    """Word offset of state (c, q)'s record, giving its page a pool slot first if it has none (the pool
    must have a free slot: :func:`improve_path` checks before each expansion)."""
    blk = c >> PAGE_BITS
    p = ptab[q, blk]
    if p < 0:
        p = iscal[I_PAGES]
        ptab[q, blk] = p
        iscal[I_PAGES] = p + 1
    return (p * PAGE + (c & PAGE_MASK)) * REC


@njit(cache=True, inline="always")
def is_closed(meta, level, iteration):
    return (meta >> 40) == iteration and (meta >> (32 + level)) & 1 == 1


@njit(cache=True, inline="always")
def with_closed(meta, bits, iteration):
    """``meta`` with ``bits`` closed in ``iteration`` (the closed bits of older iterations dropped)."""
    if (meta >> 40) != iteration:
        meta = (meta & LOW32) | (iteration << 40)
    return meta | (bits << 32)


@njit(cache=True)
def read_record(ptab, pool, poolf, num_q, s):
    """``(g, parent, action)`` of product state ``s``; action -1 if ``s`` was never reached."""
    c = s // num_q
    r = rec_find(ptab, c, s - c * num_q)
    if r < 0 or pool[r + 2] & LOW32 == 0:
        return INF, np.int64(-1), np.int64(-1)
    return poolf[r], pool[r + 1], (pool[r + 2] & LOW32) - 1


# ---- heaps -----------------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _before(key_a, g_a, key_b, g_b):
    return key_a < key_b or (key_a == key_b and g_a > g_b)


@njit(cache=True, inline="always")
def hpush(hf, hi, base, size, key, g, value):
    """Insert ``(key, g, value)`` into the heap of ``size`` entries at entry offset ``base`` (room for one
    more is the caller's business); returns the new size."""
    i = size
    while i > 0:
        parent = (i - 1) // ARITY
        a = (base + parent) * REC
        if not _before(key, g, hf[a], hf[a + 1]):
            break
        d = (base + i) * REC
        hi[d] = hi[a]
        hi[d + 1] = hi[a + 1]
        hi[d + 2] = hi[a + 2]
        i = parent
    d = (base + i) * REC
    hf[d] = key
    hf[d + 1] = g
    hi[d + 2] = value
    return size + 1


@njit(cache=True, inline="always")
def hpop(hf, hi, base, size):
    """Remove the top entry (read it at ``base`` first); returns the new size."""
    size -= 1
    if size <= 0:
        return 0
    last = (base + size) * REC
    key, g, value = hf[last], hf[last + 1], hi[last + 2]
    i = 0
    while True:
        first = ARITY * i + 1
        if first >= size:
            break
        best = first
        b = (base + first) * REC
        bk, bg = hf[b], hf[b + 1]
        for child in range(first + 1, min(first + ARITY, size)):
            e = (base + child) * REC
            if _before(hf[e], hf[e + 1], bk, bg):
                best, bk, bg = child, hf[e], hf[e + 1]
        if not _before(bk, bg, key, g):
            break
        d = (base + i) * REC
        b = (base + best) * REC
        hi[d] = hi[b]
        hi[d + 1] = hi[b + 1]
        hi[d + 2] = hi[b + 2]
        i = best
    d = (base + i) * REC
    hf[d] = key
    hf[d + 1] = g
    hi[d + 2] = value
    return size


@njit(cache=True, inline="always")
def clean_top(ptab, pool, poolf, hf, hi, hsize, capacity, num_q, i, level, iteration):
    """Drop stale entries from the top of heap ``i``; return its minimum key (inf when empty)."""
    base = i * capacity
    while hsize[i] > 0:
        e = base * REC
        s = hi[e + 2]
        c = s // num_q
        r = (ptab[s - c * num_q, c >> PAGE_BITS] * PAGE + (c & PAGE_MASK)) * REC
        if hf[e + 1] == poolf[r] and not is_closed(pool[r + 2], level, iteration):
            return hf[e]
        hsize[i] = hpop(hf, hi, base, hsize[i])
    return INF


# ---- AMRA* -----------------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def active_queues(num_queues, w1, w2):
    """How many queues (anchor first) an iteration with weights (w1, w2) runs: all of them, except at
    (1, 1), which runs the anchor alone. There the anchor is an A* with a consistent heuristic and the
    iteration ends when the best goal's g <= its minimum key: another queue can neither raise that key
    (its expansions only add or improve states of OPEN_0) nor bring a goal below the optimum, so once
    the anchor proves the optimum it has also found it, and every other expansion is pure overhead (the
    LLM queues with an uninformative h_LLM flood every state with g below the optimum, up to 4 times)."""
    return 1 if w1 <= 1.0 and w2 <= 1.0 else num_queues


@njit(cache=True)
def start_iteration(G, L, S, q_level, q_htype, w1, w2, iteration):
    """Begin AMRA* iteration number ``iteration`` with weights (w1, w2): OPEN_0 = (valid OPEN_0) + INCONS,
    re-keyed; every other queue gets the OPEN_0 states of its level; all closed sets are cleared. The
    heaps need room for ``hsize[0] + n_incons`` entries.

    Returns min over the new OPEN_0 of g + h_LTL (inf if it is empty): with the consistent h_LTL no path
    to acceptance costs less (the ARA* argument: an optimal path leaves the closed, consistent states
    through a state of OPEN_0 + INCONS whose g is then optimal), so the best goal is optimal once its g is
    at most this value, and within w2 of optimal once at most w2 times it.
    """
    num_q = L.trans.shape[0]
    ptab, pool, poolf, incons, iscal = S.ptab, S.pool, S.poolf, S.incons, S.iscal
    hf, hi, hsize = S.hbuff, S.hbuf, S.hsize
    accepting, q_row, hmap = L.accepting, L.q_row, L.hmap
    cell_room, cell_xyz, in_object_region = G.cell_room, G.cell_xyz, G.in_object_region
    llm_sum, llm_target, llm_valid = L.llm_sum, L.llm_target, L.llm_valid
    previous = iteration - 1
    capacity = hi.shape[0] // (REC * q_level.shape[0])
    cand = np.empty(hsize[0] + iscal[I_NINCONS], dtype=np.int64)
    m = 0
    for e in range(hsize[0]):
        s = hi[e * REC + 2]
        c = s // num_q
        r = rec_find(ptab, c, s - c * num_q)
        meta = pool[r + 2]
        if hf[e * REC + 1] != poolf[r] or is_closed(meta, 0, previous) or (meta >> 40) == iteration:
            continue
        pool[r + 2] = (meta & LOW32) | (iteration << 40)
        cand[m] = s
        m += 1
    for e in range(iscal[I_NINCONS]):
        s = incons[e]
        c = s // num_q
        r = rec_find(ptab, c, s - c * num_q)
        meta = pool[r + 2]
        if (meta >> 40) == iteration:
            continue
        pool[r + 2] = (meta & LOW32) | (iteration << 40)
        cand[m] = s
        m += 1
    iscal[I_NINCONS] = 0
    iscal[I_ITER] = iteration
    S.fscal[1] = w1
    S.fscal[2] = w2
    for i in range(q_level.shape[0]):
        hsize[i] = 0
    num_queues = active_queues(q_level.shape[0], w1, w2)
    fill_after = hmap.shape[1] // FILL_FRACTION
    bound = INF
    for t in range(m):
        s = cand[t]
        c = s // num_q
        q = s % num_q
        gs = poolf[rec_find(ptab, c, q)]
        row = q_row[q]
        h0 = (
            h_ltl(hmap, L.h_ready, L.h_dist, L.h_ptr, L.h_label, L.h_add, S.h_evals, fill_after, row, c)
            if row >= 0
            else (0.0 if accepting[q] else INF)
        )
        bound = min(bound, gs + h0)
        hsize[0] = hpush(hf, hi, 0, hsize[0], gs + w1 * h0, gs, s)
        for j in range(1, num_queues):
            if in_level(cell_room, in_object_region, c, q_level[j]):
                hj = (
                    h0
                    if q_htype[j] == 0
                    else h_llm_core(cell_room, cell_xyz, accepting, llm_sum, llm_target, llm_valid, c, q)
                )
                hsize[j] = hpush(hf, hi, j * capacity, hsize[j], gs + w1 * hj, gs, s)
    return bound


@njit(cache=True)
def improve_path(G, A, M, L, S, q_level, q_htype, max_level, budget, max_succ):
    """AMRA* ImprovePath, round robin over the queues, until the bound holds or a limit is hit.

    Returns ``(status, expansions)``: FOUND when the best goal's g <= w2 * (min key of the anchor queue)
    -- with a consistent anchor heuristic that bounds its cost by w1*w2 times the optimum, and makes it
    optimal at (1, 1); EXHAUSTED when the anchor queue is empty and no goal was found; BUDGET after
    ``budget`` expansions; GROW when a heap, the INCONS list or the page pool needs more room.

    Expand (AMRA*): the chosen state is closed at its queue's level (at every level when the anchor
    expands it: the anchor generates the successors of all levels from the same g), each successor whose g
    improves is recorded; an accepting one becomes a goal candidate, one already closed in the anchor goes
    to INCONS, others enter the anchor queue and every queue of a level they belong to whose key is within
    w2 of the anchor key.

    Once w1 = 1 the anchor generates occupancy moves only (and still closes the state at every level):
    the anchor is then an A* with a consistent heuristic, which expands every state whose f is below the
    optimum whatever shortcuts the graph has, and composite actions are shortcuts (sequences of occupancy
    moves, the same optimum) -- following them from the anchor only costs time. In the weighted
    iterations they are what lets the greedy anchor jump ahead.
    """
    # Unpack once (see the note above the array-level cores).
    nbr, step_cost, stairs_first, stairs_from = G.nbr, G.step_cost, G.stairs_first, G.stairs_from
    stairs_to, stairs_cost, floor_offset, cell_floor = (
        G.stairs_to,
        G.stairs_cost,
        G.floor_offset,
        G.cell_floor,
    )
    cell_label, cell_room, cell_xyz, in_object_region = (
        G.cell_label,
        G.cell_room,
        G.cell_xyz,
        G.in_object_region,
    )
    room_obj_ptr, room_obj_map, room_room_ptr, room_room_map = (
        A.room_obj_ptr,
        A.room_obj_map,
        A.room_room_ptr,
        A.room_room_map,
    )
    floor_up_map, floor_down_map, map_floor = A.floor_up_map, A.floor_down_map, A.map_floor
    map_exit_cell, map_exit_cost = A.map_exit_cell, A.map_exit_cost
    done_maps, dist, pred, run = M.done, M.dist, M.pred, M.run
    trans, accepting, dead, q_row, hmap = L.trans, L.accepting, L.dead, L.q_row, L.hmap
    h_ready, h_dist, h_ptr, h_label, h_add = L.h_ready, L.h_dist, L.h_ptr, L.h_label, L.h_add
    idempotent = L.idempotent[0]
    llm_sum, llm_target, llm_valid = L.llm_sum, L.llm_target, L.llm_valid
    ptab, pool, poolf, h_evals = S.ptab, S.pool, S.poolf, S.h_evals
    fill_after = hmap.shape[1] // FILL_FRACTION
    hf, hi, hsize, incons, fscal, iscal = S.hbuff, S.hbuf, S.hsize, S.incons, S.fscal, S.iscal
    expansions = S.expansions

    num_q = trans.shape[0]
    iteration = iscal[I_ITER]
    w1 = fscal[1]
    w2 = fscal[2]
    num_queues = active_queues(q_level.shape[0], w1, w2)
    pool_slots = pool.shape[0] // (PAGE * REC)
    out_c = np.empty(max_succ, dtype=np.int64)
    out_q = np.empty(max_succ, dtype=np.int64)
    out_cost = np.empty(max_succ, dtype=np.float64)
    out_act = np.empty(max_succ, dtype=np.int32)
    capacity = hi.shape[0] // (REC * q_level.shape[0])
    done = 0
    while True:
        mk0 = clean_top(ptab, pool, poolf, hf, hi, hsize, capacity, num_q, 0, q_level[0], iteration)
        goal = fscal[0]
        if goal < INF and goal <= w2 * mk0:
            return FOUND, done
        if mk0 == INF:
            return EXHAUSTED, done
        if done >= budget:
            return BUDGET, done
        for i in range(num_queues):
            if hsize[i] + max_succ > capacity:
                return GROW, done
        if iscal[I_NINCONS] + max_succ > incons.shape[0] or iscal[I_PAGES] + max_succ > pool_slots:
            return GROW, done
        chosen = 0
        if num_queues > 1:
            i = iscal[I_ROBIN]
            iscal[I_ROBIN] = i % (num_queues - 1) + 1
            if (
                clean_top(ptab, pool, poolf, hf, hi, hsize, capacity, num_q, i, q_level[i], iteration)
                <= w2 * mk0
            ):
                chosen = i
        s = hi[chosen * capacity * REC + 2]
        hsize[chosen] = hpop(hf, hi, chosen * capacity, hsize[chosen])
        level = q_level[chosen]
        expansions[chosen] += 1
        done += 1

        # Expand s at level.
        c = s // num_q
        q = s - c * num_q
        r = rec_find(ptab, c, q)
        if level == 0:
            pool[r + 2] = with_closed(pool[r + 2], ALL_LEVELS, iteration)
        else:
            pool[r + 2] = with_closed(pool[r + 2], 1 << level, iteration)
        gs = poolf[r]
        n = 0
        if level <= 1:
            n = step_successors(
                nbr,
                step_cost,
                stairs_first,
                stairs_from,
                stairs_to,
                stairs_cost,
                cell_label,
                trans,
                c,
                q,
                out_c,
                out_q,
                out_cost,
                out_act,
            )
        if max_level >= 2 and (level >= 2 or (level == 0 and w1 > 1.0)):
            if not maps_ready(
                done_maps,
                cell_room,
                cell_floor,
                in_object_region,
                room_obj_ptr,
                room_obj_map,
                room_room_ptr,
                room_room_map,
                floor_up_map,
                floor_down_map,
                c,
                level,
                max_level,
            ):
                ensure_maps(G, A, M, c, level, max_level)
            n = map_successors(
                floor_offset,
                cell_floor,
                cell_label,
                cell_room,
                in_object_region,
                room_obj_ptr,
                room_obj_map,
                room_room_ptr,
                room_room_map,
                floor_up_map,
                floor_down_map,
                map_floor,
                map_exit_cell,
                map_exit_cost,
                dist,
                pred,
                run,
                trans,
                accepting,
                dead,
                idempotent,
                c,
                q,
                level,
                max_level,
                n,
                out_c,
                out_q,
                out_cost,
                out_act,
            )
        for t in range(n):
            nc = out_c[t]
            nq = out_q[t]
            gn = gs + out_cost[t]
            if accepting[nq]:
                rn = rec_touch(ptab, iscal, nc, nq)
                meta = pool[rn + 2]
                if meta & LOW32 != 0 and gn >= poolf[rn]:
                    continue
                poolf[rn] = gn
                pool[rn + 1] = s
                pool[rn + 2] = (meta & ~LOW32) | (out_act[t] + 1)
                if gn < fscal[0]:
                    fscal[0] = gn
                    iscal[I_GOAL] = nc * num_q + nq
                continue
            row = q_row[nq]
            if row < 0:  # no way to acceptance from nq (h = inf)
                continue
            rn = rec_find(ptab, nc, nq)
            if rn >= 0 and pool[rn + 2] & LOW32 != 0 and gn >= poolf[rn]:
                continue
            h0 = h_ltl(hmap, h_ready, h_dist, h_ptr, h_label, h_add, h_evals, fill_after, row, nc)
            if h0 == INF:
                continue
            if rn < 0:
                rn = rec_touch(ptab, iscal, nc, nq)
            meta = pool[rn + 2]
            poolf[rn] = gn
            pool[rn + 1] = s
            pool[rn + 2] = (meta & ~LOW32) | (out_act[t] + 1)
            ns = nc * num_q + nq
            if is_closed(meta, 0, iteration):  # closed in the anchor
                incons[iscal[I_NINCONS]] = ns
                iscal[I_NINCONS] += 1
                continue
            f0 = gn + w1 * h0
            hsize[0] = hpush(hf, hi, 0, hsize[0], f0, gn, ns)
            h_l = -1.0  # h_LLM(nc, nq) (>= 0), computed once for all the LLM queues
            for j in range(1, num_queues):
                lj = q_level[j]
                if (lj == 2 and not in_object_region[nc]) or (
                    lj == 3 and cell_room[nc] < 0
                ):  # in_level, inline
                    continue
                if is_closed(meta, lj, iteration):
                    continue
                if q_htype[j] == 0:
                    hj = h0
                else:
                    if h_l < 0.0:
                        h_l = h_llm_core(
                            cell_room, cell_xyz, accepting, llm_sum, llm_target, llm_valid, nc, nq
                        )
                    hj = h_l
                fj = gn + w1 * hj
                if fj <= w2 * f0:
                    hsize[j] = hpush(hf, hi, j * capacity, hsize[j], fj, gn, ns)


@njit(cache=True)
def init_start(ptab, pool, poolf, iscal, incons, start_cell, q_start, num_q):
    """Record the start state (g 0, no parent) in fresh search memory and put it in INCONS."""
    r = rec_touch(ptab, iscal, start_cell, q_start)
    poolf[r] = 0.0
    pool[r + 1] = -1
    pool[r + 2] = 1  # reached (action field 0 + 1)
    incons[0] = start_cell * num_q + q_start
