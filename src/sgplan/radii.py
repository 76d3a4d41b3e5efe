"""The robot and reach radii a plan uses: given, else the scene's, else the defaults.

Light (no numpy): every front end resolves them the same way through :func:`resolve_radii`, and results
record where each came from (:class:`Radii`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from sgplan.errors import PlanningError

if TYPE_CHECKING:
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
