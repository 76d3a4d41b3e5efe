"""A simulated robot: it drives a run's plan cell by cell, applies each scene change when its trigger is met
(after a distance, on entering a room, at a waypoint), lets the run replan, and keeps a timeline.

The robot follows the plan exactly, so the run's monitor reads the same cells the plan was made for; a
change with no trigger is applied before the robot starts. The simulation ends when the mission is done
or violated, or when it is impossible and no change is left that the robot could still trigger.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from sgplan.execution.changes import ScheduledChange, Trigger
from sgplan.outputs.waypoints import leg_costs
from sgplan.scene.lookup import find_room

if TYPE_CHECKING:
    from sgplan.execution.events import RunEvent
    from sgplan.execution.run import Run


@dataclass(frozen=True)
class Moment:
    """One line of the timeline: at ``driven_m`` metres driven, ``what`` happened (the start, a change, the
    end); the replan it caused took ``replan_s`` and left ``cost_m`` metres to go (``inf``: impossible);
    ``left`` is what was left of the mission in words."""

    driven_m: float
    what: str
    replan_s: float | None
    cost_m: float | None
    left: str
    status: str

    def to_dict(self) -> dict[str, Any]:
        return {"driven_m": self.driven_m, "what": self.what, "replan_s": self.replan_s,
                "cost_m": None if self.cost_m is None or math.isinf(self.cost_m) else self.cost_m,
                "left": self.left, "status": self.status}

    def describe(self) -> str:
        timing = f", replanned in {self.replan_s * 1e3:.0f} ms" if self.replan_s is not None else ""
        cost = ("" if self.cost_m is None else ", no way left" if math.isinf(self.cost_m)
                else f", {self.cost_m:.2f} m to go")
        left = f"; left: {self.left}" if self.left else ""
        return f"{self.driven_m:8.2f} m  {self.what}{timing}{cost}{left}"


@dataclass
class Simulation:
    """What :func:`simulate` did: the timeline, the cells driven (``(n, 3)`` ``row, col, floor``), every plan
    the robot was given (the path rows from where it was then; all but the last abandoned, unless it
    finished), and the cells each change touched (floor -> flat positions)."""

    run: Run
    timeline: list[Moment] = field(default_factory=list)
    driven: list[np.ndarray] = field(default_factory=list)
    plans: list[np.ndarray] = field(default_factory=list)
    changed: dict[int, list[np.ndarray]] = field(default_factory=dict)

    @property
    def driven_cells(self) -> np.ndarray:
        return np.concatenate(self.driven) if self.driven else np.zeros((0, 3), dtype=np.int64)

    def to_dict(self) -> dict[str, Any]:
        """The whole log as JSON-safe data: the timeline, the run (:meth:`Run.to_dict`), the driven cells
        and the plans."""
        return {"timeline": [m.to_dict() for m in self.timeline], "status": self.run.status,
                "why": self.run.why, "driven": self.driven_cells.tolist(),
                "plans": [p[:, :3].tolist() for p in self.plans], "run": self.run.to_dict()}


def _fires(trigger: Trigger, run: Run, rest: np.ndarray, driven_m: float, lengths: np.ndarray) -> int | None:
    """The first row of ``rest`` (the plan from the robot's cell, row 0 the cell itself) at which the
    trigger is met, ``None`` if none. ``lengths[i]``: metres driven on reaching row ``i``."""
    if trigger.after_m is not None:
        hit = np.flatnonzero(lengths >= trigger.after_m)
        return int(hit[0]) if hit.size else None
    if trigger.enter is not None:
        room = find_room(run.building, trigger.enter)
        rooms = run.grid.room_map[rest[:, 2], rest[:, 0], rest[:, 1]]
        hit = np.flatnonzero(rooms == room.id)
        return int(hit[0]) if hit.size else None
    plan = run.plan
    if plan is None or trigger.waypoint is None or trigger.waypoint >= len(plan.waypoints_simplified):
        return None
    at = plan.waypoints_simplified[trigger.waypoint].index - run.remaining_offset
    return max(int(at), 0) if at < len(rest) else None


def simulate(run: Run, schedule: list[ScheduledChange]) -> Simulation:
    """Drive ``run`` along its plans, applying ``schedule``'s changes as their triggers are met (see the
    module). Cost: one replan per change that voids the plan, plus the monitor's reading of every cell.

    Raises
    ------
    SceneError
        a change that cannot apply when its trigger is met (naming it); the simulation so far is lost.
    """
    sim = Simulation(run)
    events: list[RunEvent] = []
    run.subscribe(events.append)
    sim.driven.append(np.array([run.position], dtype=np.int64))
    now = [c for c in schedule if c.when is None]
    pending = [c for c in schedule if c.when is not None]
    driven_m = 0.0
    if now:
        _apply(sim, run, [c.change for c in now], events, driven_m)
    _moment(sim, run, events, driven_m, "start", mark=len(events))
    while run.status == "in-progress" or (run.status == "impossible" and pending):
        rest = run.remaining_path
        if rest is None:  # impossible: only a change could help, and the robot stands still
            fired = [c for c in pending if c.when is not None and c.when.after_m is not None
                     and c.when.after_m <= driven_m]
            if not fired:
                break
            pending.remove(fired[0])
            _apply(sim, run, [fired[0].change], events, driven_m)
            continue
        lengths = driven_m + np.concatenate([[0.0], np.cumsum(leg_costs(rest, run.grid))])
        hits: list[tuple[int, int]] = []
        for k, c in enumerate(pending):
            row = _fires(c.when, run, rest, driven_m, lengths) if c.when is not None else None
            if row is not None:
                hits.append((row, k))
        stop = min(hits)[0] if hits else len(rest) - 1
        if stop > 0:
            run.observe(rest[1 : stop + 1, :3], metric=False)
            sim.driven.append(rest[1 : stop + 1, :3])
            driven_m = float(lengths[stop])
        if not hits:
            break
        due = [pending[k] for row, k in sorted(hits) if row == stop]
        for change in due:
            pending.remove(change)
        _apply(sim, run, [c.change for c in due], events, driven_m)
    end = {"done": "done: the mission is satisfied", "violated": "violated",
           "impossible": f"stopped: {run.why}"}.get(run.status, "stopped")
    sim.timeline.append(Moment(driven_m, end, None, None, run.left(), run.status))
    return sim


def _apply(sim: Simulation, run: Run, changes: list, events: list, driven_m: float) -> None:
    mark = len(events)
    report = run.change(changes)
    for delta in report.deltas:
        for floor, cells in delta.cells.items():
            sim.changed.setdefault(floor, []).append(cells)
    _moment(sim, run, events, driven_m, report.describe(), mark)


def _moment(sim: Simulation, run: Run, events: list, driven_m: float, what: str, mark: int) -> None:
    """Replan if needed (reading the plan), then add the timeline line for what just happened."""
    plan = run.plan
    replans = [e for e in events[mark:] if e.kind in ("replanned", "impossible")]
    seconds = replans[-1].seconds if replans else None
    if replans and plan is not None and plan.path is not None:
        sim.plans.append(plan.path)
    cost = run.remaining_cost_m if plan is not None else math.inf
    sim.timeline.append(Moment(driven_m, what, seconds, cost, run.left(), run.status))
