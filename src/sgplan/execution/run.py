"""A mission carried through a changing building: :class:`Run`, the one object for progress, monitoring,
scene changes, exact replanning and amendments (docs/execution.md).

>>> session = sgplan.Session(sgplan.load_scene("demo"))                          # doctest: +SKIP
>>> run = sgplan.Run(session, mission, start="kitchen", setup="A*")              # doctest: +SKIP
>>> run.plan.cost_m                            # the optimal plan from here     # doctest: +SKIP
>>> run.observe(run.plan.path[:40, :3], metric=False)  # the robot drove 40 cells  # doctest: +SKIP
>>> run.change([CloseDoor(("kitchen", "corridor"))]); run.plan.cost_m  # replanned  # doctest: +SKIP
>>> run.amend("always avoid the bedroom on floor 1")                            # doctest: +SKIP
>>> restored = Run.from_dict(run.to_dict(), session)                            # doctest: +SKIP

A run's progress is the robot's cell and the mission's automaton state there (after reading the cell's
label). Every plan starts from that (cell, state) in the current building, so a robot that has already
been to the bathroom is never sent back. A plan is made when :attr:`Run.plan` is read and the last one is
stale: after a change that could shorten or invalidate it, an amendment, or the robot leaving it.

Status: ``in-progress``, ``done`` (the automaton accepts: the mission is satisfied here), ``violated`` (no
continuation can satisfy it any more: the monitor names the step that broke it) or ``impossible`` (it
could still be satisfied in principle, but not from here in this building: :attr:`Run.why` says why;
the run stays usable, and a change that reopens the way makes it plannable again).

Events (:class:`~sgplan.execution.events.RunEvent`: ``changed``, ``replanned``, ``progress``, ``done``,
``violated``, ``impossible``, ``amended``, ``refused``) go to the callbacks given with
:meth:`Run.subscribe`, as they happen, and into :attr:`Run.history`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from sgplan.errors import PlanningError, SceneError
from sgplan.execution.changes import Change, change_from_dict
from sgplan.execution.events import RunEvent
from sgplan.execution.impossible import why_impossible
from sgplan.execution.labels import RunLabels
from sgplan.execution.monitor import Monitor, MonitorStatus
from sgplan.execution.parts import RunParts
from sgplan.execution.regrid import regrid
from sgplan.execution.replan import plan_from
from sgplan.execution.run_io import (
    FORMAT,
    VERSION,
    mission_from_dict,
    mission_to_dict,
    saved_session,
    scene_reference,
)
from sgplan.execution.world import SceneDelta, SceneState
from sgplan.intsets import members, unique_sorted

if TYPE_CHECKING:
    from sgplan.api import Explained, Session
    from sgplan.llm.backends import MissionGuide
    from sgplan.mission import Mission
    from sgplan.options import PlanOptions
    from sgplan.planning.termination import Termination
    from sgplan.result import PlanResult
    from sgplan.scene.model import Building
    from sgplan.starts import StartSpec

RunStatus = Literal["in-progress", "done", "violated", "impossible"]
IMPOSSIBLE_EXIT = 7
"""Exit code of a command whose run ended impossible (beside the monitor's 5 in progress, 6 violated)."""


@dataclass(frozen=True)
class ChangeReport:
    """What :meth:`Run.change` did: one :class:`~sgplan.execution.world.SceneDelta` per change, the cells
    that became obstacles / free, the cells whose label changed, and whether the current plan survives
    (it does when nothing became free, no label changed and its remaining path crosses no new obstacle:
    every other path can then only have grown longer)."""

    deltas: tuple[SceneDelta, ...]
    blocked_cells: int
    freed_cells: int
    relabelled_cells: int
    plan_kept: bool

    def describe(self) -> str:
        return "; ".join(d.description for d in self.deltas)


@dataclass(frozen=True)
class Amendment:
    """The outcome of :meth:`Run.amend`: the amendment as given, said back in words, and whether it took
    effect (``reason`` says why not)."""

    text: str
    said_back: str
    accepted: bool
    reason: str | None = None


class Run:
    """A mission carried through a changing building from a start (see the module):
    ``sgplan.Run(session, mission, start, setup="A*")``.

    Parameters
    ----------
    session:
        the session of the building as the run starts on it (its grid and labels are reused; the run's
        changes never touch the session's building).
    mission:
        the mission.
    start:
        where the robot starts, as :func:`sgplan.plan` takes it.
    options, option_values:
        the planning options (:class:`sgplan.PlanOptions`) of every plan of the run, as
        :func:`sgplan.plan` takes them: a value, or keywords (``setup="A*"``), or both.
    guide:
        where a setup using LLM guidance gets it when the mission carries none (default: the offline
        symbolic guide).
    state:
        resume a run: the automaton state at the start cell, its label already read (default: the
        mission's initial state, the start's label read as the profile says).

    Cost: the session's grid and labels for the radii (kept by the session), the run's cell numbering (two
    passes over the grid), the start cell read by the monitor. No plan is made until :attr:`plan` is
    read.
    """

    def __init__(self, session: Session, mission: Mission, start: StartSpec = None,
                 options: PlanOptions | None = None, *, guide: MissionGuide | None = None,
                 state: int | None = None, **option_values: Any) -> None:
        from sgplan.options import PlanOptions
        from sgplan.starts import start_cell

        self.session = session
        self.options = PlanOptions.from_keywords(options, **option_values)
        self.guide = guide
        self.radii = session.radii(self.options.robot_radius_m, self.options.reach_radius_m)
        self.scene = SceneState.of(session.building)
        self.grid = session.grid(self.radii.robot_m)
        self._set_mission(mission, session.proposition_cells, check=state is None)
        self.parts = RunParts(self.grid, self.labels.raster, self.scene.scene())
        self.start, self.start_from = start_cell(session.building, self.grid, start)
        self.monitor = Monitor(session.building, self.mission, self.grid, self.labels.raster,
                               profile=self.options.profile, state=state,
                               at=self.start if state is not None else None)
        self.changes: list[Change] = []
        self.amendments: list[str] = []
        self.history: list[RunEvent] = []
        self.why: str | None = None
        self._callbacks: list[Callable[[RunEvent], None]] = []
        self.stop_when: Termination | None = None
        """A further condition that stops the run's searches besides the options' budgets (e.g. a
        service's request deadline and a cancel flag, :mod:`sgplan.planning.termination`)."""
        self._plan: PlanResult | None = None
        self._on_plan = 0  # the robot's row on the current plan's path
        self._stale = True
        if state is None:
            self.monitor.observe_cells(np.array([self.start]))
        self._status: RunStatus = "in-progress"
        self._follow_status()

    # -- state -------------------------------------------------------------------------------------

    @property
    def building(self) -> Building:
        """The building as the changes so far left it."""
        return self.scene.building

    @property
    def position(self) -> tuple[int, int, int]:
        """The robot's cell ``(row, col, floor)``."""
        cell = self.monitor.cell
        assert cell is not None
        return cell

    @property
    def state(self) -> int:
        """The mission's automaton state at the robot's cell (after reading its label)."""
        return self.monitor.state

    @property
    def status(self) -> RunStatus:
        return self._status

    def left(self) -> str:
        """What is left of the mission, in words (empty once done or violated)."""
        return "" if self._status in ("done", "violated") else self.monitor.words.residual(self.state).text()

    def subscribe(self, callback: Callable[[RunEvent], None]) -> None:
        """Call ``callback`` with every later event, as it happens."""
        self._callbacks.append(callback)

    def _emit(self, kind: str, message: str, seconds: float | None = None, **details: Any) -> RunEvent:
        event = RunEvent(kind, message, details, seconds)
        self.history.append(event)
        for callback in self._callbacks:
            callback(event)
        return event

    def _set_mission(self, mission: Mission, cells: Callable | None = None, check: bool = True) -> None:
        from sgplan.planning.setups import get_setup

        if get_setup(self.options.setup).uses_llm:
            from sgplan.api import add_guidance

            mission, _ = add_guidance(mission, self.building, self.guide)
        if check:  # a restored run's mission may name objects that only its changes add
            mission.check_scene(self.building)
        self.mission = mission
        self._explained: Explained | None = None
        self._mission_data: dict[str, Any] | None = None  # to_dict's form of the mission, made once
        self.labels = RunLabels(self.building, mission.ordered_propositions, self.radii.reach_m,
                                self.options.effective_reach_model, cells)

    def _follow_status(self) -> None:
        """The status after the monitor moved, with the events it calls for."""
        status = self.monitor.observe_cells(np.zeros((0, 3), np.int64))
        if status.verdict == "violated" and self._status != "violated":
            self._status = "violated"
            text = status.summary()
            self._emit("violated", text, state=self.state, cell=list(self.position))
        elif status.verdict == "done" and self._status != "done":
            self._status = "done"
            self._emit("done", status.summary(), state=self.state, cell=list(self.position))

    # -- planning ----------------------------------------------------------------------------------

    @property
    def plan(self) -> PlanResult | None:
        """The optimal plan from the robot's cell and automaton state in the current building, made now if
        the last one is stale (cost: one search over the run's carried parts, see :meth:`replan`);
        ``None`` when the run is done, violated or impossible."""
        if self._status in ("done", "violated"):
            return None
        if self._stale:
            self.replan()
        return self._plan

    @property
    def remaining_offset(self) -> int:
        """The robot's row on the current plan's path."""
        return self._on_plan

    @property
    def remaining_path(self) -> np.ndarray | None:
        """The rows ``[row, col, floor, q]`` of the current plan from the robot's cell on."""
        plan = self.plan
        return None if plan is None or plan.path is None else plan.path[self._on_plan :]

    @property
    def remaining_cost_m(self) -> float | None:
        """Metres of :attr:`remaining_path` (the current plan from the robot's cell on)."""
        from sgplan.outputs.waypoints import leg_costs

        rest = self.remaining_path
        return None if rest is None else float(leg_costs(rest, self.grid).sum())

    def replan(self) -> PlanResult | None:
        """Plan from the robot's (cell, automaton state) in the current building, now.

        Cost: the h_LTL fields repaired for the changes since the last plan (each bounded by a full
        Dijkstra over the building), the rest of h_LTL's tables (a pass over the cells), and one AMRA*
        search; composite action maps the search needs are rebuilt after a change.
        Returns the plan, or ``None`` when no path satisfies the rest from here (status ``impossible``,
        :attr:`why` says why).
        """
        t0 = time.perf_counter()
        try:
            plan = self._search()
        except PlanningError as error:
            self._impossible(str(error), time.perf_counter() - t0)
            return None
        self._adopt_plan(plan, time.perf_counter() - t0)
        return plan

    def _search(self) -> PlanResult:
        """A plan from the robot's cell and state; :class:`PlanningError` (status ``infeasible``) when
        there is none. Other planning errors (a bug, a bad option) are raised as they are."""
        from sgplan.api import explain_for_result

        if self._explained is None:
            self._explained = explain_for_result(self.mission, self.building,
                                                 reach_radius_m=self.radii.reach_m,
                                                 reach_model=self.options.effective_reach_model)
        try:
            return plan_from(self, self.position, self.state, self._explained)
        except PlanningError as error:
            if error.status in ("infeasible", "invalid-start", "unsatisfiable"):
                raise PlanningError(str(error), status="infeasible") from None
            raise

    def _adopt_plan(self, plan: PlanResult, seconds: float) -> None:
        was_impossible = self._status == "impossible"
        self._plan, self._stale, self._on_plan = plan, False, 0
        self._status, self.why = "in-progress", None
        self._emit("replanned", f"planned {plan.cost_m:.2f} m from {self._where()}", seconds,
                   cost_m=plan.cost_m, status=plan.status, cell=list(self.position), state=self.state,
                   plannable_again=was_impossible)

    def _impossible(self, message: str, seconds: float) -> None:
        self._plan, self._stale = None, True
        self.why = why_impossible(self, message)
        self._status = "impossible"
        self._emit("impossible", self.why, seconds, cell=list(self.position), state=self.state)

    def _where(self) -> str:
        row, col, floor = self.position
        x_m, y_m, _ = self.grid.cell_xyz(floor, (row, col))
        return f"x {x_m:.2f} m, y {y_m:.2f} m, floor {floor} (automaton state {self.state})"

    # -- monitoring --------------------------------------------------------------------------------

    def observe(self, poses: object, *, metric: bool = True) -> MonitorStatus:
        """Read the poses the robot drove: metric ``(x_m, y_m, floor)`` (``metric=True``) or cells
        ``(row, col, floor)``, one or an ``(n, 3)`` array (:class:`~sgplan.execution.monitor.Monitor`).

        The plan stays current while the robot follows it (a suffix of an optimal path is optimal from
        where it starts); otherwise the next :attr:`plan` is made from where the robot is.

        Cost: linear in the poses and the cells between them (compiled), plus the monitor's words of a
        newly reached automaton state.
        """
        before = self.state
        status = (self.monitor.observe_xy(poses) if metric else self.monitor.observe_cells(poses))
        self._track_plan()
        if self.state != before and status.verdict == "in-progress":
            self._emit("progress", f"in progress: left: {status.left}", state=self.state,
                       cell=list(self.position))
        self._follow_status()
        return status

    def _track_plan(self) -> None:
        """Find the robot on the current plan's path (at or after the last row found), else mark the plan
        stale."""
        if self._plan is None or self._plan.path is None or self._stale:
            return
        path = self._plan.path
        here = np.array([*self.position, self.state])
        hits = np.flatnonzero((path[self._on_plan :] == here).all(axis=1))
        if hits.size:
            self._on_plan += int(hits[0])
        else:
            self._stale = True

    # -- changes -----------------------------------------------------------------------------------

    def change(self, changes: Sequence[Change | dict[str, Any]]) -> ChangeReport:
        """Apply scene changes (typed values or their mapping form), in order, all or none.

        Cost: per change, a copy of each floor raster it touches, the occupancy grid recomputed around the
        changed cells, the label bits of moved objects, and a copy of the run's padded cell index; the
        fields are repaired and the plan remade when next needed.

        Raises
        ------
        SceneError
            naming the change (its position, from 1) and why it cannot apply; or a change that would put
            an obstacle on the robot's own cell. Nothing is applied then.
        """
        typed = [c if not isinstance(c, dict) else change_from_dict(c, f"change {i}")
                 for i, c in enumerate(changes, 1)]
        scene, grid = self.scene, self.grid
        deltas: list[SceneDelta] = []
        objects: set[int] = set()
        blocked: list[np.ndarray] = []
        freed: list[np.ndarray] = []
        for i, change in enumerate(typed, 1):
            try:
                scene, delta = scene.apply(change)
            except SceneError as error:
                raise SceneError(f"change {i}: {error}") from None
            grid, moved = regrid(grid, scene.building, delta.cells)
            deltas.append(delta)
            objects |= delta.objects
            blocked.append(moved.blocked)
            freed.append(moved.freed)
        row, col, floor = self.position
        if not grid.traversable[floor, row, col]:
            raise SceneError(f"the changes put an obstacle on the robot's cell ({row}, {col}) of floor "
                             f"{floor}: move the robot first, or change the area around it")
        from sgplan.execution.regrid import GridChange

        overall = _net_change(self.grid, grid, np.concatenate(blocked), np.concatenate(freed))
        changed = _changed_cells(deltas)
        relabelled = self.labels.update(scene.building, objects, changed)
        self.scene, self.grid = scene, grid
        self.parts.advance(grid, GridChange(*overall), self.labels.raster, relabelled, scene.scene(),
                           at=self.position, objects=objects, changed=changed)
        self.monitor = self.monitor.rebased(grid, self.labels.raster, scene.building)
        self.changes.extend(typed)
        kept = self._plan_survives(overall[0], overall[1].size == 0 and relabelled.size == 0)
        report = ChangeReport(tuple(deltas), int(overall[0].size), int(overall[1].size), int(relabelled.size),
                              kept)
        self._emit("changed", report.describe(), blocked=report.blocked_cells, freed=report.freed_cells,
                   relabelled=report.relabelled_cells, plan_kept=kept,
                   changes=[c.to_dict() for c in typed])
        if self._status == "impossible" and (overall[1].size or relabelled.size):
            self._stale = True
        return report

    def _plan_survives(self, blocked: np.ndarray, nothing_gained: bool) -> bool:
        """Whether the current plan stays optimal (see :class:`ChangeReport`); marks it stale if not."""
        path = None if self._plan is None else self._plan.path
        if path is not None and nothing_gained and not self._stale:
            _, rows, cols = self.grid.shape
            rest = path[self._on_plan :]
            crossed = members((rest[:, 2] * rows + rest[:, 0]) * cols + rest[:, 1], blocked)
            if not crossed.any():
                return True
        self._stale = True
        return False

    # -- amendments --------------------------------------------------------------------------------

    def amend(self, text: str, *, llm: str = "offline", **llm_options: Any) -> Amendment:
        """Join an amendment (natural language, or a formula over ``enter(room_N)`` / ``reach(object_N)``)
        to what is left of the mission, from the robot's position on (:mod:`sgplan.execution.amend`).

        It is said back, checked against the scene and planned; an amendment that no path can satisfy with
        the rest is refused with the conflict named, and the current mission stays.

        Cost: a translation (offline: milliseconds), the amendment's automaton and its product with the
        mission's, the scene checks, one plan (every h_LTL field computed anew: the label bits change).
        """
        from sgplan.execution.amend import amendment_mission, combine
        from sgplan.explain import explain_mission

        amendment = amendment_mission(text, self.building, llm, **llm_options)
        said = explain_mission(amendment, self.building).text
        here = self.labels.raster[self.position[2], self.position[0], self.position[1]]
        truth = {p.name: bool(int(here) >> i & 1) for i, p in enumerate(self.labels.propositions)}
        truth |= self._truth_of(amendment)
        residual = (self.monitor.words.residual(self.state).formula if self.mission.formula is not None
                    else None)
        combined = combine(self.mission, self.state, amendment, truth, residual)
        reason = None
        if not combined.automaton.live_states()[combined.automaton.initial]:
            reason = ("with the mission's rest it can never be satisfied (or the robot's cell already "
                      "breaks it)")
        else:
            before = (self.mission, self.labels, self.monitor, self.parts, self._status, self.why, self._plan,
                      self._stale, self._on_plan)
            self._adopt(combined)
            t0 = time.perf_counter()
            try:
                plan = self._search()
            except PlanningError as error:
                reason = why_impossible(self, str(error))
                (self.mission, self.labels, self.monitor, self.parts, self._status, self.why, self._plan,
                 self._stale, self._on_plan) = before
        if reason is not None:
            self._emit("refused", f"refused the amendment {text!r}: {reason}", text=text, reason=reason)
            return Amendment(text, said, False, reason)
        self.amendments.append(text)
        self._emit("amended", f"amended: {said}", text=text)
        self._adopt_plan(plan, time.perf_counter() - t0)
        return Amendment(text, said, True)

    def _truth_of(self, mission: Mission) -> dict[str, bool]:
        """Which of ``mission``'s propositions hold on the robot's cell (token -> truth)."""
        from sgplan.scene.labels import proposition_cells

        row, col, floor = self.position
        rows, cols = self.building.grid_shape
        at = (floor * rows + row) * cols + col
        model = self.options.effective_reach_model
        return {p.name: bool(np.isin(at, proposition_cells(self.building, p, self.radii.reach_m, model)))
                for p in mission.ordered_propositions}

    def _adopt(self, mission: Mission) -> None:
        """Make ``mission`` (whose initial state is the robot's state now, a live one) the run's mission."""
        self._set_mission(mission)
        self.parts = self.parts.with_labels(self.labels.raster)
        self.monitor = Monitor(self.building, self.mission, self.grid, self.labels.raster,
                               profile=self.options.profile, state=self.mission.automaton.initial,
                               at=self.position)
        self._stale, self._status, self.why = True, "in-progress", None

    # -- saving ------------------------------------------------------------------------------------

    def restore_status(self, status: RunStatus, why: str | None) -> None:
        """Take a saved status (a restored run: ``impossible`` plans again when next asked)."""
        self._status, self.why = status, why

    def to_dict(self) -> dict[str, Any]:
        """The run as JSON-safe data (deterministic: no timings), :meth:`from_dict` reads it back.

        Cost: the mission's automaton table and the changes as data (no plan is stored: a restored run
        plans again from the same cell and state)."""
        return {
            "format": FORMAT, "version": VERSION, "scene": scene_reference(self.session.building),
            "options": self.options.to_dict(), "start": list(self.start), "start_from": self.start_from,
            "mission": self._saved_mission(mission_to_dict), "changes": [c.to_dict() for c in self.changes],
            "amendments": list(self.amendments), "position": list(self.position), "state": self.state,
            "status": self._status, "why": self.why,
            "monitor": {"poses": self.monitor.poses, "cells": self.monitor.cells,
                        "length_m": self.monitor.length_m,
                        "violation": self.monitor.violation.to_dict() if self.monitor.violation else None},
            "history": [event.to_dict() for event in self.history],
        }

    def _saved_mission(self, to_dict: Callable[[Mission], dict[str, Any]]) -> dict[str, Any]:
        """The mission as :meth:`to_dict` saves it, made once per mission (a service saves a run after
        every pose report; writing the automaton's HOA each time cost more than the report)."""
        if self._mission_data is None:
            self._mission_data = to_dict(self.mission)
        return self._mission_data

    @classmethod
    def from_dict(cls, data: dict[str, Any], session: Session | None = None) -> Run:
        """The run saved by :meth:`to_dict`, on ``session`` (default: a new one on the saved scene).

        Cost: the scene (when no session is given), the changes replayed, the mission's automaton read;
        no plan (the next :attr:`plan` makes one).

        Raises
        ------
        SgplanError
            another format or version, a session on another building, a change that no longer applies.
        """
        from sgplan.options import PlanOptions

        session = saved_session(data, session)
        run = cls(session, mission_from_dict(data["mission"]), tuple(data["position"]),
                  PlanOptions.from_dict(data["options"]), state=int(data["state"]))
        changes = [change_from_dict(c, f"saved change {i}") for i, c in enumerate(data["changes"], 1)]
        if changes:
            run.change(changes)
        run.history = [RunEvent(e["kind"], e["message"], dict(e["details"])) for e in data["history"]]
        run.start, run.start_from = tuple(data["start"]), data["start_from"]
        run.amendments = list(data["amendments"])
        counts = data["monitor"]
        run.monitor.poses, run.monitor.cells, run.monitor.length_m = counts["poses"], counts["cells"], \
            counts["length_m"]
        run.restore_status(data["status"], data.get("why"))
        return run


def _changed_cells(deltas: list[SceneDelta]) -> dict[int, np.ndarray]:
    """Floor -> the flat positions whose category some of ``deltas`` changed."""
    floors = {floor for delta in deltas for floor in delta.cells}
    return {floor: np.concatenate([d.cells[floor] for d in deltas if floor in d.cells]) for floor in floors}


def _net_change(old: Any, new: Any, blocked: np.ndarray, freed: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The cells (flat grid positions) traversable in ``old`` and not in ``new``, and the reverse, among the
    cells some change in between touched."""
    touched = unique_sorted(np.concatenate([blocked, freed]))
    before = old.traversable.reshape(-1)[touched]
    after = new.traversable.reshape(-1)[touched]
    return touched[before & ~after], touched[~before & after]

