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

from sgplan.heap import heap_pop_at, heap_push_at
from sgplan.planning._dijkstra import dijkstra, label_runs
from sgplan.planning.ltl_heuristic import fill_row

FOUND, EXHAUSTED, BUDGET, GROW = 0, 1, 2, 3
ACT_STAIRS = 8
ACT_MAP = 16
ALL_LEVELS = 0x1F  # closed bits of levels 0 (anchor) .. 4
INF = np.inf

SearchState = namedtuple(
    "SearchState", "g parent action seen closed epoch hkey hg hstate hsize incons fscal iscal expansions"
)
"""Search memory. ``fscal = [goal_g, w1, w2]``; ``iscal = [goal_state, round_robin, n_incons, iteration]``;
``hkey/hg/hstate (K * capacity,)`` one lazy heap per queue (queue ``i`` at offset ``i * capacity``) with
``hsize (K,)``; ``expansions (K,)``."""


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
def h_ltl(accepting, q_row, hmap, c, q):
    """h_LTL at (c, q); q's row must be filled (:func:`~sgplan.planning.ltl_heuristic.fill_row`)."""
    if accepting[q]:
        return 0.0
    row = q_row[q]
    if row < 0:
        return INF
    return hmap[row, c]


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


@njit(cache=True, inline="always")
def closed_at(epoch, closed, s, level, iteration):
    return epoch[s] == iteration and (closed[s] >> level) & 1 == 1


@njit(cache=True, inline="always")
def clean_top(g, epoch, closed, hkey, hg, hstate, hsize, capacity, i, level, iteration):
    """Drop stale entries from the top of heap ``i``; return its minimum key (inf when empty)."""
    base = i * capacity
    while hsize[i] > 0:
        s = hstate[base]
        if hg[base] == g[s] and not (epoch[s] == iteration and (closed[s] >> level) & 1 == 1):
            return hkey[base]
        hsize[i] = heap_pop_at(hkey, hg, hstate, base, hsize[i])
    return INF


@njit(cache=True)
def start_iteration(G, L, S, q_level, q_htype, w1, w2, iteration):
    """Begin an AMRA* iteration with weights (w1, w2): OPEN_0 = (valid OPEN_0) + INCONS, re-keyed; every
    other queue gets the OPEN_0 states of its level; all closed sets are cleared. The heaps need room for
    ``hsize[0] + n_incons`` entries."""
    num_q = L.trans.shape[0]
    g, epoch, closed, incons, iscal = S.g, S.epoch, S.closed, S.incons, S.iscal
    hkey, hg, hstate, hsize = S.hkey, S.hg, S.hstate, S.hsize
    accepting, q_row, hmap = L.accepting, L.q_row, L.hmap
    cell_room, cell_xyz, in_object_region = G.cell_room, G.cell_xyz, G.in_object_region
    llm_sum, llm_target, llm_valid = L.llm_sum, L.llm_target, L.llm_valid
    previous = iteration - 1
    capacity = hkey.shape[0] // q_level.shape[0]
    cand = np.empty(hsize[0] + iscal[2], dtype=np.int64)
    m = 0
    for e in range(hsize[0]):
        s = hstate[e]
        if hg[e] != g[s] or closed_at(epoch, closed, s, 0, previous) or epoch[s] == iteration:
            continue
        epoch[s] = iteration
        closed[s] = 0
        cand[m] = s
        m += 1
    for e in range(iscal[2]):
        s = incons[e]
        if epoch[s] == iteration:
            continue
        epoch[s] = iteration
        closed[s] = 0
        cand[m] = s
        m += 1
    iscal[2] = 0
    iscal[3] = iteration
    S.fscal[1] = w1
    S.fscal[2] = w2
    for i in range(q_level.shape[0]):
        hsize[i] = 0
    for t in range(m):
        s = cand[t]
        c = s // num_q
        q = s % num_q
        gs = g[s]
        row = q_row[q]
        if row >= 0 and L.h_ready[row] == 0:
            fill_row(hmap, L.h_ready, L.h_dist, L.h_ptr, L.h_label, L.h_add, row)
        h0 = h_ltl(accepting, q_row, hmap, c, q)
        hsize[0] = heap_push_at(hkey, hg, hstate, 0, hsize[0], gs + w1 * h0, gs, s)
        for j in range(1, q_level.shape[0]):
            if in_level(cell_room, in_object_region, c, q_level[j]):
                hj = (
                    h0
                    if q_htype[j] == 0
                    else h_llm_core(cell_room, cell_xyz, accepting, llm_sum, llm_target, llm_valid, c, q)
                )
                hsize[j] = heap_push_at(hkey, hg, hstate, j * capacity, hsize[j], gs + w1 * hj, gs, s)


@njit(cache=True)
def improve_path(G, A, M, L, S, q_level, q_htype, max_level, budget, max_succ):
    """AMRA* ImprovePath, round robin over the queues, until the bound holds or a limit is hit.

    Returns ``(status, expansions)``: FOUND when the best goal's g <= w2 * (min key of the anchor queue)
    -- with a consistent anchor heuristic that bounds its cost by w1*w2 times the optimum, and makes it
    optimal at (1, 1); EXHAUSTED when the anchor queue is empty and no goal was found; BUDGET after
    ``budget`` expansions; GROW when a heap or the INCONS list needs more room.

    Expand (AMRA*): the chosen state is closed at its queue's level (at every level when the anchor
    expands it: the anchor generates the successors of all levels from the same g), each successor whose g
    improves is recorded; an accepting one becomes a goal candidate, one already closed in the anchor goes
    to INCONS, others enter the anchor queue and every queue of a level they belong to whose key is within
    w2 of the anchor key.
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
    g, parent, action, seen, closed, epoch = S.g, S.parent, S.action, S.seen, S.closed, S.epoch
    hkey, hg, hstate, hsize, incons, fscal, iscal = (
        S.hkey,
        S.hg,
        S.hstate,
        S.hsize,
        S.incons,
        S.fscal,
        S.iscal,
    )
    expansions = S.expansions

    num_queues = q_level.shape[0]
    num_q = trans.shape[0]
    iteration = iscal[3]
    w1 = fscal[1]
    w2 = fscal[2]
    out_c = np.empty(max_succ, dtype=np.int64)
    out_q = np.empty(max_succ, dtype=np.int64)
    out_cost = np.empty(max_succ, dtype=np.float64)
    out_act = np.empty(max_succ, dtype=np.int32)
    capacity = hkey.shape[0] // num_queues
    done = 0
    while True:
        mk0 = clean_top(g, epoch, closed, hkey, hg, hstate, hsize, capacity, 0, q_level[0], iteration)
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
        if iscal[2] + max_succ > incons.shape[0]:
            return GROW, done
        chosen = 0
        if num_queues > 1:
            i = iscal[1]
            iscal[1] = i % (num_queues - 1) + 1
            if (
                clean_top(g, epoch, closed, hkey, hg, hstate, hsize, capacity, i, q_level[i], iteration)
                <= w2 * mk0
            ):
                chosen = i
        s = hstate[chosen * capacity]
        hsize[chosen] = heap_pop_at(hkey, hg, hstate, chosen * capacity, hsize[chosen])
        level = q_level[chosen]
        expansions[chosen] += 1
        done += 1

        # Expand s at level.
        c = s // num_q
        q = s % num_q
        if epoch[s] != iteration:
            epoch[s] = iteration
            closed[s] = 0
        closed[s] |= ALL_LEVELS if level == 0 else 1 << level
        gs = g[s]
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
        if max_level >= 2 and level != 1:
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
            ns = nc * num_q + nq
            gn = gs + out_cost[t]
            if seen[ns] and gn >= g[ns]:
                continue
            if accepting[nq]:
                g[ns] = gn
                parent[ns] = s
                action[ns] = out_act[t]
                seen[ns] = 1
                if gn < fscal[0]:
                    fscal[0] = gn
                    iscal[0] = ns
                continue
            row = q_row[nq]
            if row >= 0 and h_ready[row] == 0:  # first time the search meets state nq
                fill_row(hmap, h_ready, h_dist, h_ptr, h_label, h_add, row)
            h0 = h_ltl(accepting, q_row, hmap, nc, nq)
            if h0 == INF:
                continue
            g[ns] = gn
            parent[ns] = s
            action[ns] = out_act[t]
            seen[ns] = 1
            if epoch[ns] == iteration and closed[ns] & 1 == 1:  # closed in the anchor
                incons[iscal[2]] = ns
                iscal[2] += 1
                continue
            f0 = gn + w1 * h0
            hsize[0] = heap_push_at(hkey, hg, hstate, 0, hsize[0], f0, gn, ns)
            h_l = -1.0  # h_LLM(nc, nq) (>= 0), computed once for all the LLM queues
            for j in range(1, num_queues):
                lj = q_level[j]
                if (lj == 2 and not in_object_region[nc]) or (
                    lj == 3 and cell_room[nc] < 0
                ):  # in_level, inline
                    continue
                if epoch[ns] == iteration and (closed[ns] >> lj) & 1 == 1:
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
                    hsize[j] = heap_push_at(hkey, hg, hstate, j * capacity, hsize[j], fj, gn, ns)
