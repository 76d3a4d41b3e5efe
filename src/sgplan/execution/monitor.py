"""The runtime monitor: the poses a robot actually drove -> the mission's automaton state and a verdict.

>>> monitor = Monitor.in_session(sgplan.Session(building), mission)            # doctest: +SKIP
>>> status = monitor.observe_xy(poses)          # (n, 3) metres: x_m, y_m, floor   # doctest: +SKIP
>>> status.verdict, status.state, status.summary()                            # doctest: +SKIP
('in-progress', 2, 'in progress: left: go to the bedroom (room_11, floor 1); never enter ...')

What the monitor reads (the same word a planned path is judged by, docs/semantics.md): the label of every
cell the robot occupied, in order, each cell once per visit. Poses are turned into cells
(:mod:`sgplan.execution.poses`: never moved; off the grid is an error, inside an obstacle is reported).
Between two consecutive poses on one floor the robot is assumed to have driven the straight segment
between their cell centres, and every cell whose interior the segment crosses is read (a cell corner it
passes through leads into the diagonal cell; the two cells beside it are only touched, as on the
planner's diagonal step), as :func:`sgplan.outputs.waypoints.simplify_path` assumes of the waypoints it
writes; a step to a neighbouring cell reads only that cell (the planner's own move). Between floors it
took the stairs, portal to portal. A pose farther than ``max_gap_m`` from the one before, and a straight
line that crosses cells the robot cannot enter, are reported: the verdict then rests on that assumption.

Verdicts, after the poses read so far:

- ``done``: the automaton state is accepting (the mission is satisfied if the robot stops here);
- ``violated``: from this state no word of the label sets the robot can produce (those of the grid's
  traversable cells) reaches acceptance; :attr:`MonitorStatus.violation` names the step that broke it;
- ``in-progress``: otherwise; :attr:`MonitorStatus.left` says what is left. Whether it is still
  reachable *in this building from here* is a planning question (a plan from the trajectory's end).

Profiles: ``ltlf`` reads the first pose's label; ``authors`` does not (the automaton starts on it).
A missing automaton edge is the mission's business (load it with the same profile).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from sgplan.errors import PlanningError
from sgplan.execution.poses import (
    Cell3,
    PoseIssue,
    PoseNamer,
    as_poses,
    cells_of_poses,
    crossing_issues,
    gap_issues,
    obstacle_issues,
    pose_name,
    route_through_stairs,
    segment_lengths_m,
)
from sgplan.execution.words import MissionWords
from sgplan.explain.scene_labels import occurring_labels
from sgplan.mission import Mission
from sgplan.planning.setups import check_profile, reach_model_for
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building

if TYPE_CHECKING:
    from sgplan.api import Session
    from sgplan.logic.formula import Formula

Verdict = Literal["done", "violated", "in-progress"]
DEFAULT_MAX_GAP_M = 1.0
"""Default tolerance (metres, on one floor) between consecutive poses before a gap is reported."""


@dataclass(frozen=True)
class Violation:
    """The step after which the mission could no longer be completed.

    ``pose`` is the pose whose segment (from the pose before) contains the cell ``cell`` ``(row, col,
    floor)`` at metric ``x_m``, ``y_m``; the automaton went ``from_state -> to_state`` there. ``text``:
    ``entered the kitchen (room_4, floor 0), which the mission forbids: never enter the kitchen ...``.
    """

    pose: int
    cell: Cell3
    x_m: float
    y_m: float
    from_state: int
    to_state: int
    text: str

    def describe(self, name: PoseNamer = pose_name) -> str:
        """``at pose 37, x 3.10 m, y 4.55 m, floor 0: entered the kitchen ...`` (the cell's centre)."""
        return (f"at {name(self.pose)}, x {self.x_m:.2f} m, y {self.y_m:.2f} m, floor {self.cell[2]}: "
                f"{self.text}")

    def to_dict(self) -> dict[str, Any]:
        return {"pose": self.pose, "cell": list(self.cell), "x_m": self.x_m, "y_m": self.y_m,
                "from_state": self.from_state, "to_state": self.to_state, "text": self.text}


@dataclass(frozen=True)
class MonitorStatus:
    """The monitor after a call to :meth:`Monitor.observe_xy` / :meth:`Monitor.observe_cells`.

    Attributes
    ----------
    verdict:
        ``"done"``, ``"violated"`` or ``"in-progress"`` (see :mod:`sgplan.execution.monitor`).
    state:
        the automaton state after every pose read so far; ``accepting`` whether it is accepting.
    cell:
        the last cell read ``(row, col, floor)`` (``None`` before any pose).
    poses, cells:
        poses and cell labels read so far (a cell visited twice in a row is read once).
    length_m:
        metres along the route the monitor assumed (cell centres; stairs at their cost).
    states:
        ``(n,)`` int32: the automaton state after each pose of this call.
    lengths_m:
        ``(n,)`` metres along the assumed route from the run's first pose to each pose of this call.
    violation:
        the first step that broke the mission (it stays once broken), else ``None``.
    issues:
        what this call's poses made the monitor assume (:class:`~sgplan.execution.poses.PoseIssue`).
    words:
        the monitor's words (:class:`~sgplan.execution.words.MissionWords`), read by :attr:`left`.
    """

    verdict: Verdict
    state: int
    accepting: bool
    cell: Cell3 | None
    poses: int
    cells: int
    length_m: float
    states: np.ndarray = field(repr=False)
    lengths_m: np.ndarray = field(repr=False)
    violation: Violation | None
    issues: tuple[PoseIssue, ...]
    words: MissionWords = field(repr=False, compare=False)

    @property
    def left(self) -> str:
        """What is left to do, in words (``in-progress``); for ``done``, what must still hold if the robot
        goes on (empty when nothing); empty for ``violated``.

        Cost: the first time a run's monitor is asked about a state, a few small automata (milliseconds to
        tens of milliseconds: the residual formula and its reading); a look-up afterwards."""
        return "" if self.verdict == "violated" else self.words.residual(self.state).text()

    def summary(self, name: PoseNamer = pose_name) -> str:
        """One line (more for a residual read from its automaton): the verdict and what is left."""
        if self.verdict == "violated":
            if self.violation is None:  # no step of this run broke it: it was so when the monitor started
                return (f"violated: the mission cannot be completed from automaton state {self.state}, as "
                        "already when the monitor started")
            return f"violated {self.violation.describe(name)}"
        if self.verdict == "done":
            keep = f"; if the robot goes on: {self.left}" if self.left else ""
            return f"done: the mission is satisfied{keep}"
        return f"in progress: left: {self.left}" if self.left else "in progress"

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready record (``states`` as a list)."""
        return {
            "verdict": self.verdict, "state": self.state, "accepting": self.accepting,
            "cell": list(self.cell) if self.cell is not None else None, "poses": self.poses,
            "cells": self.cells, "length_m": self.length_m, "states": self.states.tolist(),
            "lengths_m": self.lengths_m.tolist(),
            "violation": self.violation.to_dict() if self.violation else None, "left": self.left,
            "issues": [issue.to_dict() for issue in self.issues],
        }


class Monitor:
    """Follows a running mission from the poses a robot drove (see the module for the model).

    Parameters
    ----------
    building, mission:
        the scene and the mission being run.
    grid, labels:
        the occupancy grid (robot radius) and the mission's ``(floors, rows, cols)`` label raster (bit
        ``i`` = ``mission.automaton.aps[i]``) the monitor reads; after a scene change, :meth:`rebased`
        takes the new ones.
    profile:
        ``"ltlf"`` (the first pose's label is read) or ``"authors"`` (it is not).
    max_gap_m:
        metres between consecutive poses (on their floor) beyond which a gap is reported.
    state, at:
        resume a run: the automaton ``state`` after the robot's cell ``at`` ``(row, col, floor)`` (e.g. a
        plan's state at that path cell); the next pose is joined to ``at``, whose label is not read again.
        Default: the initial state, nothing read.

    Raises
    ------
    PlanningError
        an unknown profile, a label raster of another shape than the grid, a ``state`` the automaton
        lacks, or ``at`` off the grid.
    """

    def __init__(self, building: Building, mission: Mission, grid: OccupancyGrid, labels: np.ndarray, *,
                 profile: str = "ltlf", max_gap_m: float = DEFAULT_MAX_GAP_M, state: int | None = None,
                 at: Cell3 | None = None) -> None:
        check_profile(profile)
        if tuple(labels.shape) != grid.shape:
            raise PlanningError(f"label raster has shape {tuple(labels.shape)}, the grid {grid.shape} "
                                "(floors, rows, cols); build both from the same building")
        automaton = mission.automaton
        if state is not None and not 0 <= state < automaton.num_states:
            raise PlanningError(f"automaton state {state} does not exist (states 0.."
                                f"{automaton.num_states - 1})")
        self.building, self.mission, self.grid, self.profile = building, mission, grid, profile
        self.max_gap_m = float(max_gap_m)
        self.labels = np.ascontiguousarray(labels)
        self._table = np.ascontiguousarray(automaton.table, dtype=np.int32)
        self._progressions: dict[tuple[int, ...], Formula] = {}  # MissionWords': kept by rebased()
        self.state = automaton.initial if state is None else int(state)
        self.cell: Cell3 | None = None
        if at is not None:
            row, col, floor = cells_of_poses(as_poses(at, "at"), grid, metric=False, first=0)[0].tolist()
            self.cell = (row, col, floor)
        self.poses = self.cells = 0
        self.length_m = 0.0
        self.violation: Violation | None = None

    @cached_property
    def _realizable(self) -> np.ndarray:
        """What the robot can produce: the labels of the cells it may enter (made on first use: a monitor
        rebased on every scene change of a run reads them only when it reads poses or says words)."""
        return occurring_labels(self.labels, self.grid.traversable, self.mission.automaton.num_labels)

    @cached_property
    def _dead(self) -> np.ndarray:
        """``(Q,)`` bool: the states from which no word of :attr:`_realizable` labels accepts."""
        return ~self.mission.automaton.live_states(self._realizable)

    @cached_property
    def words(self) -> MissionWords:
        """The mission's words in this building (what is left, what broke it)."""
        return MissionWords(self.mission, self.building, self._realizable, self._progressions)

    @classmethod
    def in_session(cls, session: Session, mission: Mission, *, profile: str = "ltlf",
                   robot_radius_m: float | None = None, reach_radius_m: float | None = None,
                   reach_model: str | None = None, max_gap_m: float = DEFAULT_MAX_GAP_M,
                   state: int | None = None, at: Cell3 | None = None) -> Monitor:
        """A monitor on the session's grid and label raster for these radii and reach model (the scene's
        radii and the profile's model by default, as :meth:`sgplan.Session.plan` uses them); the other
        parameters are :class:`Monitor`'s."""
        radii = session.radii(robot_radius_m, reach_radius_m)
        labels = session.labels(mission, radii.reach_m, reach_model_for(profile, reach_model))
        return cls(session.building, mission, session.grid(radii.robot_m), labels, profile=profile,
                   max_gap_m=max_gap_m, state=state, at=at)

    def rebased(self, grid: OccupancyGrid, labels: np.ndarray, building: Building | None = None) -> Monitor:
        """This monitor's progress (state, last cell, counts, violation) on a changed scene: its new grid,
        label raster and building."""
        other = Monitor(building or self.building, self.mission, grid, labels, profile=self.profile,
                        max_gap_m=self.max_gap_m, state=self.state)
        other.cell, other.poses, other.cells = self.cell, self.poses, self.cells
        other.length_m, other.violation = self.length_m, self.violation
        other._progressions = self._progressions
        return other

    def observe_xy(self, poses: object, *, name: PoseNamer = pose_name) -> MonitorStatus:
        """Read metric poses: one ``(x_m, y_m, floor)`` (e.g. a :class:`sgplan.Point`) or an ``(n, 3)``
        array, in the scene's frame. See :meth:`observe_cells`."""
        return self._observe(as_poses(poses, "poses"), metric=True, name=name)

    def observe_cells(self, poses: object, *, name: PoseNamer = pose_name) -> MonitorStatus:
        """Read cell poses: one ``(row, col, floor)`` or an ``(n, 3)`` integer array.

        Reading poses in batches or one at a time gives the same states and verdicts. A call is atomic:
        when it raises, nothing of it was read. ``name`` names pose ``k`` (over all poses read) in
        messages.

        Cost: linear in the poses and the cells between them (compiled; the first call of a process
        loads the kernel, the first ever compiles it); the words of what is left are made when
        :attr:`MonitorStatus.left` is read; those of a violation, once, when it happens.

        Raises
        ------
        TrajectoryError
            a pose that is not finite, off the grid or on a floor the scene lacks, or a floor change with
            no stairs (named by ``name``).
        """
        return self._observe(as_poses(poses, "poses"), metric=False, name=name)

    def _observe(self, poses: np.ndarray, *, metric: bool, name: PoseNamer) -> MonitorStatus:
        from sgplan.execution._follow import follow

        first = self.poses
        if not len(poses):
            return self._status(np.zeros(0, np.int32), np.zeros(0), ())
        cells = cells_of_poses(poses, self.grid, metric=metric, first=first, name=name)
        # The route starts on the cell the robot already stands on, if any (not read again).
        shift = 0 if self.cell is None else 1
        joined = cells if self.cell is None else np.vstack([np.array([self.cell], np.int64), cells])
        route, rows = route_through_stairs(joined, self.grid, first=first - shift, name=name)
        states = np.empty(len(route), np.int32)
        blocked = np.empty(len(route), np.bool_)
        state, count, broken_row, r, c, before, at, state_before = follow(
            route, self.cell is None and self.profile == "ltlf", self.labels, self.grid.traversable,
            self._table, self.state, self._dead, states, blocked)
        planar_m, stairs_m = segment_lengths_m(route, self.grid)
        issues = self._issues(cells, rows, planar_m, blocked, first, shift, name)
        if broken_row >= 0 and self.violation is None:
            floor = int(route[broken_row, 2])
            x_m, y_m, _ = self.grid.cell_xyz(floor, (r, c))
            self.violation = Violation(
                first - shift + int(np.searchsorted(rows, broken_row)), (int(r), int(c), floor), x_m, y_m,
                int(state_before), int(self._table[state_before, at]),
                self.words.breach(int(state_before), int(before), int(at)),
            )
        lengths_m = self.length_m + np.cumsum(planar_m + stairs_m)[rows[shift:]]
        self.state, self.cell = int(state), (int(cells[-1, 0]), int(cells[-1, 1]), int(cells[-1, 2]))
        self.poses += len(cells)
        self.cells += int(count)
        self.length_m = float(lengths_m[-1])
        return self._status(states[rows[shift:]], lengths_m, tuple(issues))

    def _issues(self, cells: np.ndarray, rows: np.ndarray, planar_m: np.ndarray, blocked: np.ndarray,
                first: int, shift: int, name: PoseNamer) -> list[PoseIssue]:
        """Obstacle poses, gaps and lines through obstacles among this call's poses."""
        # Per pose: the metres from the pose before, and whether its line crossed a blocked cell (route
        # rows rows[k-1]+1 .. rows[k]); the run's very first pose comes from nowhere (row 0: 0, False).
        walked = np.diff(np.cumsum(planar_m)[rows], prepend=0.0)[shift:]
        crossed = np.diff(np.cumsum(blocked)[rows], prepend=0)[shift:] > 0
        return [*obstacle_issues(cells, self.grid, self.building, first=first, name=name),
                *gap_issues(walked, self.max_gap_m, first=first, name=name),
                *crossing_issues(crossed, first=first, name=name)]

    def _status(self, states: np.ndarray, lengths_m: np.ndarray, issues: tuple[PoseIssue, ...]
                ) -> MonitorStatus:
        accepting = bool(self.mission.automaton.accepting[self.state])
        verdict: Verdict = ("violated" if self._dead[self.state] else "done" if accepting else "in-progress")
        return MonitorStatus(verdict, self.state, accepting, self.cell, self.poses, self.cells, self.length_m,
                             states, lengths_m, self.violation, issues, self.words)
