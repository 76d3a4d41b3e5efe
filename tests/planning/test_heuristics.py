"""h_LTL (values, admissibility, consistency on every move, dominance over the paper's region-level bound)
and h_LLM (cost model, robustness)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.logic import And, Atom, Eventually
from sgplan.planning import PlanningProblem
from sgplan.planning._search import h_llm
from sgplan.planning.domain import domain_of
from sgplan.planning.llm_heuristic import build_llm_heuristic
from sgplan.planning.ltl_heuristic import (
    UNIT_M,
    build_ltl_heuristic,
    fill_row,
    reachable_states,
    unit_costs,
    unit_field,
)

from .instances import RES, automaton, marks, open_building, open_grid, random_problem
from .oracle import optimal_cost
from .test_domain import _edges
from .test_optimality import _instance


def _open_problem(formula: str, cells: dict, start=(2, 0, 0)) -> PlanningProblem:
    building = open_building()
    grid = open_grid(building)
    aps = tuple(f"p{i}" for i in range(max(cells) + 1))
    return PlanningProblem(building, grid, marks(grid.shape, cells), automaton(formula, aps), start)


def test_ltl_value_is_exact_on_open_floor() -> None:
    # On an obstacle-free floor the geodesic label distances make h exact for a sequence of two goals: the
    # optimum with every move's cost rounded down to whole units of the fields, within a unit a move of it.
    problem = _open_problem("F(p1 & F p0)", {0: [(2, 10, 0)], 1: [(0, 5, 0)]})
    domain = domain_of(problem)
    ltl = domain.ltl
    h = ltl.value(domain.start_cell, domain.q_start)
    assert ltl.unit_m == UNIT_M
    straight, diagonal = math.floor(RES / UNIT_M), math.floor(math.hypot(RES, RES) / UNIT_M)
    assert h == 2 * (3 * straight + 2 * diagonal) * UNIT_M
    assert h == pytest.approx(2 * (3 * RES + 2 * math.hypot(RES, RES)), abs=10 * UNIT_M)


def test_distance_fields_are_whole_units_of_the_rounded_down_move_costs() -> None:
    # A field is the exact shortest path over the moves' costs rounded down to whole units (so h stays
    # consistent in the real costs), UNREACHED where its region cannot be reached, and a coarser unit is
    # taken when a distance would not fit in 32 bits.
    problem = _open_problem("F p0", {0: [(2, 10, 0)]})
    graph = domain_of(problem).graph
    target = np.array([graph.cell_id(2, 10, 0)])
    field = unit_field(graph, target, UNIT_M)
    assert field is not None and field.dtype == np.uint32 and field[target[0]] == 0
    step, stairs = unit_costs(graph, UNIT_M)
    assert (step == np.floor(graph.step_cost / UNIT_M)).all() and (step >= 1).all()
    assert (step * UNIT_M <= graph.step_cost).all() and stairs.shape == graph.stairs_cost.shape
    # Bellman's equations: |d(x) - d(y)| <= the rounded-down cost of every move, and a neighbour attains it.
    neighbours = graph.neighbours()
    for x in range(graph.num_cells):
        moves = [(int(field[y]), int(step[k])) for k, y in enumerate(neighbours[x]) if y >= 0]
        assert all(abs(int(field[x]) - there) <= cost for there, cost in moves)
        assert field[x] == 0 if x == target[0] else field[x] == min(there + cost for there, cost in moves)
    too_fine = unit_field(graph, target, 2.0**-40)  # 2^32 units of 2^-40 m: 3.9 mm
    assert isinstance(too_fine, float)
    assert too_fine * 2.0**-40 == pytest.approx(field.max() * UNIT_M, rel=1e-5)


def test_a_distance_too_long_for_the_unit_takes_a_coarser_one(monkeypatch: pytest.MonkeyPatch) -> None:
    # With units of 2^-40 m a field overflows 32 bits past 3.9 mm: the heuristic takes the power of two
    # its longest distance needs, and h is still the rounded-down geodesic.
    from sgplan.planning import ltl_heuristic

    problem = _open_problem("F(p1 & F p0)", {0: [(2, 10, 0)], 1: [(0, 5, 0)]})
    domain = domain_of(problem)
    monkeypatch.setattr(ltl_heuristic, "UNIT_M", 2.0**-40)
    graph = domain.graph
    ltl = build_ltl_heuristic(graph, domain.cell_label, domain.trans, domain.accepting, domain.q_start,
                              graph.reachable(domain.start_cell), start_cell=domain.start_cell)
    assert 2.0**-40 < ltl.unit_m <= 2.0**-20 and np.log2(ltl.unit_m).is_integer()
    assert ltl.dist.max() < ltl_heuristic.UNREACHED
    exact = 2 * (3 * RES + 2 * math.hypot(RES, RES))
    assert exact - 10 * ltl.unit_m <= ltl.value(domain.start_cell, domain.q_start) <= exact


def _possible(domain) -> np.ndarray:
    """``(Q, L)`` bool: q can be the automaton state at a cell of compact label l during a search -- q is
    ``T(p, l)`` for a non-accepting state p reachable from the start state (plus the start itself, which
    callers add)."""
    trans = domain.trans
    expanded = reachable_states(trans, domain.q_start) & ~domain.accepting
    possible = np.zeros(trans.shape, dtype=bool)
    for label in range(trans.shape[1]):
        possible[trans[expanded, label], label] = True
    return possible


def _check_consistency(problem: PlanningProblem, rng: np.random.Generator, samples: int) -> int:
    """Check h(x) <= c(x, x') + h(x') on the anchor-level edges of sampled states that a search can meet;
    returns edges checked."""
    domain = domain_of(problem)
    domain.build_actions()
    graph = domain.graph
    possible = _possible(domain) & ~domain.accepting[:, None]
    checked = 0
    for cell in rng.integers(graph.num_cells, size=samples):
        states = np.flatnonzero(possible[:, domain.cell_label[cell]])
        if states.size == 0:
            continue
        q = int(rng.choice(states))
        h = domain.ltl.value(int(cell), q)
        if math.isinf(h):
            continue
        for end, nq, cost, _ in _edges(domain, int(cell), q):
            assert h <= cost + domain.ltl.value(end, nq) + 1e-9, (cell, q, end, nq, cost)
            checked += 1
    return checked


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**31 - 1), st.sampled_from(["ltlf", "authors"]))
def test_ltl_consistent_and_admissible_on_random_instances(seed: int, profile: str) -> None:
    problem = random_problem(seed, profile, guidance="none")
    try:
        domain = domain_of(problem)
    except PlanningError:
        return
    _check_consistency(problem, np.random.default_rng(seed), 40)
    row, col, floor = problem.start
    optimum = optimal_cost(problem.grid, problem.labels, problem.automaton, (row, col, floor), profile)
    assert domain.ltl.value(domain.start_cell, domain.q_start) <= optimum + 1e-9


@pytest.mark.gibson
def test_ltl_consistent_on_benevolence(gibson_root) -> None:
    from .gibson_cases import load_case

    problem = load_case(gibson_root, "Benevolence", 4, 0)
    rng = np.random.default_rng(0)
    assert _check_consistency(problem, rng, 400) > 1000
    # The stairs portals, where the authors' own heuristic violated consistency by millimetres.
    graph = domain_of(problem).graph
    possible = _possible(domain_of(problem)) & ~domain_of(problem).accepting[:, None]
    for portal in graph.stairs_from:
        for q in np.flatnonzero(possible[:, domain_of(problem).cell_label[portal]]):
            h = domain_of(problem).ltl.value(int(portal), int(q))
            for end, nq, cost, _ in _edges(domain_of(problem), int(portal), int(q)):
                assert h <= cost + domain_of(problem).ltl.value(end, nq) + 1e-9


def test_llm_cost_model_and_robustness() -> None:
    problem = _open_problem("F p0", {0: [(2, 10, 0)]})
    building = problem.building
    room = building.room(uuid=10)
    guidance = {
        10: {
            0: ["move(10, 10)", "reach(10, 999)", "bogus", 7, "move(10, 10)"],  # 2 usable, 3 skipped
            1: [],
            "x": ["move(10, 10)"],  # bad state key: skipped entry
        },
        "nope": {0: []},  # unknown room: skipped entry
        10.5: "not a mapping",
    }
    llm = build_llm_heuristic(guidance, building, [10], num_states=2)
    assert llm.stats.calls_used == 2 and llm.stats.calls_skipped == 3 and llm.stats.entries_skipped == 3
    assert llm.has_target[0, 0] and not llm.has_target[0, 1]
    assert llm.leg_sum[0, 0] == 0.0  # move(10, 10) has zero length
    assert np.allclose(llm.target[0, 0], room.location_m)
    assert build_llm_heuristic(["not", "a", "dict"], building, [10], 2).stats.entries_skipped == 1


def test_llm_value_online() -> None:
    problem = _open_problem("F p0", {0: [(2, 10, 0)]})
    problem.guidance = {10: {0: ["move(10, 10)"]}}
    domain = domain_of(problem)
    cell = domain.start_cell
    expected = float(np.linalg.norm(domain.graph.cell_xyz[cell] - problem.building.room(uuid=10).location_m))
    assert h_llm(domain.kgraph, domain.klogic, cell, 0) == pytest.approx(expected)
    assert h_llm(domain.kgraph, domain.klogic, cell, 1) == 0.0  # accepting
    # Bit for bit the value from the per-cell centres, at every cell of the room.
    target, xyz = domain.klogic.llm_target[0, 0], domain.graph.cell_xyz
    for c in np.flatnonzero(domain.kgraph.cell_room == 0):
        d = xyz[c] - target
        assert h_llm(domain.kgraph, domain.klogic, c, 0) == domain.klogic.llm_sum[0, 0] + math.sqrt(
            d[0] * d[0] + d[1] * d[1] + d[2] * d[2])


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_ltl_rows_filled_on_demand_match_the_eager_minimum(seed: int) -> None:
    """A search fills only the rows of states it meets (the others are computed per cell); every row,
    filled by the search, computed per cell or filled afterwards, equals the eager numpy minimum over its
    terms, to the bit (and is +inf exactly where no term is finite)."""
    from sgplan.planning import plan

    problem = random_problem(seed, guidance="none")
    try:
        ltl = domain_of(problem).ltl
        plan(problem, "A*")
    except PlanningError:
        return
    eager_rows = _eager_rows(ltl)
    for q in np.flatnonzero(ltl.q_row >= 0):
        row = int(ltl.q_row[q])
        eager = eager_rows[q].tolist()
        assert [ltl.value(c, int(q)) for c in range(len(eager))] == eager
        fill_row(ltl.hmap, ltl.ready, ltl.dist, ltl.unit_m, ltl.term_ptr, ltl.term_label, ltl.term_add, row)
        assert ltl.ready[row] == 1 and ltl.hmap[row].tolist() == eager


def _eager_rows(ltl) -> np.ndarray:
    """``(Q, N)`` h_LTL of every state at every cell, in numpy from the terms (0 accepting, inf without a
    row): per term, phi = max(0, max over fields f of lo_f - d_f, d_f - hi_f), plus the cost to go, in units
    of the fields, times the unit."""
    dist = ltl.fields_m() / ltl.unit_m  # (F, N) units
    num_fields = dist.shape[0]
    rows = np.full((ltl.q_row.shape[0], dist.shape[1]), np.inf)
    rows[ltl.accepting] = 0.0
    for q in np.flatnonzero(ltl.q_row >= 0):
        row = int(ltl.q_row[q])
        groups = ltl.term_label[ltl.term_ptr[row] : ltl.term_ptr[row + 1]]
        for t in (t for _, first, end in groups for t in range(first, end)):
            lo = ltl.term_add[t, 1 : 1 + num_fields, None]
            hi = ltl.term_add[t, 1 + num_fields :, None]
            phi = np.maximum(np.maximum(lo - dist, dist - hi).max(axis=0), 0.0)
            rows[q] = np.minimum(rows[q], phi + ltl.term_add[t, 0])
    return rows * ltl.unit_m


def _paper_rows(ltl, trans: np.ndarray) -> np.ndarray:
    """``(Q, N)`` the paper's h_LTL over the same label regions (one region per label, region-to-region
    costs ``c(l, l') = min over the region of l of d_l'``), by value iteration: the bound the pieces
    tighten."""
    labels = ltl.leaving_labels
    dist = ltl.fields_m()  # (F, N)
    regions = [dist[i] == 0.0 for i in range(len(labels))]
    cost = np.array([[dist[j][regions[i]].min() for j in range(len(labels))] for i in range(len(labels))])
    num_states = trans.shape[0]
    to_go = np.where(ltl.accepting[None, :], 0.0, np.inf) * np.ones((len(labels), 1))
    changed = True
    while changed:
        changed = False
        for q in np.flatnonzero(~ltl.accepting):
            for j, label in enumerate(labels):
                nq = trans[q, label]
                if nq == q:
                    continue
                better = cost[:, j] + to_go[j, nq]
                if (better < to_go[:, q]).any():
                    to_go[:, q] = np.minimum(to_go[:, q], better)
                    changed = True
    rows = np.full((num_states, dist.shape[1]), np.inf)
    rows[ltl.accepting] = 0.0
    for q in np.flatnonzero(~ltl.accepting):
        for j, label in enumerate(labels):
            nq = trans[q, label]
            if nq != q:
                rows[q] = np.minimum(rows[q], dist[j] + to_go[j, nq])
    return rows


def _every_move(graph):
    """``(src, dst, cost)`` arrays of every move of the cell graph (steps and stairs)."""
    src = np.repeat(np.arange(graph.num_cells), 8)
    dst = graph.neighbours().ravel().astype(np.int64)
    cost = np.tile(graph.step_cost, graph.num_cells)
    keep = dst >= 0
    return (np.concatenate([src[keep], graph.stairs_from]), np.concatenate([dst[keep], graph.stairs_to]),
            np.concatenate([cost[keep], graph.stairs_cost]))


def test_ltl_value_sees_through_a_wide_region() -> None:
    # A corridor: p0 covers columns 3..12, p1 is column 16, the start column 0; the mission visits p0
    # then p1. The paper's bound lets the robot enter p0 at column 3 and leave it from column 12 (3 + 4
    # cells); the pieces know that who enters at column 3 is 13 columns from p1: exact.
    building = open_building(rows=1, cols=18)
    problem = PlanningProblem(building, open_grid(building),
                              marks((1, 1, 18), {0: [(0, c, 0) for c in range(3, 13)], 1: [(0, 16, 0)]}),
                              automaton("F(p0 & F p1)", ("p0", "p1")), (0, 0, 0))
    domain = domain_of(problem)
    assert domain.ltl.value(domain.start_cell, domain.q_start) == pytest.approx(16 * RES, abs=16 * UNIT_M)
    paper = _paper_rows(domain.ltl, domain.trans)[domain.q_start, domain.start_cell]
    assert paper == pytest.approx(7 * RES, abs=7 * UNIT_M)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**31 - 1), st.sampled_from(["ltlf", "authors"]), st.sampled_from([0.2, 0.6, 1.5]),
       st.sampled_from([1, 3, 24]))
def test_ltl_consistent_on_every_move_and_above_the_paper_bound(
    seed: int, profile: str, piece_m: float, max_pieces: int
) -> None:
    """Whatever the pieces (one cell each, squares of 2-6 cells, or merged down to 1-3 per label), on
    every move out of every product state a search can meet, h(x, q) <= cost + h(x', q') (exhaustively,
    with the numpy twin of the terms, which must match value()); h = 0 at acceptance; h(start) <= the
    oracle's optimum; and h >= the paper's bound everywhere."""
    problem = random_problem(seed, profile, guidance="none")
    try:
        domain = domain_of(problem)
    except PlanningError:
        return
    graph = domain.graph
    ltl = build_ltl_heuristic(graph, domain.cell_label, domain.trans, domain.accepting, domain.q_start,
                              graph.reachable(domain.start_cell), start_cell=domain.start_cell,
                              piece_m=piece_m, max_pieces=max_pieces)
    rows = _eager_rows(ltl)
    cells = np.random.default_rng(seed).integers(graph.num_cells, size=20)
    for q in range(domain.num_states):
        assert [ltl.value(int(c), q) for c in cells] == rows[q, cells].tolist()
    assert (rows[domain.accepting] == 0.0).all()
    src, dst, cost = _every_move(graph)
    possible = _possible(domain)[:, domain.cell_label]  # (Q, N)
    possible[domain.q_start, domain.start_cell] = True
    for q in np.flatnonzero(~domain.accepting):
        at = possible[q, src] & np.isfinite(rows[q, src])
        nq = domain.trans[q, domain.cell_label[dst[at]]]
        slack = cost[at] + rows[nq, dst[at]] - rows[q, src[at]]
        assert slack.min(initial=0.0) >= -1e-9, (q, src[at][np.argmin(slack)], dst[at][np.argmin(slack)])
    paper = _paper_rows(ltl, domain.trans)
    assert (rows >= paper - 1e-9).all()
    row, col, floor = problem.start
    optimum = optimal_cost(problem.grid, problem.labels, problem.automaton, (row, col, floor), profile)
    assert rows[domain.q_start, domain.start_cell] <= optimum + 1e-9


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**31 - 1), st.sampled_from([0.2, 1.5]), st.sampled_from([1, 4, 32]),
       st.sampled_from(["A*", "NO-LLM"]))
def test_unordered_goals_solved_optimally_with_any_pieces(
    seed: int, piece_m: float, max_pieces: int, setup: str
) -> None:
    """Visit 3-4 places in any order (the case the pieces are for): whatever the pieces, the search with
    this h_LTL as its anchor heuristic returns the oracle's optimum."""
    from sgplan.planning import plan

    goals = 3 + seed % 2
    problem = _instance(seed, And(tuple(Eventually(Atom(f"a{i}")) for i in range(goals))), "ltlf", "visible")
    problem.guidance = None
    row, col, floor = problem.start
    expected = optimal_cost(problem.grid, problem.labels, problem.automaton, (row, col, floor), "ltlf")
    try:
        domain = domain_of(problem)
    except PlanningError:
        assert math.isinf(expected)
        return
    graph = domain.graph
    ltl = build_ltl_heuristic(graph, domain.cell_label, domain.trans, domain.accepting, domain.q_start,
                              graph.reachable(domain.start_cell), start_cell=domain.start_cell,
                              piece_m=piece_m, max_pieces=max_pieces)
    domain.ltl = ltl
    domain.klogic = domain.klogic._replace(hmap=ltl.hmap, q_row=ltl.q_row, h_ready=ltl.ready, h_dist=ltl.dist,
                                           h_unit=ltl.unit_m, h_ptr=ltl.term_ptr, h_label=ltl.term_label,
                                           h_add=ltl.term_add)
    result = plan(problem, setup)
    assert result.cost_m == pytest.approx(expected, rel=1e-9, abs=1e-9)
    assert ltl.value(domain.start_cell, domain.q_start) <= expected + 1e-9
