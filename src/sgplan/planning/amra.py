"""AMRA* over the hierarchical domain: the Python driver.

:func:`plan` runs the iterations of a weight schedule (:mod:`sgplan.planning.schedule`) with the queues of a
setup (:mod:`sgplan.planning.setups`) over the compiled loop (:mod:`sgplan.planning._search`), in chunks of
at most :data:`CHUNK_EXPANSIONS` expansions between which it grows the search memory
(:mod:`sgplan.planning.search_memory`) and polls a termination condition
(:mod:`sgplan.planning.termination`); it records each iteration and recovers the path at the end.

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
from sgplan.planning import _search, search_memory
from sgplan.planning._search import ACT_MAP, BUDGET, GROW, SearchState
from sgplan.planning.domain import PlanningDomain, _infeasible_reason, domain_of
from sgplan.planning.problem import PlanningProblem
from sgplan.planning.schedule import PAPER_SCHEDULE, WeightSchedule
from sgplan.planning.setups import Setup, get_setup
from sgplan.planning.termination import Progress, Stop, Termination


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
class SearchResult:
    """Outcome of :func:`plan` (the search's own; the public result of :func:`sgplan.plan` is
    :class:`sgplan.PlanResult`).

    Attributes
    ----------
    status:
        ``"optimal"`` (the final iteration finished: ``cost_m`` is the exact optimum), ``"timeout"`` (a time,
        deadline or expansion limit ran out) or ``"cancelled"`` (a cancel flag was set); a stopped search
        keeps the best path so far, or none.
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
        bytes of search memory in use at the end (:func:`~sgplan.planning.search_memory.state_bytes`):
        state records of the pages the search touched, the page table, heap and INCONS entries -- not
        cells x automaton states.
    stop_reason:
        why a stopped search stopped (:class:`~sgplan.planning.termination.Stop`), ``None`` otherwise.
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
    stop_reason: str | None = None

    @property
    def expansions(self) -> int:
        return int(sum(self.iterations[-1].expansions)) if self.iterations else 0


IterationCallback = Callable[[IterationRecord], None]

CHUNK_EXPANSIONS = 4096
"""Expansions of one call of the compiled search at most. Between two calls the driver grows the search
memory when asked and polls the termination condition, so a cancel or a limit takes effect within one
chunk; small enough for that, large enough that the calls cost nothing next to the search."""


def plan(
    problem: PlanningProblem,
    setup: str = "ALL",
    *,
    termination: Termination | None = None,
    callback: IterationCallback | None = None,
    schedule: WeightSchedule = PAPER_SCHEDULE,
    prebuild_actions: bool = True,
    release_maps: bool = False,
) -> SearchResult:
    """Plan an optimal path for ``problem`` with AMRA* in configuration ``setup``.

    Parameters
    ----------
    problem:
        the planning problem; its domain is built on first use and reused by later calls.
    setup:
        a name of :data:`~sgplan.planning.setups.SETUPS` (ALL, NO-LLM, A*, OCC, OBJ, ROOM, FLR).
    termination:
        when to stop before the optimum (:mod:`sgplan.planning.termination`: a time or expansion limit, a
        deadline, a cancel flag, any of them together), polled before the domain is built, before the
        search and before every chunk of at most :data:`CHUNK_EXPANSIONS` expansions; the result then has
        its status (``"timeout"`` or ``"cancelled"``), its ``stop_reason`` and the best path found so far.
        ``None``: run to the optimum.
    callback:
        called with each :class:`IterationRecord` as soon as its iteration finishes.
    schedule:
        the iterations' weights (:class:`~sgplan.planning.schedule.WeightSchedule`; the paper's by default).
    prebuild_actions:
        build every composite action map before the search clock starts (the authors' accounting, and
        a first path within milliseconds); ``False`` builds them lazily inside the search, which saves
        precomputation on large scenes when only the optimum matters. Setups without composite
        actions (A*, ``max_level`` 1) never build them.
    release_maps:
        the caller plans on ``problem`` only this once (its domain and action maps are no one else's, as
        in :func:`sgplan.plan` without a keeping session): the maps' distances and label runs are freed
        when the first iteration with w1 = 1 starts, since from then on the anchor searches alone on
        occupancy moves (:func:`sgplan.planning._search.improve_path`) and never reads them. A later plan
        on the problem still works: it rebuilds the maps it needs.

    Raises
    ------
    PlanningError
        ``status="invalid-start"`` / ``"infeasible"`` (see :func:`sgplan.planning.domain.build_domain`;
        ``"infeasible"`` also when the search proves that no path exists), or ``status="error"`` for a bad
        setup or a setup that needs LLM guidance the problem does not carry.
    """
    spec = get_setup(setup)
    stop = _poll(termination, Progress())
    if stop is not None:  # before any precomputation
        return _stopped_before_search(problem, spec, stop)
    search = _Search(problem, spec, prebuild_actions)
    if search.start_accepts:
        return search.accepting_start(schedule.first)
    stop = _poll(termination, Progress())
    for w1, w2 in () if stop is not None else schedule:
        if release_maps and w1 <= 1.0:
            search.domain.release_map_fields()
        stop = search.run_iteration(w1, w2, termination)
        if stop is not None:
            break
        record = search.record(w1, w2)
        search.result.iterations.append(record)
        if callback is not None:
            callback(record)
    return search.finish(stop)


def _poll(termination: Termination | None, progress: Progress) -> Stop | None:
    return None if termination is None else termination.check(progress)


def _stopped_before_search(problem: PlanningProblem, spec: Setup, stop: Stop) -> SearchResult:
    return SearchResult(
        status=stop.status, setup=spec.name, profile=problem.profile, cost_m=float("inf"), path=None,
        iterations=[], queues=spec.queue_names, precompute_s=0.0, search_s=0.0, stop_reason=stop.reason,
    )


class _Search:
    """One AMRA* search on a problem's domain: the search memory, the clock and counters the driver keeps
    between calls of the compiled loop, and the result it fills in."""

    def __init__(self, problem: PlanningProblem, spec: Setup, prebuild_actions: bool) -> None:
        domain = domain_of(problem, spec.max_level)  # A*: no composite action tables
        if spec.uses_llm and domain.llm is None:
            raise PlanningError(
                f"setup {spec.name} needs LLM guidance; give the problem guidance or use NO-LLM"
            )
        num_maps = len(domain.kactions.map_floor)
        too_big = _search.check_layout(domain.graph.num_cells, domain.num_states, num_maps)
        if too_big is not None:
            raise PlanningError(f"{too_big}: split the building or simplify the mission")
        if prebuild_actions and spec.max_level >= 2:
            domain.build_actions()
        self.problem, self.domain, self.spec = problem, domain, spec
        self.q_level = np.array([level for level, _ in spec.queues], dtype=np.int32)
        self.q_htype = np.array([h for _, h in spec.queues], dtype=np.int32)
        acts = domain.kactions
        self.max_succ = int(
            10 + np.diff(acts.room_obj_ptr).max(initial=0) + np.diff(acts.room_room_ptr).max(initial=0) + 2
        )
        warm_s = _warm_up(domain, self.q_level, self.q_htype, spec.max_level, self.max_succ)
        self.result = SearchResult(
            status="optimal", setup=spec.name, profile=problem.profile, cost_m=float("inf"), path=None,
            iterations=[], queues=spec.queue_names, precompute_s=domain.precompute_s + warm_s, search_s=0.0,
        )
        self.start_accepts = bool(domain.accepting[domain.q_start])
        self.state = search_memory.new_state(domain, len(spec.queues))
        self.expansions = 0
        self.started = 0  # iterations begun in the compiled search (one whose bound holds begins none)
        self.bound = 0.0  # a lower bound on the optimum from the last iteration's start (start_iteration)

    @property
    def progress(self) -> Progress:
        return Progress(search_s=self.result.search_s, expansions=self.expansions)

    def accepting_start(self, weights: tuple[float, float]) -> SearchResult:
        """The result when the start itself is accepting: the one-cell path, at cost 0."""
        domain = self.domain
        self.result.cost_m = 0.0
        self.result.path = _path_rows(domain, np.array([domain.start_cell]))
        self.result.iterations.append(
            IterationRecord(*weights, 0.0, weights[0] * weights[1], 0.0, (0,) * len(self.spec.queues))
        )
        return self.result

    def run_iteration(self, w1: float, w2: float, termination: Termination | None) -> Stop | None:
        """Run the iteration with weights (w1, w2) to its end, or until ``termination`` says stop (polled
        before each chunk); returns that :class:`Stop`, or ``None`` when the iteration finished.

        Raises :class:`PlanningError` (``"infeasible"``) when the search exhausts every state without a goal.
        """
        # An iteration whose bound already holds (best goal <= w2 x the lower bound: it would stop before
        # its first expansion) is recorded without re-keying the queues; ARA*'s own shortcut.
        if not (self.state.fscal[0] <= w2 * self.bound):
            self._begin(w1, w2)
        while not (self.state.fscal[0] <= w2 * self.bound):
            stop = _poll(termination, self.progress)
            if stop is not None:
                return stop
            left = termination.expansions_left(self.progress) if termination is not None else None
            code = self._improve(CHUNK_EXPANSIONS if left is None else min(CHUNK_EXPANSIONS, left))
            if code not in (BUDGET, GROW):  # FOUND, or EXHAUSTED
                break
        if not np.isfinite(self.state.fscal[0]):
            domain = self.domain
            raise PlanningError(
                _infeasible_reason(
                    self.problem, domain.label_masks[domain.cell_label],
                    np.isfinite(domain.graph.distances(np.array([domain.start_cell]))), domain.q_start,
                ) + " (proved by exhaustive search)",
                status="infeasible",
            )
        return None

    def _begin(self, w1: float, w2: float) -> None:
        """Start an iteration in the compiled search: OPEN re-keyed for (w1, w2), INCONS merged."""
        self.started += 1
        self.state = search_memory.reserve(
            self.state, int(self.state.hsize[0] + self.state.iscal[_search.I_NINCONS]) + self.max_succ
        )
        t0 = time.perf_counter()
        self.bound = _search.start_iteration(self.domain.kgraph, self.domain.klogic, self.state, self.q_level,
                                             self.q_htype, w1, w2, self.started)
        self.result.search_s += time.perf_counter() - t0

    def _improve(self, budget: int) -> int:
        """One chunk of at most ``budget`` expansions of the compiled search; its return code, after growing
        the search memory if it asked for room."""
        domain = self.domain
        t0 = time.perf_counter()
        code, done = _search.improve_path(
            domain.kgraph, domain.kactions, domain.kmaps, domain.klogic, self.state, self.q_level,
            self.q_htype, self.spec.max_level, budget, self.max_succ,
        )
        self.result.search_s += time.perf_counter() - t0
        self.expansions += int(done)
        if code == GROW:
            self.state = search_memory.reserve(
                self.state, 2 * int(self.state.hsize.max(initial=0)) + self.max_succ, free_pages=self.max_succ
            )
        return int(code)

    def record(self, w1: float, w2: float) -> IterationRecord:
        """The record of the iteration that just finished at weights (w1, w2)."""
        state = self.state
        expansions = tuple(int(x) for x in state.expansions)
        return IterationRecord(w1, w2, float(state.fscal[0]), w1 * w2, self.result.search_s, expansions)

    def finish(self, stop: Stop | None) -> SearchResult:
        """The result: the status (the stop's, if any), the search memory used, the best path found."""
        result, state = self.result, self.state
        if stop is not None:
            result.status, result.stop_reason = stop.status, stop.reason
        result.search_bytes = search_memory.state_bytes(state)
        if np.isfinite(state.fscal[0]):
            cells = _recover_cells(self.domain, state, int(state.iscal[_search.I_GOAL]))
            result.path = _path_rows(self.domain, cells)
            result.cost_m = path_cost(self.domain, cells)
        return result


def _warm_up(
    domain: PlanningDomain, q_level: np.ndarray, q_htype: np.ndarray, max_level: int, max_succ: int
) -> float:
    """Load (or compile) the search kernels on an empty search, so that no JIT time counts as search."""
    t0 = time.perf_counter()
    scratch = search_memory.new_state(domain, len(q_level), pages=1)
    scratch.iscal[2] = 0
    _search.start_iteration(domain.kgraph, domain.klogic, scratch, q_level, q_htype, 1.0, 1.0, 1)
    _search.improve_path(domain.kgraph, domain.kactions, domain.kmaps, domain.klogic, scratch, q_level,
                         q_htype, max_level, 0, max_succ)
    return time.perf_counter() - t0


def _recover_cells(domain: PlanningDomain, state: SearchState, goal: int) -> np.ndarray:
    """Cell indices of the path to ``goal``, composite actions replayed cell by cell."""
    qb = int(_search.q_bits(domain.num_states))
    limit = int(state.iscal[_search.I_PAGES]) * _search.PAGE + 1
    states, actions = _search.parent_chain(state.ptab, state.pool, state.poolf, goal, limit)
    if states.size == 0:
        raise PlanningError("internal error: the parent pointers form a cycle")
    cells = states >> qb
    if not (actions >= ACT_MAP).any():
        return cells
    out = [int(cells[0])]
    for cell, code in zip(cells[1:].tolist(), actions[1:].tolist()):
        if code < ACT_MAP:
            out.append(cell)
        else:
            out += domain.action_cells(code - ACT_MAP, out[-1], cell)
    return np.array(out, dtype=np.int64)


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
        [*graph.row_col(cells), graph.cell_floor[cells], states], axis=1
    ).astype(np.int64)


def path_cost(domain: PlanningDomain, cells: np.ndarray) -> float:
    """Metres of a cell sequence: Euclidean steps on a floor plus stairs costs between floors."""
    graph = domain.graph
    a, b = cells[:-1], cells[1:]
    same = graph.cell_floor[a] == graph.cell_floor[b]
    res_x, res_y = (graph.step_cost[1], graph.step_cost[3])
    rows, cols = graph.row_col(cells)
    steps = np.hypot(np.diff(rows)[same] * res_x, np.diff(cols)[same] * res_y)
    total = float(steps.sum())
    for u, v in zip(a[~same], b[~same]):
        j = np.flatnonzero((graph.stairs_from == u) & (graph.stairs_to == v))
        total += float(graph.stairs_cost[j[0]])
    return total
