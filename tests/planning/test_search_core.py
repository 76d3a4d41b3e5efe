"""The search core's own structures: paged state records, pool growth, lazy h_LTL values, reuse across
AMRA* iterations, the frontier bound, the anchor-only iterations at w1 = 1, final closed states at w1 = 1
and the occupancy-only anchor at w1 = 1.

Optimality against the oracle is covered by test_optimality.py; here each structure is checked against
the plain thing it replaces (a dense dict, a filled row, a fresh search).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.planning import PlanningProblem, plan, search_memory
from sgplan.planning import _search as core
from sgplan.planning.checker import check_path
from sgplan.planning.schedule import WeightSchedule

from .instances import automaton, marks, open_building, open_grid, random_problem
from .oracle import optimal_cost

_FEW = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _oracle(problem: PlanningProblem) -> float:
    start = (problem.start[0], problem.start[1], problem.start[2])
    return optimal_cost(problem.grid, problem.labels, problem.automaton, start, problem.profile)


def _plan_or_none(problem: PlanningProblem, setup: str, **kw):
    try:
        return plan(problem, setup, **kw)
    except PlanningError as error:
        assert error.status in ("infeasible", "invalid-start")
        return None


def _empty_records(num_q: int, cells: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A page table, a pool with a slot for every (state, block), its float view, and the counters."""
    blocks = -(-cells // core.PAGE)
    ptab = np.full((num_q, blocks), -1, dtype=np.int32)
    pool = np.zeros(num_q * blocks * core.PAGE * core.REC, dtype=np.int64)
    return ptab, pool, pool.view(np.float64), np.array([-1, 1, 0, 0, 0, 0, 0], dtype=np.int64)


def test_page_table_hands_out_one_slot_per_touched_state_block() -> None:
    num_q, cells = 7, 5000
    ptab, pool, poolf, iscal = _empty_records(num_q, cells)
    rng = np.random.default_rng(3)
    written: dict[tuple[int, int], float] = {}
    for c, q in zip(rng.integers(cells, size=300), rng.integers(num_q, size=300)):
        r = core.rec_touch(ptab, iscal, int(c), int(q))
        assert r == core.rec_find(ptab, int(c), int(q))
        poolf[r] = float(c) + q / 10
        pool[r + 1] = core.with_parent(pool[r + 1], 1000 + int(c), 5)
        written[(int(c), int(q))] = float(c) + q / 10
    used = {(q, c >> core.PAGE_BITS) for c, q in written}
    assert iscal[core.I_PAGES] == len(used)  # one slot per touched (state, block), nothing else
    assert sorted(ptab[ptab >= 0].tolist()) == list(range(len(used)))
    qb = core.q_bits(num_q)
    assert (1 << qb) >= num_q > (1 << (qb - 1))
    for (c, q), g in written.items():
        assert core.read_record(ptab, pool, poolf, (c << qb) | q) == (g, 1000 + c, 5)
    untouched = next((c, q) for c in range(cells) for q in range(num_q) if (c, q) not in written)
    assert core.read_record(ptab, pool, poolf, (untouched[0] << qb) | untouched[1])[2] == -1


def test_closed_bits_belong_to_their_iteration() -> None:
    parent = (1 << 34) - 3  # the largest product state the layout holds
    link = core.with_parent(0, parent, core.ACT_MAP + 1000)
    assert core.reached(link) and not core.reached(0)
    link = core.with_closed(link, 1 << 2, 3)
    assert core.is_closed(link, 2, 3) and not core.is_closed(link, 0, 3) and not core.is_closed(link, 2, 4)
    link = core.with_closed(link, core.ALL_LEVELS, 4)  # a new iteration drops the old bits
    assert all(core.is_closed(link, level, 4) for level in range(5)) and not core.is_closed(link, 2, 3)
    assert core.link_parent(link) == parent and core.link_action(link) == core.ACT_MAP + 1000  # untouched
    link = core.with_parent(link, -1, 7)  # a new parent keeps the closed bits
    assert core.is_closed(link, 1, 4) and core.link_parent(link) == -1 and core.link_action(link) == 7
    assert link > 0 and core.retagged(link, 255) & 0x1F == 0 and core.has_tag(core.retagged(link, 255), 255)
    assert core.check_layout(1 << 24, 512, 10) is None  # 16M cells x 512 states
    assert "2^34" in core.check_layout(1 << 25, 512, 10)
    assert "composite" in core.check_layout(100, 4, 1 << 16)


def test_a_schedule_longer_than_the_iteration_tags_is_refused() -> None:
    problem = random_problem(3)
    with pytest.raises(PlanningError, match="iterations"):
        plan(problem, "A*", schedule=WeightSchedule((10.0, 20.0), decay=0.99))


@_FEW
@given(st.integers(0, 2**31 - 1), st.sampled_from(["A*", "NO-LLM", "ALL"]))
def test_a_one_page_pool_grows_to_the_same_optimum(seed: int, setup: str) -> None:
    problem = random_problem(seed)
    default = _plan_or_none(problem, setup)
    if default is None:
        return
    original = search_memory.new_state
    try:
        one_page = lambda domain, k, pages=1: original(domain, k, pages=1)  # noqa: E731
        search_memory.new_state = one_page  # type: ignore[assignment]
        small = plan(problem, setup)
    finally:
        search_memory.new_state = original  # type: ignore[assignment]
    assert small.cost_m == pytest.approx(_oracle(problem), abs=1e-9)
    assert small.cost_m == default.cost_m and small.expansions == default.expansions
    assert check_path(small.path, problem.grid, problem.labels, problem.automaton, problem.profile).valid


@_FEW
@given(st.integers(0, 2**31 - 1), st.sampled_from(["A*", "NO-LLM", "ALL", "ROOM"]))
def test_reusing_work_across_iterations_keeps_the_fresh_optimum(seed: int, setup: str) -> None:
    """The anytime schedule (g-values, INCONS and the frontier bound carried across iterations) ends at
    the optimum of a fresh single (1, 1) search, and each iteration's cost stays within its bound."""
    problem = random_problem(seed)
    anytime = _plan_or_none(problem, setup)
    if anytime is None or anytime.cost_m == 0:  # no path, or the start is accepting (one record)
        return
    fresh = plan(problem, setup, schedule=WeightSchedule((1.0, 1.0)))
    expected = _oracle(problem)
    assert anytime.cost_m == pytest.approx(expected, abs=1e-9)
    assert fresh.cost_m == pytest.approx(expected, abs=1e-9)
    assert [(it.w1, it.w2) for it in anytime.iterations] == [
        (10, 20), (5, 10), (2.5, 5), (1.25, 2.5), (1, 1.25), (1, 1)
    ]
    for it in anytime.iterations:
        assert it.cost_m <= it.bound * expected + 1e-9
    totals = [sum(it.expansions) for it in anytime.iterations]
    assert totals == sorted(totals)


def test_an_iteration_whose_bound_already_holds_costs_no_expansion() -> None:
    # Open room, goal straight ahead: the greedy first path is optimal, and the frontier bound at the
    # next iteration's start proves it, so every later iteration is recorded without an expansion.
    building = open_building(rows=5, cols=30)
    grid = open_grid(building)
    problem = PlanningProblem(building, grid, marks(grid.shape, {0: [(2, 25, 0)]}),
                              automaton("F p0", ("p0",)), (2, 0, 0))
    result = plan(problem, "A*")
    assert result.cost_m == pytest.approx(25 * 0.1, abs=1e-12)
    first = result.iterations[0].expansions
    assert all(it.expansions == first for it in result.iterations)


@_FEW
@given(st.integers(0, 2**31 - 1))
def test_lazy_h_values_equal_the_filled_rows(seed: int) -> None:
    problem = random_problem(seed, guidance="none")
    try:
        domain = problem.domain
    except PlanningError:
        return
    L = domain.klogic
    rows = L.h_ready.shape[0]
    ready = np.zeros(rows, dtype=np.uint8)
    hmap = np.zeros_like(L.hmap)
    evals = np.zeros(rows, dtype=np.int64)
    cells = np.random.default_rng(seed).integers(domain.graph.num_cells, size=40)
    for row in range(rows):
        lazy = [core.h_ltl(hmap, ready, L.h_dist, L.h_unit, L.h_ptr, L.h_label, L.h_add, evals, 10**9, row,
                           int(c))
                for c in cells]
        assert not ready[row]  # computed from the terms, the row untouched
        filled = [core.h_ltl(hmap, ready, L.h_dist, L.h_unit, L.h_ptr, L.h_label, L.h_add, evals, 0, row,
                             int(c))
                  for c in cells]
        assert ready[row]  # past the threshold the row is filled
        assert lazy == filled  # the same bits
        q = int(np.flatnonzero(L.q_row == row)[0])
        assert lazy == [domain.ltl.value(int(c), q) for c in cells]


@_FEW
@given(st.integers(0, 2**31 - 1))
def test_at_w1_one_the_anchor_is_the_plain_a_star(seed: int) -> None:
    """From w1 = 1 the anchor follows occupancy moves only: NO-LLM's single (1, 1) search is A*'s,
    expansion for expansion; with LLM guidance every w1 = 1 iteration runs the anchor alone."""
    problem = random_problem(seed)
    astar = _plan_or_none(problem, "A*", schedule=WeightSchedule((1.0, 1.0)))
    if astar is None or astar.cost_m == 0:
        return
    nollm = plan(problem, "NO-LLM", schedule=WeightSchedule((1.0, 1.0)))
    assert nollm.expansions == astar.expansions and nollm.cost_m == astar.cost_m
    everything = plan(problem, "ALL")
    weighted = [it for it in everything.iterations if it.w1 > 1]
    for it in everything.iterations:
        if it.w1 == 1 and weighted:  # no LLM queue expanded at (1, 1.25) or (1, 1)
            assert it.expansions[1:] == weighted[-1].expansions[1:]
    assert everything.cost_m == pytest.approx(astar.cost_m, abs=1e-9)


# Seeds where, before closed states became final at w1 = 1, a (1, 1) iteration after a (1, w2) one
# re-expanded states whose g had improved by float rounding only.
@pytest.mark.parametrize("seed", [19, 57, 91, 103, 116, 128, 129, 172, 180, 188, 215, 232])
def test_iterations_at_w1_one_are_one_a_star_search(seed: int) -> None:
    """(1, 4) -> (1, 2) -> (1, 1) expands exactly what a single (1, 1) search does: at w1 = 1 a closed
    state is final, so the later iterations only continue the first one."""
    problem = random_problem(seed)
    single = plan(problem, "A*", schedule=WeightSchedule((1.0, 1.0)))
    stepped = plan(problem, "A*", schedule=WeightSchedule((1.0, 4.0)))
    assert [(it.w1, it.w2) for it in stepped.iterations] == [(1, 4), (1, 2), (1, 1)]
    assert stepped.expansions == single.expansions
    assert stepped.cost_m == single.cost_m == pytest.approx(_oracle(problem), abs=1e-9)


def test_search_memory_is_sparse_in_automaton_states() -> None:
    """Four unordered goals near the start of a long hall: 16 automaton states x 60,000 cells dense
    would be 23 MB of records; the search touches a small corner of it."""
    building = open_building(rows=40, cols=1500)
    grid = open_grid(building)
    goals = {0: [(5, 8, 0)], 1: [(30, 10, 0)], 2: [(20, 30, 0)], 3: [(2, 40, 0)]}
    problem = PlanningProblem(building, grid, marks(grid.shape, goals),
                              automaton("F p0 & F p1 & F p2 & F p3", ("p0", "p1", "p2", "p3")), (20, 0, 0))
    result = plan(problem, "A*")
    assert math.isfinite(result.cost_m) and result.cost_m == pytest.approx(_oracle(problem), abs=1e-9)
    dense = problem.domain.graph.num_cells * problem.domain.num_states * core.REC * 8
    assert 0 < result.search_bytes < dense / 20


def _run_kernel(kernel, domain, state, q_level, q_htype, max_level: int):
    """Run ``kernel`` (improve_path's signature) to the end of the iteration, growing memory on demand."""
    while True:
        code, _ = kernel(domain.kgraph, domain.kactions, domain.kmaps, domain.klogic, state, q_level, q_htype,
                         max_level, 10**9, 16)
        if code != core.GROW:
            return code, state
        state = search_memory.reserve(state, 2 * int(state.hsize.max(initial=0)) + 16, free_pages=16)


@_FEW
@given(st.integers(0, 2**31 - 1))
def test_the_flat_anchor_loop_is_the_general_loop(seed: int) -> None:
    """anchor_path (the A* / w1 = 1 loop written out flat) leaves bit-identical search memory to the
    general multi_queue_path, iteration after iteration of the A* schedule (INCONS and closed-is-final
    included)."""
    problem = random_problem(seed)
    try:
        domain = problem.domain
    except PlanningError:
        return
    if domain.accepting[domain.q_start]:
        return
    q_level, q_htype = np.zeros(1, dtype=np.int32), np.zeros(1, dtype=np.int32)
    states = [search_memory.new_state(domain, 1, pages=1), search_memory.new_state(domain, 1, pages=1)]
    flat = lambda G, A, M, L, S, ql, qh, ml, budget, succ: core.anchor_path(G, L, S, budget, succ)  # noqa: E731
    for started, (w1, w2) in enumerate([(10.0, 20.0), (2.5, 5.0), (1.0, 1.25), (1.0, 1.0)], start=1):
        codes = []
        for i, kernel in enumerate((flat, core.multi_queue_path)):
            room = int(states[i].hsize[0] + states[i].iscal[core.I_NINCONS]) + 16
            state = search_memory.reserve(states[i], room)
            core.start_iteration(domain.kgraph, domain.klogic, state, q_level, q_htype, w1, w2, started)
            code, states[i] = _run_kernel(kernel, domain, state, q_level, q_htype, 1)
            codes.append(code)
        assert codes[0] == codes[1]
        a, b = states
        used = int(a.iscal[core.I_PAGES]) * core.PAGE * core.REC
        assert np.array_equal(a.ptab, b.ptab) and np.array_equal(a.pool[:used], b.pool[:used])
        heap = int(a.hsize[0]) * core.HREC
        assert np.array_equal(a.hbuf[:heap], b.hbuf[:heap]) and a.hsize[0] == b.hsize[0]
        n = int(a.iscal[core.I_NINCONS])
        assert np.array_equal(a.incons[:n], b.incons[:n])
        assert np.array_equal(a.iscal, b.iscal) and np.array_equal(a.expansions, b.expansions)
        assert a.fscal[0] == b.fscal[0] or (math.isinf(a.fscal[0]) and math.isinf(b.fscal[0]))


def test_a_pool_the_system_will_not_map_falls_back_to_a_smaller_one(monkeypatch) -> None:
    """The default pool reserves a slot per (state, block); when the OS refuses that much address space
    the pool starts smaller (halving; the search grows it as test_a_one_page_pool... checks)."""
    page_words = core.PAGE * core.REC
    asked = []

    def picky(shape, dtype):
        asked.append(shape // page_words)
        if shape > 100 * page_words:
            raise MemoryError
        return np.zeros(shape, dtype)

    monkeypatch.setattr(search_memory, "sparse_zeros", picky)
    assert search_memory.pool_buffer(1000).shape[0] == 62 * page_words
    assert asked == [1000, 500, 250, 125, 62]
    asked.clear()
    refuse = lambda shape, dtype: (_ for _ in ()).throw(MemoryError)  # noqa: E731
    monkeypatch.setattr(search_memory, "sparse_zeros", refuse)
    with pytest.raises(MemoryError):
        search_memory.pool_buffer(1000)


def test_the_parent_chain_is_the_walk_of_the_records_from_the_goal() -> None:
    num_q, cells = 3, 3000
    ptab, pool, poolf, iscal = _empty_records(num_q, cells)
    qb = core.q_bits(num_q)
    rng = np.random.default_rng(5)
    picked = zip(rng.permutation(cells)[:200], rng.integers(num_q, size=200))
    walk = [(int(c) << qb) | int(q) for c, q in picked]
    for k, s in enumerate(walk):  # the start has no parent; each later state's parent is the one before
        r = core.rec_touch(ptab, iscal, s >> qb, s & ((1 << qb) - 1))
        poolf[r] = float(k)
        if k:
            pool[r + 1] = core.with_parent(pool[r + 1], walk[k - 1], 7 + k % 3)
    states, actions = core.parent_chain(ptab, pool, poolf, walk[-1], len(walk) + 1)
    expected = [-1] + [7 + k % 3 for k in range(1, len(walk))]
    assert states.tolist() == walk and actions.tolist() == expected
    states, actions = core.parent_chain(ptab, pool, poolf, walk[-1], 50)  # more states than allowed
    assert len(states) == len(actions) == 0
