"""Problem assembly: scene + mission + start + options -> a planning problem, with the scene's defaults.

The one place every front end (through :mod:`sgplan.api`) turns its inputs into a
:class:`~sgplan.planning.problem.PlanningProblem`: which radii apply (:mod:`sgplan.radii`), how the grid and
the label raster are built, which semantics profile and guidance the problem carries.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

from sgplan.errors import PlanningError
from sgplan.options import PlanOptions
from sgplan.radii import Radii, resolve_radii

if TYPE_CHECKING:  # the planner and the grid builder (numba, scipy) load when a problem is made
    import numpy as np

    from sgplan.mission import Mission
    from sgplan.planning.problem import PlanningProblem
    from sgplan.planning.shared import SharedParts
    from sgplan.scene.grid import OccupancyGrid
    from sgplan.scene.model import Building


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
