"""AMRA*: known optimal costs on hand-made instances, setups, iteration records, budgets, determinism."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.planning import SETUPS, PlanningProblem, get_setup, plan
from sgplan.planning.checker import check_path
from sgplan.planning.domain import domain_of
from sgplan.planning.setups import LLM, LTL
from sgplan.planning.termination import ExpansionLimit
from sgplan.scene.grid import StairsLink

from .instances import RES, automaton, marks, open_building, open_grid, random_problem
from .oracle import optimal_cost


def _problem(formula: str, cells: dict, start=(2, 0, 0), floors: int = 1, stairs=(), **kw) -> PlanningProblem:
    building = open_building(floors)
    grid = open_grid(building, stairs)
    aps = tuple(f"p{i}" for i in range(max(cells) + 1))
    return PlanningProblem(building, grid, marks(grid.shape, cells), automaton(formula, aps), start, **kw)


def test_straight_line() -> None:
    result = plan(_problem("F p0", {0: [(2, 10, 0)]}), "NO-LLM")
    assert result.status == "optimal"
    assert result.cost_m == pytest.approx(10 * RES, abs=1e-12)
    assert result.path[0].tolist()[:3] == [2, 0, 0] and result.path[-1].tolist()[:3] == [2, 10, 0]


def test_two_goals_in_order_with_diagonals() -> None:
    # start (2,0) -> b (0,5) -> a (2,10): each leg 2 diagonal + 3 straight steps.
    result = plan(_problem("F(p1 & F p0)", {0: [(2, 10, 0)], 1: [(0, 5, 0)]}), "A*")
    assert result.cost_m == pytest.approx(2 * (3 * RES + 2 * math.hypot(RES, RES)), abs=1e-12)


def test_avoidance_detour() -> None:
    # A wall of "forbidden" cells on column 5 except row 0 forces a detour through (0, 5).
    forbidden = [(r, 5, 0) for r in range(1, 5)]
    result = plan(_problem("!p1 U p0", {0: [(4, 10, 0)], 1: forbidden}, start=(4, 0, 0)), "NO-LLM")
    legs = (4 * math.hypot(RES, RES) + 1 * RES) * 2  # (4,0) -> (0,4/5/6) -> (4,10)
    assert result.cost_m == pytest.approx(legs, abs=1e-12)
    assert not any(tuple(c[:3]) in {(r, 5, 0) for r in range(1, 5)} for c in result.path.tolist())


def test_stairs_cost_is_used() -> None:
    link = StairsLink(lower_floor=0, lower_cell=(2, 6), upper_cell=(2, 6), cost_m=4.0)
    problem = _problem("F p0", {0: [(2, 11, 1)]}, floors=2, stairs=(link,))
    for setup in ("A*", "NO-LLM"):
        result = plan(problem, setup)
        assert result.cost_m == pytest.approx(6 * RES + 4.0 + 5 * RES, abs=1e-12)
        assert check_path(result.path, problem.grid, problem.labels, problem.automaton).valid


def test_start_already_accepting() -> None:
    result = plan(_problem("F p0", {0: [(2, 0, 0)]}), "A*")
    assert result.cost_m == 0.0 and len(result.path) == 1


def test_authors_profile_does_not_read_start() -> None:
    # G !p0 & F p1 from a p0 cell: impossible under ltlf, fine under authors.
    cells = {0: [(2, 0, 0)], 1: [(2, 3, 0)]}
    with pytest.raises(PlanningError) as info:
        plan(_problem("G !p0 & F p1", cells), "A*")
    assert info.value.status == "invalid-start"
    assert plan(_problem("G !p0 & F p1", cells, profile="authors"), "A*").cost_m == pytest.approx(3 * RES)


def test_iteration_records_and_callback() -> None:
    problem = random_problem(7)
    seen = []
    result = plan(problem, "ALL", callback=seen.append)
    assert seen == result.iterations
    weights = [(r.w1, r.w2) for r in result.iterations]
    assert weights[0] == (10.0, 20.0) and weights[-1] == (1.0, 1.0)
    assert all(r.bound == r.w1 * r.w2 for r in result.iterations)
    costs = [r.cost_m for r in result.iterations]
    assert costs == sorted(costs, reverse=True)
    times = [r.time_s for r in result.iterations]
    assert times == sorted(times)
    assert len(result.iterations[-1].expansions) == len(result.queues) == 5
    assert result.iterations[-1].cost_m == pytest.approx(result.cost_m, abs=1e-9)


def test_expansion_budget_gives_timeout() -> None:
    problem = _problem("F(p0 & F p1)", {0: [(4, 11, 0)], 1: [(0, 0, 0)]}, start=(0, 11, 0))
    result = plan(problem, "NO-LLM", termination=ExpansionLimit(1))
    assert result.status == "timeout"
    assert result.expansions <= 1


def test_setups_by_name() -> None:
    assert get_setup("no_llm") is SETUPS["NO-LLM"] and get_setup("a_star") is SETUPS["A*"]
    # (level, LTL) queues are merged into the anchor: the anchor, then the LLM queues of the setup.
    assert SETUPS["ALL"].queues == ((0, LTL),) + tuple((level, LLM) for level in range(1, 5))
    assert SETUPS["NO-LLM"].queues == ((0, LTL),) and SETUPS["NO-LLM"].max_level == 4
    assert SETUPS["A*"].queues == ((0, LTL),) and SETUPS["A*"].max_level == 1
    assert [SETUPS[name].queues[1] for name in ("OCC", "OBJ", "ROOM", "FLR")] == [
        (lv, LLM) for lv in range(1, 5)
    ]
    with pytest.raises(PlanningError, match="unknown setup"):
        get_setup("FAST")
    with pytest.raises(PlanningError, match="needs LLM guidance"):
        plan(_problem("F p0", {0: [(2, 10, 0)]}), "ALL")


def test_deterministic() -> None:
    first = plan(random_problem(19), "ALL")
    second = plan(random_problem(19), "ALL")
    assert first.cost_m == second.cost_m
    assert np.array_equal(first.path, second.path)
    assert [r.expansions for r in first.iterations] == [r.expansions for r in second.iterations]


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**31 - 1), st.sampled_from(["ltlf", "authors"]))
def test_every_setup_is_optimal_on_random_instances(seed: int, profile: str) -> None:
    problem = random_problem(seed, profile)
    row, col, floor = problem.start
    expected = optimal_cost(problem.grid, problem.labels, problem.automaton, (row, col, floor), profile)
    for name in SETUPS:
        try:
            result = plan(problem, name)
        except PlanningError as error:
            assert error.status in ("infeasible", "invalid-start") and math.isinf(expected), (
                name,
                str(error),
            )
            continue
        assert result.cost_m == pytest.approx(expected, abs=1e-9), name
        check = check_path(result.path, problem.grid, problem.labels, problem.automaton, profile)
        assert check.valid, check.problems
        assert check.cost_m == pytest.approx(result.cost_m, abs=1e-9)


@pytest.mark.parametrize("seed", [7, 10])  # instances whose ALL search runs the w1 = 1 iterations
def test_released_maps_change_no_result(seed: int) -> None:
    """A plan that frees its maps' distances and runs once w1 = 1 finds the same path with the same
    expansions (its path's composite actions are replayed from the move codes kept); a later plan on the
    same problem rebuilds what it needs and stays optimal."""
    kept, released = random_problem(seed), random_problem(seed)
    row, col, floor = kept.start
    expected = optimal_cost(kept.grid, kept.labels, kept.automaton, (row, col, floor), "ltlf")
    for name in ("ALL", "NO-LLM", "A*", "OBJ"):
        mine, theirs = plan(released, name, release_maps=True), plan(kept, name)
        assert np.array_equal(mine.path, theirs.path), name
        assert [r.expansions for r in mine.iterations] == [r.expansions for r in theirs.iterations], name
        assert mine.cost_m == pytest.approx(expected, abs=1e-9)
        assert check_path(mine.path, released.grid, released.labels, released.automaton, "ltlf").valid
        assert mine.iterations[-1].w1 == 1.0  # so the maps were freed (A*: still, from NO-LLM)
        assert domain_of(released, 1).kmaps.dist.size == 0 and domain_of(released, 1).max_level == 1, name
    assert domain_of(kept).kmaps.dist.size > 0  # kept by default
