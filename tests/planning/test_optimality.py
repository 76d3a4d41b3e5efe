"""Optimality: AMRA*'s last iteration equals an independent exact product-graph Dijkstra.

Random small buildings x random LTLf formulas x random starts x every setup, with random (adversarial)
LLM guidance, under both semantics profiles and both reach models (the labels and the object level's
regions). Every returned path must also pass the independent checker.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.logic import Always, And, Atom, Eventually, Formula, Next, Not, Or, Until, ltlf_to_dfa
from sgplan.planning.amra import plan
from sgplan.planning.checker import check_path
from sgplan.planning.problem import PlanningProblem
from sgplan.planning.setups import SETUPS
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import Proposition, label_raster
from tests.scene.small_buildings import random_small_building

from .oracle import optimal_cost

NUM_PROPS = 4


def formulas(depth: int = 3) -> st.SearchStrategy[Formula]:
    """Formulas over atoms a0..a3 (mapped to random rooms/objects per example)."""
    atom = st.integers(0, NUM_PROPS - 1).map(lambda i: Atom(f"a{i}"))
    return st.recursive(
        atom,
        lambda sub: st.one_of(
            sub.map(Not), sub.map(Eventually), sub.map(Always), sub.map(Next),
            st.tuples(sub, sub).map(lambda p: And((p[0], p[1]))),
            st.tuples(sub, sub).map(lambda p: Or((p[0], p[1]))),
            st.tuples(sub, sub).map(lambda p: Until(p[0], p[1])),
        ),
        max_leaves=5,
    )


def mission_style() -> st.SearchStrategy[Formula]:
    """Formulas shaped like real missions: ordered visits plus avoidance."""
    atom = st.integers(0, NUM_PROPS - 1).map(lambda i: Atom(f"a{i}"))
    visit = atom.map(Eventually)
    ordered = st.tuples(atom, atom).map(lambda p: Eventually(And((p[0], Eventually(p[1])))))
    chain = st.tuples(atom, atom, atom).map(
        lambda p: Eventually(And((p[0], Eventually(And((p[1], Eventually(p[2])))))))
    )
    avoid = atom.map(lambda a: Always(Not(a)))
    avoid_until = st.tuples(atom, atom).map(lambda p: Until(Not(p[0]), p[1]))
    part = st.one_of(visit, ordered, chain, avoid, avoid_until)
    return st.lists(part, min_size=1, max_size=4).map(lambda ps: ps[0] if len(ps) == 1 else And(tuple(ps)))


def _instance(seed: int, formula: Formula, profile: str, reach_model: str):
    rng = np.random.default_rng(seed)
    building = random_small_building(rng)
    rooms = [r for r in building.rooms()]
    objects = list(building.objects())
    pool = [Proposition("enter", r.uuid) for r in rooms] + [Proposition("reach", o.uuid) for o in objects]
    props = [pool[int(i)] for i in rng.integers(len(pool), size=NUM_PROPS)]
    aps = tuple(f"a{i}" for i in range(NUM_PROPS))
    automaton = ltlf_to_dfa(formula, aps=aps)
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    labels = label_raster(building, props, building.reach_radius_m, reach_model)
    free = np.argwhere(grid.traversable)
    floor, row, col = (int(v) for v in free[int(rng.integers(len(free)))])
    guidance = _adversarial_guidance(rng, building, automaton.num_states)
    problem = PlanningProblem(building=building, grid=grid, labels=labels, automaton=automaton,
                              start=(row, col, floor), profile=profile, guidance=guidance,
                              reach_radius_m=building.reach_radius_m, reach_model=reach_model)
    return problem


def _adversarial_guidance(rng: np.random.Generator, building, num_states: int) -> dict:
    """Random calls, valid or not, including garbage, empty lists and missing entries."""
    rooms = [r.uuid for r in building.rooms()]
    ids = rooms + [o.uuid for o in building.objects()] + [999]
    guidance: dict = {}
    for room in rooms:
        states = {}
        for q in range(num_states):
            if rng.random() < 0.2:
                continue
            calls = []
            for _ in range(int(rng.integers(0, 5))):
                kind = ("move", "reach", "fly")[int(rng.integers(3))]
                a, b = (int(ids[int(i)]) for i in rng.integers(len(ids), size=2))
                calls.append(f"{kind}({a}, {b})" if rng.random() > 0.1 else "garbage")
            states[q] = calls
        guidance[room] = states
    return guidance


def _check_all_setups(problem: PlanningProblem) -> None:
    expected = optimal_cost(problem.grid, problem.labels, problem.automaton,
                            (problem.start[0], problem.start[1], problem.start[2]), problem.profile)
    for setup in SETUPS:
        try:
            result = plan(problem, setup)
        except PlanningError as error:
            assert math.isinf(expected), f"{setup}: planner says {error.status} ({error}), oracle {expected}"
            assert error.status in ("infeasible", "invalid-start")
            continue
        assert math.isfinite(expected), f"{setup}: planner found cost {result.cost_m}, oracle says infeasible"
        assert result.status == "optimal"
        assert result.cost_m == pytest.approx(expected, rel=1e-9, abs=1e-9), setup
        costs = [it.cost_m for it in result.iterations]
        assert all(a >= b - 1e-9 for a, b in itertools.pairwise(costs)), f"{setup}: costs rose {costs}"
        for it in result.iterations:
            assert it.cost_m <= it.bound * expected + 1e-9, f"{setup}: bound broken {it}"
        check = check_path(result.path, problem.grid, problem.labels, problem.automaton, problem.profile)
        assert check.valid, (setup, check.problems)
        assert check.cost_m == pytest.approx(result.cost_m, rel=1e-9, abs=1e-9)


_SETTINGS = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


_MODELS = st.sampled_from(["box", "visible"])


@_SETTINGS
@given(seed=st.integers(0, 2**32 - 1), formula=formulas(), profile=st.sampled_from(["ltlf", "authors"]),
       reach_model=_MODELS)
def test_random_formulas_are_solved_optimally_by_every_setup(
    seed: int, formula: Formula, profile: str, reach_model: str
) -> None:
    _check_all_setups(_instance(seed, formula, profile, reach_model))


@_SETTINGS
@given(seed=st.integers(0, 2**32 - 1), formula=mission_style(), reach_model=_MODELS)
def test_mission_shaped_formulas_are_solved_optimally_by_every_setup(
    seed: int, formula: Formula, reach_model: str
) -> None:
    _check_all_setups(_instance(seed, formula, "ltlf", reach_model))
