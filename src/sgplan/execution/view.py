"""What a run's helpers read of it (:class:`RunView`): the modules that plan for a run
(:mod:`sgplan.execution.replan`) and explain it (:mod:`sgplan.execution.impossible`) take the run as this
view, so they sit below :class:`sgplan.execution.run.Run`, which calls them."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from sgplan.execution.events import RunEvent
    from sgplan.execution.labels import RunLabels
    from sgplan.execution.monitor import Monitor
    from sgplan.execution.parts import RunParts
    from sgplan.mission import Mission
    from sgplan.options import PlanOptions
    from sgplan.planning.termination import Termination
    from sgplan.radii import Radii
    from sgplan.scene.grid import OccupancyGrid
    from sgplan.scene.model import Building


class RunView(Protocol):
    """A run's current building, mission and planner parts, read-only
    (:class:`~sgplan.execution.run.Run` is one)."""

    @property
    def options(self) -> PlanOptions:
        """The planning options of every plan of the run."""

    @property
    def mission(self) -> Mission:
        """The mission, amendments joined."""

    @property
    def building(self) -> Building:
        """The building as the changes so far left it."""

    @property
    def grid(self) -> OccupancyGrid:
        """The occupancy grid of :attr:`building`."""

    @property
    def labels(self) -> RunLabels:
        """The label raster of the mission's propositions over :attr:`building`."""

    @property
    def radii(self) -> Radii:
        """The robot and reach radii of the run's plans."""

    @property
    def parts(self) -> RunParts:
        """The planner's parts of :attr:`grid` and :attr:`labels`, carried across changes."""

    @property
    def stop_when(self) -> Termination | None:
        """A further condition that stops the run's searches besides the options' budgets."""

    @property
    def position(self) -> tuple[int, int, int]:
        """The robot's cell ``(row, col, floor)``."""

    @property
    def state(self) -> int:
        """The mission's automaton state at the robot's cell (after reading its label)."""

    @property
    def monitor(self) -> Monitor:
        """The monitor of the poses the robot drove, with the words of the mission's automaton states."""

    @property
    def history(self) -> Sequence[RunEvent]:
        """The run's events so far, oldest first."""
