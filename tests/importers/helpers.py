"""Checks shared by the importer tests: free cells, and a planned cost against the exact oracle."""

from __future__ import annotations

import math

import numpy as np

from sgplan.assembly import make_problem
from sgplan.mission import compile_mission
from sgplan.planning.amra import plan
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.model import Building, Room

from ..planning.oracle import optimal_cost


def free_cells(building: Building, radius_m: float = 0.0) -> int:
    return int(build_occupancy_grid(building, radius_m).traversable.sum())


def planned_and_exact_cost(
    building: Building, formula: str, start: tuple[int, int, int]
) -> tuple[float, float]:
    """The NO-LLM planner's cost and the oracle's, for ``formula`` from ``start`` (the scene's radii)."""
    mission = compile_mission(formula)
    problem = make_problem(building, mission, start).problem
    expected = optimal_cost(problem.grid, problem.labels, problem.automaton, start, problem.profile)
    result = plan(problem, "NO-LLM")
    assert result.status == "optimal" and math.isfinite(expected)
    return float(result.cost_m), float(expected)


def room_named(building: Building, name: str) -> Room:
    (room,) = building.rooms_named(name)
    return room


def cells_of(building: Building, room_id: int) -> int:
    return int(np.count_nonzero(building.floors[0].room_map == room_id))
