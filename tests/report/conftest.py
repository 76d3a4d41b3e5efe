"""A planned demo mission shared by the report tests (planned once per session, NO-LLM setup)."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from sgplan.mission import Mission, mission_from_formula
from sgplan.planning.amra import PlanResult, plan
from sgplan.planning.problem import PlanningProblem
from sgplan.scene.demo import demo_building
from sgplan.scene.grid import OccupancyGrid, build_occupancy_grid
from sgplan.scene.model import Building

# The demo's mission shape: the bathroom without its sink, then a dining-room chair, then the bedroom upstairs,
# always avoiding the living room and the kitchen. The path goes out and back and uses the stairs.
FORMULA = ('F("enter(room_5)" & !"reach(object_21)" & F("reach(object_28)" & "enter(room_7)" & F "enter(room_11)")) '
           '& G(!"enter(room_6)" & !"enter(room_4)")')
REACH_M = 0.6


@dataclass
class DemoPlan:
    building: Building
    grid: OccupancyGrid
    mission: Mission
    result: PlanResult


@pytest.fixture(scope="session")
def demo_plan() -> DemoPlan:
    building = demo_building()
    mission = mission_from_formula(FORMULA, text="Visit the bathroom but not its sink, sit on a dining chair, "
                                                 "then go to the bedroom upstairs; never enter the living room or kitchen.")
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    problem = PlanningProblem(building=building, grid=grid, labels=mission.labels(building, REACH_M),
                              automaton=mission.automaton, start=building.initial_cells[0], reach_radius_m=REACH_M)
    result = plan(problem, "NO-LLM")
    assert result.path is not None
    return DemoPlan(building, grid, mission, result)
