"""Joining the parts: scene + mission + start -> a planning problem, with the scene's defaults.

These helpers hold the choices every front end must make the same way (through :mod:`sgplan.api`): which
robot and reach radii apply, which initial position is meant, and how the grid and labels are built.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from sgplan.errors import PlanningError
from sgplan.options import PlanOptions

if TYPE_CHECKING:  # the planner and the grid builder (numba, scipy) load when a problem is made
    import numpy as np

    from sgplan.mission import Mission
    from sgplan.planning.amra import IterationRecord
    from sgplan.planning.problem import PlanningProblem
    from sgplan.planning.shared import SharedParts
    from sgplan.scene.grid import OccupancyGrid
    from sgplan.scene.model import Building

DEFAULT_REACH_RADIUS_M = 0.6
"""The authors' app default, used when neither the user nor the scene gives a reach radius."""


@dataclass(frozen=True)
class Radii:
    """Robot and reach radii in metres, and where each came from (for messages and records)."""

    robot_m: float
    reach_m: float
    robot_from: str
    reach_from: str


def resolve_radii(building: Building, robot_m: float | None = None, reach_m: float | None = None) -> Radii:
    """The radii to plan with: given values, else the scene's (radius_config.bash), else 0 / 0.6 m.

    Raises :class:`PlanningError` for negative radii or a reach radius below the robot radius (a robot
    could then never reach an object it cannot touch; the authors' app refuses it too).
    """
    robot, robot_from = (robot_m, "given") if robot_m is not None else (
        (building.robot_radius_m, "scene") if building.robot_radius_m is not None else (0.0, "default")
    )
    reach, reach_from = (
        (reach_m, "given")
        if reach_m is not None
        else (
            (building.reach_radius_m, "scene")
            if building.reach_radius_m is not None
            else (DEFAULT_REACH_RADIUS_M, "default")
        )
    )
    if robot < 0 or reach <= 0:
        raise PlanningError(
            f"radii must be robot >= 0 and reach > 0 metres, got robot {robot}, reach {reach}"
        )
    if reach < robot:
        raise PlanningError(
            f"reach radius {reach} m is smaller than the robot radius {robot} m; give a larger --reach-radius"
        )
    return Radii(float(robot), float(reach), robot_from, reach_from)


def resolve_start(
    building: Building, start: tuple[int, int, int] | None = None, index: int | None = None
) -> tuple[int, int, int]:
    """The start cell ``(row, col, floor)``: given, or the scene's initial cell number ``index``
    (initial_positions.yaml), or its first one."""
    if start is not None:
        return (int(start[0]), int(start[1]), int(start[2]))
    cells = building.initial_cells
    if not cells:
        raise PlanningError(
            f"scene {building.name!r} has no initial positions: give a start cell (row, col, floor)"
        )
    k = 0 if index is None else index
    if not 0 <= k < len(cells):
        raise PlanningError(
            f"start index {k} is out of range: scene {building.name!r} has {len(cells)} initial positions"
        )
    return cells[k]


@dataclass(frozen=True)
class PreparedProblem:
    """A problem with the radii it was built for and the seconds spent building grid and labels."""

    problem: PlanningProblem
    radii: Radii
    build_s: float


def make_problem(
    building: Building,
    mission: Mission,
    start: tuple[int, int, int],
    options: PlanOptions | None = None,
    *,
    use_guidance: bool = True,
    grid: OccupancyGrid | None = None,
    labels: np.ndarray | None = None,
    shared: SharedParts | None = None,
    start_state: int | None = None,
) -> PreparedProblem:
    """Build the occupancy grid and the label raster, and assemble a :class:`PlanningProblem` with the
    profile, radii and reach model of ``options`` (default: the defaults, :class:`sgplan.PlanOptions`).

    ``grid`` / ``labels`` may be given already built (a :class:`sgplan.api.Session` keeps them between
    missions); they must be the ones of these radii and reach model (``grid.robot_radius_m`` is checked).
    ``shared``: the session's building-only planner parts (:mod:`sgplan.planning.shared`). ``start_state``:
    resume a mission part-way (:class:`~sgplan.planning.PlanningProblem`).
    """
    from sgplan.planning.problem import PlanningProblem
    from sgplan.scene.grid import build_occupancy_grid

    t0 = time.perf_counter()
    options = options if options is not None else PlanOptions()
    model = options.effective_reach_model
    radii = resolve_radii(building, options.robot_radius_m, options.reach_radius_m)
    if grid is None:
        grid = build_occupancy_grid(building, radii.robot_m)
    elif grid.robot_radius_m != radii.robot_m:
        raise PlanningError(
            f"the given grid is for robot radius {grid.robot_radius_m} m, not {radii.robot_m} m"
        )
    if labels is None:
        labels = mission.labels(building, radii.reach_m, model)
    problem = PlanningProblem(
        building=building,
        grid=grid,
        labels=labels,
        automaton=mission.automaton,
        start=start,
        profile=options.profile,
        guidance=mission.guidance if use_guidance else None,
        reach_radius_m=radii.reach_m,
        reach_model=model,
        ap_descriptions=mission.descriptions,
        shared=shared,
        start_state=start_state,
    )
    return PreparedProblem(problem, radii, time.perf_counter() - t0)


def iteration_records(iterations: Sequence[IterationRecord]) -> list[dict[str, Any]]:
    """JSON-ready records of AMRA* iterations: weights, ``cost_m`` (metres), suboptimality bound w1*w2,
    cumulative search seconds and cumulative expansions per queue (``PlanResult.queues`` order).
    The one shape of iterations in every sgplan output (``plan --json``, demo's run.json, bench rows)."""
    return [
        {"w1": it.w1, "w2": it.w2, "cost_m": it.cost_m, "bound": it.bound, "time_s": it.time_s,
         "expansions": list(it.expansions)}
        for it in iterations
    ]


def finite_or_none(value: float) -> float | None:
    """``value``, or ``None`` for an infinite / NaN one (JSON has no infinity)."""
    return value if math.isfinite(value) else None
