"""A planned demo mission shared by the drawing and report tests (planned once, NO-LLM setup)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

from sgplan.mission import Mission, compile_mission
from sgplan.planning.amra import SearchResult, plan
from sgplan.planning.problem import PlanningProblem
from sgplan.scene.demo import demo_building
from sgplan.scene.grid import OccupancyGrid, build_occupancy_grid
from sgplan.scene.model import Building

# The demo's mission shape: the bathroom without its sink, then a dining-room chair, then the bedroom
# upstairs, always avoiding the living room and the kitchen. The path goes out and back and takes the stairs.
FORMULA = (
    'F("enter(room_5)" & !"reach(object_21)" & F("reach(object_28)" & "enter(room_7)" & F "enter(room_11)")) '
    '& G(!"enter(room_6)" & !"enter(room_4)")'
)
TEXT = (
    "Visit the bathroom but not its sink, sit on a dining chair, then go to the bedroom upstairs; "
    "never enter the living room or kitchen."
)
REACH_M = 0.6


@dataclass(frozen=True)
class DemoPlan:
    building: Building
    grid: OccupancyGrid
    mission: Mission
    result: SearchResult


@lru_cache(maxsize=1)
def demo_plan() -> DemoPlan:
    """The demo building, its grid, the mission above and its optimal plan from initial position 0."""
    building = demo_building()
    mission = compile_mission(FORMULA, text=TEXT)
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    problem = PlanningProblem(
        building=building,
        grid=grid,
        labels=mission.labels(building, REACH_M),
        automaton=mission.automaton,
        start=building.initial_cells[0],
        reach_radius_m=REACH_M,
    )
    result = plan(problem, "NO-LLM")
    assert result.path is not None
    return DemoPlan(building, grid, mission, result)
