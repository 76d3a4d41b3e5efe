"""Plans over a run's carried parts (masked cell graph, repaired fields) after random scene changes are
exactly optimal: their cost equals the independent oracle's on the changed building."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.execution.parts import RunParts
from sgplan.execution.world import SceneState
from sgplan.logic import parse_infix
from sgplan.logic.ltlf import ltlf_to_dfa
from sgplan.planning import PlanningProblem
from sgplan.planning.amra import plan
from sgplan.planning.cells import build_cell_graph
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import Proposition
from tests.execution.buildings import house
from tests.execution.test_fields import label_raster
from tests.execution.test_world import random_changes
from tests.planning.oracle import optimal_cost

PROPS = [Proposition("reach", 10), Proposition("enter", 9), Proposition("enter", 6)]
"""The sink, the office, the bedroom of :func:`tests.execution.buildings.house`."""
FORMULAS = ["F p0 & F p1", "F(p0 & F p1) & G !p2", "F p2 & F p0"]


def _free_cell(rng, grid):
    floors, rows, cols = np.nonzero(grid.traversable)
    k = int(rng.integers(len(rows)))
    return int(rows[k]), int(cols[k]), int(floors[k])


@settings(max_examples=25)
@given(st.integers(0, 2**32 - 1), st.sampled_from(FORMULAS), st.sampled_from(["A*", "NO-LLM"]))
def test_plans_over_carried_parts_are_optimal_after_changes(seed, formula, setup):
    rng = np.random.default_rng(seed)
    automaton = ltlf_to_dfa(parse_infix(formula), aps=("p0", "p1", "p2"))
    state = SceneState.of(house())
    grid = build_occupancy_grid(state.building, 0.0)
    labels = label_raster(state.building, PROPS, 0.3)
    parts = RunParts(grid, labels, state.building)
    for step in itertools.chain([None], random_changes(rng, state, grid, 4)):
        if step is not None:
            state, _, grid, change = step
            new_labels = label_raster(state.building, PROPS, 0.3)
            relabelled = np.flatnonzero(new_labels != labels)
            labels = new_labels
            parts.advance(grid, change, labels, relabelled, state.building)
        start = _free_cell(rng, grid)
        expected = optimal_cost(grid, labels, automaton, start)
        problem = PlanningProblem(state.building, grid, labels, automaton, start, reach_radius_m=0.3,
                                  shared=parts)
        try:
            found = plan(problem, setup).cost_m
        except PlanningError as error:
            assert error.status in ("infeasible", "invalid-start"), error
            found = math.inf
        assert found == pytest.approx(expected, abs=1e-6)
        if parts.component.cells is not None:
            _check_component(parts, grid, labels, start)


def _check_component(parts, grid, labels, start):
    """The run's component is the start's over the cells a live state may enter (the graph without the
    fatal labels' cells: a room the mission forbids), as a flood over a fresh graph of them finds it."""
    fatal = np.flatnonzero(parts.fatal.flags)
    allowed = replace(grid, traversable=grid.traversable & ~np.isin(labels, fatal))
    row, col, floor = start
    if not allowed.traversable[floor, row, col]:
        return
    fresh = build_cell_graph(allowed)
    expected = np.zeros(grid.traversable.size, dtype=bool)
    expected[fresh.positions()[fresh.reachable(fresh.cell_id(row, col, floor))]] = True
    kept = np.zeros(grid.traversable.size, dtype=bool)
    kept[parts.graph.positions()[parts.component.cells]] = True
    assert np.array_equal(kept, expected)
