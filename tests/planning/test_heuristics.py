"""h_LTL (values, admissibility, consistency on sampled edges) and h_LLM (cost model, robustness)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.planning import PlanningProblem
from sgplan.planning._search import h_llm
from sgplan.planning.llm_heuristic import build_llm_heuristic
from sgplan.planning.ltl_heuristic import reachable_states

from .instances import RES, automaton, marks, open_building, open_grid, random_problem
from .oracle import optimal_cost
from .test_domain import _edges


def _open_problem(formula: str, cells: dict, start=(2, 0, 0)) -> PlanningProblem:
    building = open_building()
    grid = open_grid(building)
    aps = tuple(f"p{i}" for i in range(max(cells) + 1))
    return PlanningProblem(building, grid, marks(grid.shape, cells), automaton(formula, aps), start)


def test_ltl_value_is_exact_on_open_floor() -> None:
    # On an obstacle-free floor the geodesic label distances make h exact for a sequence of two goals.
    problem = _open_problem("F(p1 & F p0)", {0: [(2, 10, 0)], 1: [(0, 5, 0)]})
    domain = problem.domain
    h = domain.ltl.value(domain.start_cell, domain.q_start)
    assert h == pytest.approx(2 * (3 * RES + 2 * math.hypot(RES, RES)), abs=1e-12)


def _check_consistency(problem: PlanningProblem, rng: np.random.Generator, samples: int) -> int:
    """Check h(x) <= c(x, x') + h(x') on the anchor-level edges of sampled states; returns edges checked."""
    domain = problem.domain
    domain.build_actions()
    graph = domain.graph
    states = np.flatnonzero(reachable_states(domain.trans, domain.q_start) & ~domain.accepting)
    checked = 0
    if states.size == 0:
        return checked
    for cell in rng.integers(graph.num_cells, size=samples):
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
        domain = problem.domain
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
    graph = problem.domain.graph
    for portal in graph.stairs_from:
        for q in np.flatnonzero(~problem.domain.accepting):
            h = problem.domain.ltl.value(int(portal), int(q))
            for end, nq, cost, _ in _edges(problem.domain, int(portal), int(q)):
                assert h <= cost + problem.domain.ltl.value(end, nq) + 1e-9


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
    domain = problem.domain
    cell = domain.start_cell
    expected = float(np.linalg.norm(domain.graph.cell_xyz[cell] - problem.building.room(uuid=10).location_m))
    assert h_llm(domain.kgraph, domain.klogic, cell, 0) == pytest.approx(expected)
    assert h_llm(domain.kgraph, domain.klogic, cell, 1) == 0.0  # accepting


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_ltl_rows_filled_on_demand_match_the_eager_minimum(seed: int) -> None:
    """A search fills only the rows of states it meets; every row, filled on demand, equals the eager
    numpy minimum over its terms (and is +inf exactly where no term is finite)."""
    from sgplan.planning import plan

    problem = random_problem(seed, guidance="none")
    try:
        ltl = problem.domain.ltl
        plan(problem, "A*")
    except PlanningError:
        return
    met = ltl.ready.copy()
    for row in range(ltl.ready.shape[0]):
        terms = range(ltl.term_ptr[row], ltl.term_ptr[row + 1])
        eager = np.min([ltl.dist[ltl.term_label[t]] + ltl.term_add[t] for t in terms], axis=0)
        q = int(np.flatnonzero(ltl.q_row == row)[0])
        assert [ltl.value(c, q) for c in range(eager.shape[0])] == eager.tolist()
    start_row = int(ltl.q_row[problem.domain.q_start])
    assert start_row < 0 or met[start_row] == 1  # the search read the start's row
    assert ltl.ready.all()
