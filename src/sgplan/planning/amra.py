"""AMRA* over the hierarchical domain: setups, weight schedule, budgets, results (the Python driver).

The compiled loop is in :mod:`sgplan.planning._search`; this module owns the iteration schedule
(weights (10, 20) halving to (1, 1), reference-algorithm.md §6; at most 255 iterations), the queue layout
of each setup (§7.2), the search memory (a record pool reserved once, lazily committed), time/expansion
budgets, per-iteration records and path recovery.

Goal tracking (departing from the authors' inert test, §12.9): every generated state whose automaton
state is accepting is a goal; the best one's g is compared with ``w2 * min key(anchor)`` after every
expansion, which keeps the w1*w2 bound of each iteration and makes the (1, 1) iteration exactly optimal
(the anchor heuristic h_LTL is consistent). Any number of accepting states is supported.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from sgplan.errors import PlanningError
from sgplan.planning import _search
from sgplan.planning._memory import sparse_zeros
from sgplan.planning._search import ACT_MAP, BUDGET, GROW, SearchState
from sgplan.planning.domain import PlanningDomain, _infeasible_reason
from sgplan.planning.problem import PlanningProblem
from sgplan.planning.setups import get_setup


@dataclass(frozen=True)
class IterationRecord:
    """One AMRA* iteration: weights, solution cost (metres), suboptimality bound w1*w2, cumulative search
    seconds at its end, and cumulative expansions per queue (``PlanResult.queues`` order)."""

    w1: float
    w2: float
    cost_m: float
    bound: float
    time_s: float
    expansions: tuple[int, ...]


@dataclass(eq=False)
class PlanResult:
    """Outcome of :func:`plan`.

    Attributes
    ----------
    status:
        ``"optimal"`` (the (1, 1) iteration finished: ``cost_m`` is the exact optimum) or ``"timeout"``
        (a budget ran out: the best path so far, or none).
    cost_m:
        cost of ``path`` in metres (``inf`` without a path).
    path:
        ``(n, 4)`` int64 ``[row, col, floor, q]`` of every cell, start first; ``q`` is the automaton state
        after the cell's label was read (the start's per the profile). ``None`` without a path.
    iterations:
        one :class:`IterationRecord` per finished iteration.
    precompute_s, search_s:
        seconds to build the domain (once per problem), and of search (including lazily built actions).
    search_bytes:
        bytes of search memory in use at the end (:func:`state_bytes`): state records of the pages the
        search touched, the page table, heap and INCONS entries -- not cells x automaton states.
    """

    status: str
    setup: str
    profile: str
    cost_m: float
    path: np.ndarray | None
    iterations: list[IterationRecord]
    queues: tuple[str, ...]
    precompute_s: float
    search_s: float
    search_bytes: int = 0

    @property
    def expansions(self) -> int:
        return int(sum(self.iterations[-1].expansions)) if self.iterations else 0


IterationCallback = Callable[[IterationRecord], None]


def plan(
    problem: PlanningProblem,
    setup: str = "ALL",
    *,
    time_limit_s: float | None = None,
    max_expansions: int | None = None,
    callback: IterationCallback | None = None,
    weights: tuple[float, float] = (10.0, 20.0),
    final_weights: tuple[float, float] = (1.0, 1.0),
    decay: float = 0.5,
    prebuild_actions: bool = True,
    release_maps: bool = False,
) -> PlanResult:
    """Plan an optimal path for ``problem`` with AMRA* in configuration ``setup``.

    Parameters
    ----------
    problem:
        the planning problem; its domain is built on first use and reused by later calls.
    setup:
        a name of :data:`SETUPS` (ALL, NO-LLM, A*, OCC, OBJ, ROOM, FLR).
    time_limit_s, max_expansions:
        budgets for the search (seconds of search, total expansions); when one runs out the result has
        status ``"timeout"`` and the best path found so far.
    callback:
        called with each :class:`IterationRecord` as soon as its iteration finishes.
    weights, final_weights, decay:
        the schedule: (w1, w2) start at ``weights`` and are multiplied by ``decay`` (floored at
        ``final_weights``) after each iteration; the iteration run at ``final_weights`` is the last.
    prebuild_actions:
        build every composite action map before the search clock starts (the authors' accounting, and
        a first path within milliseconds); ``False`` builds them lazily inside the search, which saves
        1-3 s of precomputation on large scenes when only the optimum matters. Setups without composite
        actions (A*, ``max_level`` 1) never build them.
    release_maps:
        the caller plans on ``problem`` only this once (its domain and action maps are no one else's, as
        in :func:`sgplan.plan` without a keeping session): the maps' distances and label runs are freed
        when the first iteration with w1 = 1 starts, since from then on the anchor searches alone on
        occupancy moves (:func:`sgplan.planning._search.improve_path`) and never reads them (22 MB of
        the 254 MB peak of Collierville mission 5, ALL). A later plan on the problem still works: it
        rebuilds the maps it needs.

    Raises
    ------
    PlanningError
        ``status="invalid-start"`` / ``"infeasible"`` (see :func:`sgplan.planning.domain.build_domain`;
        ``"infeasible"`` also when the search proves that no path exists), or ``status="error"`` for a bad
        setup or a setup that needs LLM guidance the problem does not carry.
    """
    spec = get_setup(setup)
    if (
        not (0 < decay < 1)
        or min(final_weights) < 1
        or weights[0] < final_weights[0]
        or weights[1] < final_weights[1]
    ):
        raise PlanningError(f"bad weight schedule {weights} -> {final_weights} with decay {decay}")
    if _schedule_length(weights, final_weights, decay) > MAX_ITERATIONS:
        raise PlanningError(
            f"weight schedule {weights} -> {final_weights} with decay {decay} has more than {MAX_ITERATIONS}"
            " iterations (the search tags closed states with the iteration in 8 bits); lower the decay factor"
        )
    domain = problem.domain_for(spec.max_level)  # A*: no composite action tables
    if spec.uses_llm and domain.llm is None:
        raise PlanningError(f"setup {spec.name} needs LLM guidance; give the problem guidance or use NO-LLM")
    too_big = _search.check_layout(domain.graph.num_cells, domain.num_states, len(domain.kactions.map_floor))
    if too_big is not None:
        raise PlanningError(f"{too_big}: split the building or simplify the mission")
    if prebuild_actions and spec.max_level >= 2:
        domain.build_actions()
    q_level = np.array([level for level, _ in spec.queues], dtype=np.int32)
    q_htype = np.array([h for _, h in spec.queues], dtype=np.int32)
    acts = domain.kactions
    max_succ = int(
        10 + np.diff(acts.room_obj_ptr).max(initial=0) + np.diff(acts.room_room_ptr).max(initial=0) + 2
    )
    warm_s = _warm_up(domain, q_level, q_htype, spec.max_level, max_succ)
    result = PlanResult(
        status="optimal", setup=spec.name, profile=problem.profile, cost_m=float("inf"), path=None,
        iterations=[], queues=spec.queue_names, precompute_s=domain.precompute_s + warm_s, search_s=0.0,
    )
    if domain.accepting[domain.q_start]:
        result.cost_m = 0.0
        result.path = _path_rows(domain, np.array([domain.start_cell]))
        result.iterations.append(
            IterationRecord(*weights, 0.0, weights[0] * weights[1], 0.0, (0,) * len(spec.queues))
        )
        return result

    state = _new_state(domain, len(spec.queues))
    chunk = 4096
    w1, w2 = float(weights[0]), float(weights[1])
    started = 0
    expansions = 0
    bound = 0.0  # a lower bound on the optimum, from the last iteration's start (see _search.start_iteration)
    while True:
        # An iteration whose bound already holds (best goal <= w2 x the lower bound: it would stop before
        # its first expansion) is recorded without re-keying the queues; ARA*'s own shortcut.
        if release_maps and w1 <= 1.0:
            domain.release_map_fields()
        if not (state.fscal[0] <= w2 * bound):
            started += 1
            state = _reserve(state, int(state.hsize[0] + state.iscal[_search.I_NINCONS]) + max_succ)
            t0 = time.perf_counter()
            bound = _search.start_iteration(
                domain.kgraph, domain.klogic, state, q_level, q_htype, w1, w2, started
            )
            result.search_s += time.perf_counter() - t0
        while not (state.fscal[0] <= w2 * bound):
            budget = chunk if max_expansions is None else max(0, min(chunk, max_expansions - expansions))
            t0 = time.perf_counter()
            code, done = _search.improve_path(
                domain.kgraph, domain.kactions, domain.kmaps, domain.klogic, state, q_level, q_htype,
                spec.max_level, budget, max_succ,
            )
            result.search_s += time.perf_counter() - t0
            expansions += int(done)
            if code == GROW:
                state = _reserve(state, 2 * int(state.hsize.max(initial=0)) + max_succ, free_pages=max_succ)
                continue
            if code != BUDGET:
                break
            over_time = time_limit_s is not None and result.search_s >= time_limit_s
            if over_time or (max_expansions is not None and expansions >= max_expansions):
                result.status = "timeout"
                break
        if result.status == "timeout":
            break
        if not np.isfinite(state.fscal[0]):
            raise PlanningError(
                _infeasible_reason(
                    problem, domain.label_masks[domain.cell_label],
                    np.isfinite(domain.graph.distances(np.array([domain.start_cell]))), domain.q_start,
                ) + " (proved by exhaustive search)",
                status="infeasible",
            )
        record = IterationRecord(
            w1, w2, float(state.fscal[0]), w1 * w2, result.search_s, tuple(int(x) for x in state.expansions)
        )
        result.iterations.append(record)
        if callback is not None:
            callback(record)
        if w1 <= final_weights[0] and w2 <= final_weights[1]:
            break
        w1, w2 = max(w1 * decay, final_weights[0]), max(w2 * decay, final_weights[1])

    result.search_bytes = state_bytes(state)
    if np.isfinite(state.fscal[0]):
        cells = _recover_cells(domain, state, int(state.iscal[0]))
        result.path = _path_rows(domain, cells)
        result.cost_m = path_cost(domain, cells)
    return result


MAX_ITERATIONS = _search.TAG_MASK
"""The longest weight schedule (closed sets are tagged with the iteration number modulo 256)."""


def _schedule_length(weights: tuple[float, float], final: tuple[float, float], decay: float) -> int:
    """Iterations in the schedule ``weights`` -> ``final`` (each weight times ``decay``, floored)."""
    w1, w2, n = float(weights[0]), float(weights[1]), 1
    while not (w1 <= final[0] and w2 <= final[1]):
        w1, w2, n = max(w1 * decay, final[0]), max(w2 * decay, final[1]), n + 1
        if n > MAX_ITERATIONS:
            break
    return n


def _warm_up(
    domain: PlanningDomain, q_level: np.ndarray, q_htype: np.ndarray, max_level: int, max_succ: int
) -> float:
    """Load (or compile) the search kernels on an empty search, so that no JIT time counts as search."""
    t0 = time.perf_counter()
    scratch = _new_state(domain, len(q_level), pages=1)
    scratch.iscal[2] = 0
    _search.start_iteration(domain.kgraph, domain.klogic, scratch, q_level, q_htype, 1.0, 1.0, 1)
    _search.improve_path(
        domain.kgraph,
        domain.kactions,
        domain.kmaps,
        domain.klogic,
        scratch,
        q_level,
        q_htype,
        max_level,
        0,
        max_succ,
    )
    return time.perf_counter() - t0


def _new_state(domain: PlanningDomain, num_queues: int, pages: int | None = None) -> SearchState:
    """Fresh search memory with the start state in INCONS (so the first iteration opens it).

    The pool has ``pages`` page slots, grown on demand; by default a slot for every (automaton state,
    block) pair, or as many as the operating system lets us map (:func:`_pool_buffer`). The reservation
    is lazily committed, so the slots a search never uses cost no memory, and a pool that never grows is
    never copied: each doubling wrote and page-faulted the used part again (10-17 % of the search on the
    larger Gibson cases), and at its peak held both copies (+1 GB on 9 unordered goals)."""
    num_q = domain.num_states
    blocks = -(-domain.graph.num_cells // _search.PAGE)
    pool = _pool_buffer(num_q * blocks if pages is None else pages)
    capacity = int(min(domain.graph.num_cells * num_q + 16, 1 << 20))
    hbuf = sparse_zeros(num_queues * capacity * _search.HREC, np.int64)
    state = SearchState(
        ptab=np.full((num_q, blocks), -1, dtype=np.int32),
        pool=pool,
        poolf=pool.view(np.float64),
        hbuf=hbuf,
        hbuff=hbuf.view(np.float64),
        hsize=np.zeros(num_queues, dtype=np.int64),
        incons=np.empty(capacity, dtype=np.int64),
        fscal=np.array([np.inf, 1.0, 1.0]),
        iscal=np.array([-1, 1, 1, 0, 0, 0, 0], dtype=np.int64),
        expansions=np.zeros(num_queues, dtype=np.int64),
        h_evals=np.zeros(domain.klogic.h_ready.shape[0], dtype=np.int64),
    )
    _search.init_start(state.ptab, state.pool, state.poolf, state.iscal, state.incons,
                       domain.start_cell, domain.q_start)
    return state


def _pool_buffer(pages: int) -> np.ndarray:
    """A lazily committed pool of ``pages`` page slots, or of as many as can be mapped (halving on
    MemoryError, down to one; the search grows it later if it needs more)."""
    while True:
        try:
            return sparse_zeros(pages * _search.PAGE * _search.REC, np.int64)
        except MemoryError:
            if pages <= 1:
                raise
            pages //= 2


def _reserve(state: SearchState, capacity: int, free_pages: int = 0) -> SearchState:
    """``state`` with heaps and INCONS able to hold at least ``capacity`` entries each, and at least
    ``free_pages`` unused page slots in the pool (each grown by doubling, contents kept)."""
    rec = _search.HREC
    num_queues = state.hsize.shape[0]
    old_cap = state.hbuf.shape[0] // (rec * num_queues)
    new = old_cap
    while new < capacity:
        new *= 2
    if new != old_cap:
        hbuf = sparse_zeros(num_queues * new * rec, np.int64)
        for i in range(num_queues):  # heap i moves from entry offset i * old_cap to i * new
            size, to, at = int(state.hsize[i]) * rec, i * new * rec, i * old_cap * rec
            hbuf[to : to + size] = state.hbuf[at : at + size]
        state = state._replace(hbuf=hbuf, hbuff=hbuf.view(np.float64))
    if state.incons.shape[0] < capacity:
        incons = np.empty(max(capacity, 2 * state.incons.shape[0]), dtype=np.int64)
        incons[: state.iscal[2]] = state.incons[: state.iscal[2]]
        state = state._replace(incons=incons)
    page_words = _search.PAGE * _search.REC
    used, slots = int(state.iscal[_search.I_PAGES]), state.pool.shape[0] // page_words
    if used + free_pages > slots:
        pool = sparse_zeros(max(2 * slots, used + free_pages) * page_words, np.int64)
        pool[: used * page_words] = state.pool[: used * page_words]
        state = state._replace(pool=pool, poolf=pool.view(np.float64))
    return state


def state_bytes(state: SearchState) -> int:
    """Bytes of search memory that can be committed: used pool pages, page table, heap and INCONS
    entries in use (the rest of the lazily committed buffers is never touched)."""
    used = int(state.iscal[_search.I_PAGES]) * _search.PAGE * _search.REC * 8
    heaps = int(state.hsize.sum()) * _search.HREC * 8
    return used + state.ptab.nbytes + heaps + int(state.iscal[2]) * 8


def _recover_cells(domain: PlanningDomain, state: SearchState, goal: int) -> np.ndarray:
    """Cell indices of the path to ``goal``, composite actions replayed cell by cell."""
    qb = int(_search.q_bits(domain.num_states))
    chain = [(goal, -1)]
    while True:
        _, parent, action = _search.read_record(state.ptab, state.pool, state.poolf, chain[-1][0])
        if parent < 0:
            break
        chain[-1] = (chain[-1][0], int(action))
        chain.append((int(parent), -1))
        if len(chain) > int(state.iscal[_search.I_PAGES]) * _search.PAGE + 1:
            raise PlanningError("internal error: the parent pointers form a cycle")
    chain.reverse()
    cells = [chain[0][0] >> qb]
    for child, code in chain[1:]:
        if code < ACT_MAP:
            cells.append(child >> qb)
        else:
            cells += domain.action_cells(code - ACT_MAP, cells[-1], child >> qb)
    return np.array(cells, dtype=np.int64)


def _path_rows(domain: PlanningDomain, cells: np.ndarray) -> np.ndarray:
    """``(n, 4)`` ``[row, col, floor, q]`` rows for a cell sequence, q replayed from q_start."""
    graph = domain.graph
    states = np.empty(len(cells), dtype=np.int64)
    q = domain.q_start
    states[0] = q
    labels = domain.cell_label[cells]
    for i in range(1, len(cells)):
        q = int(domain.trans[q, labels[i]])
        states[i] = q
    return np.stack(
        [graph.cell_row[cells], graph.cell_col[cells], graph.cell_floor[cells], states], axis=1
    ).astype(np.int64)


def path_cost(domain: PlanningDomain, cells: np.ndarray) -> float:
    """Metres of a cell sequence: Euclidean steps on a floor plus stairs costs between floors."""
    graph = domain.graph
    a, b = cells[:-1], cells[1:]
    same = graph.cell_floor[a] == graph.cell_floor[b]
    res_x, res_y = (graph.step_cost[1], graph.step_cost[3])
    steps = np.hypot(
        (graph.cell_row[b] - graph.cell_row[a])[same] * res_x,
        (graph.cell_col[b] - graph.cell_col[a])[same] * res_y,
    )
    total = float(steps.sum())
    for u, v in zip(a[~same], b[~same]):
        j = np.flatnonzero((graph.stairs_from == u) & (graph.stairs_to == v))
        total += float(graph.stairs_cost[j[0]])
    return total
