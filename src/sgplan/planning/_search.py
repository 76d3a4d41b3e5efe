"""The compiled core of AMRA*: successor generation over the hierarchical domain and the search loop.

Product state ``s = cell * Q + q`` (int64). Per-state arrays are allocated with ``np.zeros`` by the
caller, so only pages of states the search touches are ever committed. Closed flags carry the iteration
number they belong to (``epoch``), which clears every closed set between iterations in O(1).

Action codes stored with each state's parent: 0..7 an occupancy step (``cells.STEPS`` index), 8 stairs,
``ACT_MAP + k`` composite action family ``k`` (``PlanningDomain.maps[k]``).

The loop is re-entrant: :func:`improve_path` returns after a budget of expansions (so the Python driver
can check the clock and report progress) or when a heap needs more room; all state lives in arrays.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba import njit

from sgplan.planning._dijkstra import dijkstra, label_runs
from sgplan.heap import heap_pop, heap_push

FOUND, EXHAUSTED, BUDGET, GROW = 0, 1, 2, 3
ACT_STAIRS = 8
ACT_MAP = 16
INF = np.inf

SearchState = namedtuple(
    "SearchState", "g parent action seen closed epoch hkey hg hstate hsize incons fscal iscal expansions"
)
"""Search memory. ``fscal = [goal_g, w1, w2]``; ``iscal = [goal_state, round_robin, n_incons, iteration]``;
``hkey/hg/hstate (K, capacity)`` one lazy heap per queue with ``hsize (K,)``; ``expansions (K,)``."""


@njit(cache=True)
def build_map(G, A, M, k):
    """Exact shortest paths of composite action family ``k`` (multi-source Dijkstra on its floor)."""
    f = A.map_floor[k]
    lo = G.floor_offset[f]
    hi = G.floor_offset[f + 1]
    src = A.map_src[A.map_src_ptr[k] : A.map_src_ptr[k + 1]]
    count = dijkstra(
        G.nbr, G.step_cost, G.stairs_first, G.stairs_from, G.stairs_to, G.stairs_cost, lo, hi, np.bool_(False), src,
        G.cell_room, A.map_stop_room[k], A.map_stop_count[k], M.dist[k], M.pred[k], M.order,
    )
    label_runs(M.order, count, M.pred[k], G.cell_label, lo, M.run[k])
    M.done[k] = 1


@njit(cache=True)
def build_all_maps(G, A, M):
    """Build every action family not built yet."""
    for k in range(M.done.shape[0]):
        if M.done[k] == 0:
            build_map(G, A, M, np.int64(k))


@njit(cache=True)
def follow_map(G, A, M, L, k, c, q):
    """``(end cell, q, cost)`` of action family ``k`` taken from cell ``c`` in state ``q``; end = -1 if the
    action is unavailable (``c`` is a target already, cannot reach one, or the automaton dies on the way).

    The automaton reads every cell after ``c`` up to the end (for a floor action also the far portal); it
    stops early, at that cell and cost, when it accepts. With an idempotent table (T(T(q,l),l) = T(q,l))
    a stretch of equal labels is read once.
    """
    if M.done[k] == 0:
        build_map(G, A, M, np.int64(k))
    lo = G.floor_offset[A.map_floor[k]]
    pred = M.pred[k]
    dist = M.dist[k]
    run = M.run[k]
    u = c - lo
    p = pred[u]
    if p <= 1:
        return -1, q, 0.0
    total = dist[u]
    x = p - 2
    idempotent = L.idempotent[0]
    while True:
        q = L.trans[q, G.cell_label[x + lo]]
        if L.accepting[q]:
            return x + lo, q, total - dist[x]
        if L.dead[q]:
            return -1, q, 0.0
        y = run[x] - 1 if idempotent else x
        py = pred[y]
        if py == 1:
            break
        x = py - 2
    end = y + lo
    cost = total
    exit_cell = A.map_exit_cell[k]
    if exit_cell >= 0:
        q = L.trans[q, G.cell_label[exit_cell]]
        if L.dead[q]:
            return -1, q, 0.0
        end = exit_cell
        cost = total + A.map_exit_cost[k]
    return end, q, cost


@njit(cache=True)
def successors(G, A, M, L, c, q, level, max_level, out_c, out_q, out_cost, out_act):
    """Write the successors of (c, q) at ``level`` (0 = anchor: union of levels 1..max_level) into the
    ``out_*`` buffers; returns their number. Successor q may be dead; the caller filters."""
    n = 0
    if level <= 1:
        for k in range(8):
            v = G.nbr[c, k]
            if v >= 0:
                out_c[n] = v
                out_q[n] = L.trans[q, G.cell_label[v]]
                out_cost[n] = G.step_cost[k]
                out_act[n] = k
                n += 1
        j = G.stairs_first[c]
        while j >= 0 and j < G.stairs_from.shape[0] and G.stairs_from[j] == c:
            v = G.stairs_to[j]
            out_c[n] = v
            out_q[n] = L.trans[q, G.cell_label[v]]
            out_cost[n] = G.stairs_cost[j]
            out_act[n] = ACT_STAIRS
            n += 1
            j += 1
    room = G.cell_room[c]
    if max_level >= 2 and (level == 0 or level == 2) and G.in_object_region[c] and room >= 0:
        for t in range(A.room_obj_ptr[room], A.room_obj_ptr[room + 1]):
            k = A.room_obj_map[t]
            end, nq, cost = follow_map(G, A, M, L, k, c, q)
            if end >= 0:
                out_c[n] = end
                out_q[n] = nq
                out_cost[n] = cost
                out_act[n] = ACT_MAP + k
                n += 1
    if max_level >= 3 and (level == 0 or level == 3) and room >= 0:
        for t in range(A.room_room_ptr[room], A.room_room_ptr[room + 1]):
            k = A.room_room_map[t]
            end, nq, cost = follow_map(G, A, M, L, k, c, q)
            if end >= 0:
                out_c[n] = end
                out_q[n] = nq
                out_cost[n] = cost
                out_act[n] = ACT_MAP + k
                n += 1
    if max_level >= 4 and (level == 0 or level == 4):
        f = G.cell_floor[c]
        for k in (A.floor_up_map[f], A.floor_down_map[f]):
            if k >= 0:
                end, nq, cost = follow_map(G, A, M, L, k, c, q)
                if end >= 0:
                    out_c[n] = end
                    out_q[n] = nq
                    out_cost[n] = cost
                    out_act[n] = ACT_MAP + k
                    n += 1
    return n


@njit(cache=True, inline="always")
def h_ltl(L, c, q):
    if L.accepting[q]:
        return 0.0
    row = L.q_row[q]
    if row < 0:
        return INF
    return L.hmap[row, c]


@njit(cache=True, inline="always")
def h_llm(G, L, c, q):
    if L.accepting[q]:
        return 0.0
    room = G.cell_room[c]
    if room < 0 or not L.llm_valid[room, q]:
        return 0.0
    dx = G.cell_xyz[c, 0] - L.llm_target[room, q, 0]
    dy = G.cell_xyz[c, 1] - L.llm_target[room, q, 1]
    dz = G.cell_xyz[c, 2] - L.llm_target[room, q, 2]
    return L.llm_sum[room, q] + np.sqrt(dx * dx + dy * dy + dz * dz)


@njit(cache=True, inline="always")
def in_level(G, c, level):
    if level == 2:
        return G.in_object_region[c]
    if level == 3:
        return G.cell_room[c] >= 0
    return True


@njit(cache=True, inline="always")
def closed_at(S, s, level, iteration):
    return S.epoch[s] == iteration and (S.closed[s] >> level) & 1 == 1


@njit(cache=True)
def queue_h(G, L, htype, c, q, h0):
    return h0 if htype == 0 else h_llm(G, L, c, q)


@njit(cache=True)
def expand(G, A, M, L, S, q_level, q_htype, max_level, s, level, out_c, out_q, out_cost, out_act):
    """Expand state ``s`` at ``level``: close it there and update its successors (AMRA* Expand)."""
    num_q = L.trans.shape[0]
    c = s // num_q
    q = s % num_q
    iteration = S.iscal[3]
    w1 = S.fscal[1]
    w2 = S.fscal[2]
    if S.epoch[s] != iteration:
        S.epoch[s] = iteration
        S.closed[s] = 0
    S.closed[s] |= 1 << level
    gs = S.g[s]
    n = successors(G, A, M, L, c, q, level, max_level, out_c, out_q, out_cost, out_act)
    for t in range(n):
        nc = out_c[t]
        nq = out_q[t]
        ns = nc * num_q + nq
        gn = gs + out_cost[t]
        if S.seen[ns] and gn >= S.g[ns]:
            continue
        if L.accepting[nq]:
            S.g[ns] = gn
            S.parent[ns] = s
            S.action[ns] = out_act[t]
            S.seen[ns] = 1
            if gn < S.fscal[0]:
                S.fscal[0] = gn
                S.iscal[0] = ns
            continue
        h0 = h_ltl(L, nc, nq)
        if h0 == INF:
            continue
        S.g[ns] = gn
        S.parent[ns] = s
        S.action[ns] = out_act[t]
        S.seen[ns] = 1
        if closed_at(S, ns, 0, iteration):
            S.incons[S.iscal[2]] = ns
            S.iscal[2] += 1
            continue
        f0 = gn + w1 * h0
        S.hsize[0] = heap_push(S.hkey[0], S.hg[0], S.hstate[0], S.hsize[0], f0, gn, ns)
        for j in range(1, q_level.shape[0]):
            lj = q_level[j]
            if not in_level(G, nc, lj) or closed_at(S, ns, lj, iteration):
                continue
            fj = gn + w1 * queue_h(G, L, q_htype[j], nc, nq, h0)
            if fj <= w2 * f0:
                S.hsize[j] = heap_push(S.hkey[j], S.hg[j], S.hstate[j], S.hsize[j], fj, gn, ns)


@njit(cache=True)
def clean_top(S, i, level, iteration):
    """Drop stale entries from the top of heap ``i``; return its minimum key (inf when empty)."""
    while S.hsize[i] > 0:
        s = S.hstate[i, 0]
        if S.hg[i, 0] == S.g[s] and not closed_at(S, s, level, iteration):
            return S.hkey[i, 0]
        S.hsize[i] = heap_pop(S.hkey[i], S.hg[i], S.hstate[i], S.hsize[i])
    return INF


@njit(cache=True)
def start_iteration(G, L, S, q_level, q_htype, w1, w2, iteration):
    """Begin an AMRA* iteration with weights (w1, w2): OPEN_0 = (valid OPEN_0) + INCONS, re-keyed; every
    other queue gets the OPEN_0 states of its level; all closed sets are cleared. The heaps need room for
    ``hsize[0] + n_incons`` entries."""
    num_q = L.trans.shape[0]
    previous = iteration - 1
    cand = np.empty(S.hsize[0] + S.iscal[2], dtype=np.int64)
    m = 0
    for e in range(S.hsize[0]):
        s = S.hstate[0, e]
        if S.hg[0, e] != S.g[s] or closed_at(S, s, 0, previous) or S.epoch[s] == iteration:
            continue
        S.epoch[s] = iteration
        S.closed[s] = 0
        cand[m] = s
        m += 1
    for e in range(S.iscal[2]):
        s = S.incons[e]
        if S.epoch[s] == iteration:
            continue
        S.epoch[s] = iteration
        S.closed[s] = 0
        cand[m] = s
        m += 1
    S.iscal[2] = 0
    S.iscal[3] = iteration
    S.fscal[1] = w1
    S.fscal[2] = w2
    for i in range(q_level.shape[0]):
        S.hsize[i] = 0
    for t in range(m):
        s = cand[t]
        c = s // num_q
        q = s % num_q
        gs = S.g[s]
        h0 = h_ltl(L, c, q)
        S.hsize[0] = heap_push(S.hkey[0], S.hg[0], S.hstate[0], S.hsize[0], gs + w1 * h0, gs, s)
        for j in range(1, q_level.shape[0]):
            if in_level(G, c, q_level[j]):
                fj = gs + w1 * queue_h(G, L, q_htype[j], c, q, h0)
                S.hsize[j] = heap_push(S.hkey[j], S.hg[j], S.hstate[j], S.hsize[j], fj, gs, s)


@njit(cache=True)
def improve_path(G, A, M, L, S, q_level, q_htype, max_level, budget, max_succ):
    """AMRA* ImprovePath, round robin over the queues, until the bound holds or a limit is hit.

    Returns ``(status, expansions)``: FOUND when the best goal's g <= w2 * (min key of the anchor queue)
    -- with a consistent anchor heuristic that bounds its cost by w1*w2 times the optimum, and makes it
    optimal at (1, 1); EXHAUSTED when the anchor queue is empty and no goal was found; BUDGET after
    ``budget`` expansions; GROW when a heap or the INCONS list needs more room.
    """
    num_queues = q_level.shape[0]
    iteration = S.iscal[3]
    w2 = S.fscal[2]
    out_c = np.empty(max_succ, dtype=np.int64)
    out_q = np.empty(max_succ, dtype=np.int64)
    out_cost = np.empty(max_succ, dtype=np.float64)
    out_act = np.empty(max_succ, dtype=np.int32)
    capacity = S.hkey.shape[1]
    done = 0
    while True:
        mk0 = clean_top(S, np.int64(0), q_level[0], iteration)  # typed as the other call: one specialization
        goal = S.fscal[0]
        if goal < INF and goal <= w2 * mk0:
            return FOUND, done
        if mk0 == INF:
            return EXHAUSTED, done
        if done >= budget:
            return BUDGET, done
        for i in range(num_queues):
            if S.hsize[i] + max_succ > capacity:
                return GROW, done
        if S.iscal[2] + max_succ > S.incons.shape[0]:
            return GROW, done
        chosen = 0
        if num_queues > 1:
            i = S.iscal[1]
            S.iscal[1] = i % (num_queues - 1) + 1
            if clean_top(S, i, q_level[i], iteration) <= w2 * mk0:
                chosen = i
        s = S.hstate[chosen, 0]
        S.hsize[chosen] = heap_pop(S.hkey[chosen], S.hg[chosen], S.hstate[chosen], S.hsize[chosen])
        expand(G, A, M, L, S, q_level, q_htype, max_level, s, q_level[chosen], out_c, out_q, out_cost, out_act)
        S.expansions[chosen] += 1
        done += 1
