"""The public result of planning one mission: :class:`PlanResult` (what :func:`sgplan.plan` returns).

It holds the path and how it was found (status, cost, iterations, timings), the mission it satisfies
(text, formula, propositions), the robot-ready outputs (metric waypoints dense and simplified, the events
along the path) and, when available, a plain-language explanation of the mission. ``to_dict()`` /
``to_json()`` give the one JSON shape sgplan writes (``plan --json``, demo's ``run.json``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from sgplan.english import count
from sgplan.errors import OutputError
from sgplan.outputs.events import Event
from sgplan.outputs.jsontext import finite_or_none, iteration_records, record_json
from sgplan.outputs.robot_files import write_ros_path_yaml, write_waypoints_csv
from sgplan.outputs.waypoints import Waypoint
from sgplan.radii import Radii

if TYPE_CHECKING:
    from sgplan.mission import Mission
    from sgplan.planning.amra import IterationRecord
    from sgplan.scene.grid import OccupancyGrid
    from sgplan.scene.model import Building


@dataclass(eq=False)
class PlanResult:
    """One planned mission.

    Attributes
    ----------
    scene:
        the building's name.
    status:
        ``"optimal"`` (``cost_m`` is the exact optimum), ``"timeout"`` (a budget ran out) or
        ``"cancelled"`` (a cancel flag was set): the best path so far, within ``bound`` times the optimum,
        or no path.
    cost_m:
        path cost in metres (``inf`` without a path).
    bound:
        the suboptimality bound w1*w2 of the last finished iteration (1 when optimal), ``None`` if none
        finished.
    path:
        ``(n, 4)`` int64 ``[row, col, floor, q]`` per cell, start first (``q``: automaton state after the
        cell); ``None`` without a path.
    start, start_from:
        the start cell ``(row, col, floor)`` and how it was chosen (``"room kitchen room_5"``).
    reach_model:
        where an object counted as reached: ``"visible"`` or ``"box"`` (:mod:`sgplan.scene.reach`).
    waypoints, waypoints_simplified:
        the path in metres, every cell / the simplified polyline (see :mod:`sgplan.outputs.waypoints`).
    waypoint_tolerance_m:
        the clearance the simplified polyline may give up at the inflated obstacles' edge (metres; 0 by
        default, :meth:`simplify_waypoints` sets another).
    events:
        propositions becoming true and automaton moves along the path (:mod:`sgplan.outputs.events`).
    verified:
        True when the independent checker accepted the path and its cost, ``None`` when not checked.
    guidance:
        where the LLM-heuristic guidance came from: ``"mission"`` (it carried some) or the name of the
        guide that a setup using guidance asked; ``None`` when there is none.
    explanation:
        the mission in plain English (:func:`sgplan.explain.explain_mission`), said back before planning;
        ``explanation_method`` says how it was read (``"patterns"`` or ``"automaton"``).
    scene_check:
        the findings of the scene-aware checks run before the search (warnings and notes; an error stops
        the plan), as records (:meth:`sgplan.explain.checks.SceneCheck.to_dict`).
    timings:
        seconds: ``prepare_s`` (guidance, grid and labels), ``precompute_s`` (planning domain),
        ``search_s``, ``wall_s`` (the whole call).
    """

    scene: str
    status: str
    setup: str
    profile: str
    reach_model: str
    cost_m: float
    bound: float | None
    path: np.ndarray | None
    start: tuple[int, int, int]
    start_from: str
    radii: Radii
    queues: tuple[str, ...]
    iterations: Sequence[IterationRecord]
    mission_text: str | None
    grounded_text: str | None
    formula: str | None
    propositions: dict[str, str]
    waypoints: list[Waypoint] = field(default_factory=list)
    waypoints_simplified: list[Waypoint] = field(default_factory=list)
    waypoint_tolerance_m: float = 0.0
    events: list[Event] = field(default_factory=list)
    verified: bool | None = None
    guidance: str | None = None
    explanation: str | None = None
    explanation_method: str | None = None
    scene_check: list[dict[str, Any]] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    building: Building | None = field(default=None, repr=False)
    grid: OccupancyGrid | None = field(default=None, repr=False)
    labels: np.ndarray | None = field(default=None, repr=False)
    mission: Mission | None = field(default=None, repr=False)

    @property
    def found(self) -> bool:
        """Whether a path was found."""
        return self.path is not None

    @property
    def cells(self) -> list[tuple[int, int, int]]:
        """The path as ``(row, col, floor)`` cells (empty without a path)."""
        return [] if self.path is None else [(int(r), int(c), int(f)) for r, c, f, _ in self.path.tolist()]

    def summary(self) -> str:
        """One line: status, cost, cells, waypoints, setup."""
        if self.path is None:
            return f"{self.status}: no path (setup {self.setup})"
        along = (f" ({self.waypoints_simplified[-1].cost_m:.4f} m of straight segments)"
                 if len(self.waypoints_simplified) > 1 else "")
        return (f"{self.status}: cost {self.cost_m:.4f} m over {count(len(self.path), 'cell')}, "
                f"{count(len(self.waypoints_simplified), 'simplified waypoint')}{along} (setup {self.setup}, "
                f"{count(len(self.iterations), 'iteration')})")

    def __str__(self) -> str:
        return self.summary()

    def __repr__(self) -> str:
        return f"<PlanResult {self.scene!r} from {self.start} ({self.start_from}) {self.summary()}>"

    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready record (plain dicts, lists, numbers, strings, ``None``; no infinities)."""
        return {
            "scene": self.scene,
            "mission": {
                "text": self.mission_text, "grounded_text": self.grounded_text, "formula": self.formula,
                "propositions": dict(self.propositions),
            },
            "explanation": None
            if self.explanation is None
            else {"text": self.explanation, "method": self.explanation_method},
            "scene_check": list(self.scene_check),
            "start": list(self.start),
            "start_from": self.start_from,
            "setup": self.setup,
            "profile": self.profile,
            "reach_model": self.reach_model,
            "status": self.status,
            "cost_m": finite_or_none(self.cost_m),
            "bound": self.bound,
            "verified": self.verified,
            "guidance": self.guidance,
            "radii": {
                "robot_m": self.radii.robot_m, "reach_m": self.radii.reach_m,
                "robot_from": self.radii.robot_from, "reach_from": self.radii.reach_from,
            },
            "queues": list(self.queues),
            "iterations": iteration_records(self.iterations),
            "path": None if self.path is None else self.path.tolist(),
            "waypoints": [w.to_dict() for w in self.waypoints],
            "waypoints_simplified": [w.to_dict() for w in self.waypoints_simplified],
            "waypoint_tolerance_m": self.waypoint_tolerance_m,
            "events": [e.to_dict() for e in self.events],
            "timings": dict(self.timings),
            "notes": list(self.notes),
        }

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON text in the layout ``plan --json`` writes
        (:func:`sgplan.outputs.jsontext.record_json`: a line per key and per row of the long lists)."""
        return record_json(self.to_dict())

    def write_json(self, path: str | Path) -> Path:
        """Write :meth:`to_json` to ``path`` (folders created); returns the path."""
        return write_text(path, self.to_json())

    def simplify_waypoints(self, tolerance_m: float = 0.0) -> list[Waypoint]:
        """Simplify the path again into :attr:`waypoints_simplified`, letting segments give up
        ``tolerance_m`` metres of clearance at the inflated obstacles' edge (fewer waypoints where the path
        hugs a rounded corner; :func:`sgplan.outputs.waypoints.simplify_path`); returns them.

        Raises
        ------
        OutputError
            without a path, or for a tolerance that is negative or not below the robot radius.
        """
        from sgplan.outputs.waypoints import path_waypoints, simplify_path

        if (self.path is None or self.grid is None or self.labels is None or self.mission is None
                or self.building is None):
            raise OutputError("this result has no path, or no grid, labels, mission and building to simplify")
        keep = simplify_path(self.path, self.grid, self.labels, self.mission.automaton,
                             tolerance_m=tolerance_m, building=self.building)
        self.waypoints_simplified = path_waypoints(self.path, self.grid, self.building, keep)
        self.waypoint_tolerance_m = float(tolerance_m)
        return self.waypoints_simplified

    def write_waypoints_csv(self, path: str | Path, *, simplified: bool = True) -> Path:
        """The (simplified, by default) waypoints as CSV
        (:func:`sgplan.outputs.robot_files.write_waypoints_csv`)."""
        return write_waypoints_csv(self.waypoints_simplified if simplified else self.waypoints, path)

    def write_ros_path_yaml(
        self, path: str | Path, *, simplified: bool = True, frame_id: str = "map"
    ) -> Path:
        """The (simplified) waypoints as ROS ``nav_msgs/Path`` per floor stretch
        (:func:`sgplan.outputs.robot_files.write_ros_path_yaml`)."""
        return write_ros_path_yaml(
            self.waypoints_simplified if simplified else self.waypoints, path, frame_id
        )

    def draw(self, out_dir: str | Path, *, stem: str = "plan_floor", formats: Sequence[str] = ("png", "svg"),
             automaton: bool = True, axes: str = "metres") -> list[Path]:
        """Draw every floor with the path, the mission and the cost into ``out_dir`` (one picture per floor
        and format: PNG and SVG, as ``plan --draw``), and the mission's automaton beside them
        (``automaton.dot`` / ``.svg``, unless ``automaton=False``); returns the files. ``axes`` is
        ``"metres"`` (the map frame) or ``"cells"`` (:func:`sgplan.scene.draw.draw_floor`)."""
        from sgplan.report.automaton import write_automaton
        from sgplan.scene.draw import MissionView, draw_building

        building, mission = self._drawable()
        view = MissionView(
            text=self.mission_text or self.formula, explanation=self.explanation,
            cost_m=self.cost_m if self.path is not None else None,
            propositions=tuple(mission.ordered_propositions), reach_radius_m=self.radii.reach_m,
            reach_model=self.reach_model,
        )
        written = draw_building(building, out_dir, grid=self.grid, path=self.path, mission=view, stem=stem,
                                formats=formats, axes=axes)
        if automaton:
            written += write_automaton(mission.automaton, out_dir, names=mission.descriptions)
        return written

    def write_html(self, path: str | Path) -> Path:
        """Write the self-contained HTML report of this plan
        (:func:`sgplan.report.html.write_html_report`)."""
        from sgplan.report.html import write_html_report

        building, mission = self._drawable()
        return write_html_report(path, building, self.grid, self, mission, explanation=self.explanation,
                                 reach_radius_m=self.radii.reach_m, reach_model=self.reach_model)

    def _drawable(self) -> tuple[Building, Mission]:
        if self.building is None or self.mission is None:
            raise OutputError("this result carries no building and mission to draw (it was built by hand)")
        return self.building, self.mission


def write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8, folders created; an earlier file stays whole if this
    write fails); :class:`OutputError` naming the file on failure."""
    from sgplan.files import write_text_atomically

    target = Path(path).expanduser()
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        write_text_atomically(target, text)
    except OSError as error:
        raise OutputError(f"{target}: cannot write: {error.strerror}") from None
    return target
