"""Regression on the shipped Gibson missions: the authors-profile optima of reference-algorithm.md §11
(the "stay" column), the cases where the default ltlf profile answers differently, and the failures.
The full table runs in benchmarks/planning_gibson.py --all."""

from __future__ import annotations

import pytest

from sgplan.errors import PlanningError
from sgplan.planning import plan
from sgplan.planning.checker import check_path
from sgplan.planning.domain import domain_of

from .gibson_cases import STAY_COSTS, load_case

pytestmark = pytest.mark.gibson


def _plan(root, scene, mission, start, setup, profile="authors"):
    problem = load_case(root, scene, mission, start, profile)
    result = plan(problem, setup, prebuild_actions=False)
    check = check_path(result.path, problem.grid, problem.labels, problem.automaton, profile)
    assert check.valid, check.problems
    assert check.cost_m == pytest.approx(result.cost_m, abs=1e-9)
    return result


@pytest.mark.parametrize(
    "scene, mission, start, setup",
    [
        ("Benevolence", 1, 0, "ALL"),
        ("Benevolence", 2, 2, "ALL"),
        ("Allensville", 4, 3, "NO-LLM"),
        ("Allensville", 5, 0, "A*"),
        ("Allensville", 5, 3, "OBJ"),
    ],
)
def test_authors_profile_matches_reference_optimum(gibson_root, scene, mission, start, setup) -> None:
    result = _plan(gibson_root, scene, mission, start, setup)
    assert result.status == "optimal"
    assert round(result.cost_m, 4) == pytest.approx(STAY_COSTS[(scene, mission)][start], abs=1e-9)


def test_collierville_runs_across_floors(gibson_root) -> None:
    result = _plan(gibson_root, "Collierville", 1, 0, "ALL")
    assert result.status == "optimal" and len(set(result.path[:, 2].tolist())) > 1


@pytest.mark.parametrize(
    "scene, start, clearance", [("Benevolence", 1, "0.177 m"), ("Allensville", 2, "0.112 m")]
)
def test_start_in_collision(gibson_root, scene, start, clearance) -> None:
    with pytest.raises(PlanningError) as info:
        domain_of(load_case(gibson_root, scene, 1, start))
    assert info.value.status == "invalid-start" and clearance in str(info.value)


def test_unreachable_room_is_infeasible(gibson_root) -> None:
    # Benevolence mission 3 from start 3 needs the utility room (uuid 20), erased by the 0.2 m inflation;
    # h_LTL, built over the start's component only, is infinite at the start.
    with pytest.raises(PlanningError) as info:
        plan(load_case(gibson_root, "Benevolence", 3, 3), "NO-LLM", prebuild_actions=False)
    assert info.value.status == "infeasible" and "enter(room_20)" in str(info.value)


def test_ltlf_rejecting_missing_edges_changes_the_optimum(gibson_root) -> None:
    # Allensville 4's automaton lacks edges that the authors' "stay" rule turns into self-loops.
    assert STAY_COSTS[("Allensville", 4)][1] == 6.1445
    assert round(_plan(gibson_root, "Allensville", 4, 1, "NO-LLM", "ltlf").cost_m, 4) == 6.5667


@pytest.mark.parametrize(
    "scene, mission, start, named",
    [("Allensville", 3, 1, "no proposition"), ("Collierville", 1, 0, "p3 (enter(room_8))")],
)
def test_ltlf_reads_the_start_label(gibson_root, scene, mission, start, named) -> None:
    # Allensville 3 constrains the first letter; Collierville 1 forbids the corridor the start lies in.
    with pytest.raises(PlanningError) as info:
        domain_of(load_case(gibson_root, scene, mission, start, "ltlf"))
    assert info.value.status == "invalid-start" and named in str(info.value)
