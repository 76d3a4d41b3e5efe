"""What the service understood of a mission: translated or parsed once, said back, checked.

:class:`MissionBook` turns a request's text or formula into a :class:`sgplan.mission.Mission` over a
served scene and keeps the last few (with their explanation and start-independent scene checks), so the
page's say-back as one types, the plan that follows and a run made of it translate and explain the
mission once. Missions are values here: nobody changes a kept one (a plan that needs guidance works on a
copy, :func:`sgplan.api.add_guidance`).
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from sgplan.explain.checks import SceneCheck, check_mission_in_scene

if TYPE_CHECKING:
    from sgplan.explain import Explanation
    from sgplan.mission import Mission
    from sgplan.serve.models import ExplainRequest, MissionIn
    from sgplan.serve.scenes import SceneHost


@dataclass(frozen=True)
class Understood:
    """A mission and what the service says back about it: the explanation and the scene checks that
    need no start."""

    mission: Mission
    explanation: Explanation
    checks: SceneCheck

    def record(self, scene: str, checks: SceneCheck | None = None) -> dict[str, Any]:
        """The JSON of ``POST /api/explain`` (:class:`sgplan.serve.models.ExplainResponse`), with
        ``checks`` (default: the start-independent ones)."""
        from sgplan.logic import to_infix

        formula = self.mission.formula
        return {
            "scene": scene,
            "formula": to_infix(formula) if formula is not None else None,
            "propositions": self.mission.descriptions,
            "explanation": self.explanation.text,
            "method": self.explanation.method,
            "scene_check": (checks or self.checks).to_dict(),
            "notes": list(self.mission.notes),
        }


class MissionBook:
    """Missions made from requests, the last ``capacity`` kept by (scene, text or formula, start floor)."""

    def __init__(self, capacity: int = 256) -> None:
        self.capacity = capacity
        self._kept: OrderedDict[tuple[Any, ...], Understood] = OrderedDict()
        self._lock = threading.Lock()
        self.made = 0
        """Missions translated or parsed (not taken from the kept ones)."""

    def understand(self, host: SceneHost, request: MissionIn, start: Any = None) -> Understood:
        """The mission of ``request`` on ``host``'s scene; ``start`` (a start spec) tells the offline
        translator the start's floor (*upstairs*, *downstairs*).

        Raises
        ------
        MissionError, FormulaError, SceneError
            text the translator cannot read (the message names the phrase), a malformed formula, an
            entity the scene lacks.
        """
        from sgplan.starts import start_floor

        floor = start_floor(host.building, start) if request.text is not None else None
        key = (host.name, request.text, request.formula, floor)
        with self._lock:
            if key in self._kept:
                self._kept.move_to_end(key)
                return self._kept[key]
        understood = self._make(host, request, floor)
        with self._lock:
            self._kept[key] = understood
            self.made += 1
            while len(self._kept) > self.capacity:
                self._kept.popitem(last=False)
        return understood

    def _make(self, host: SceneHost, request: MissionIn, floor: int | None) -> Understood:
        from dataclasses import replace

        from sgplan.api import mission_from_formula, mission_from_text
        from sgplan.explain import explain_mission
        from sgplan.llm.backends import open_backends

        building = host.building
        if request.formula is not None:
            mission = mission_from_formula(request.formula, building)
        else:
            assert request.text is not None
            backends = open_backends("offline")
            backends = replace(backends, translator=backends.translator.starting_on(floor))
            mission = mission_from_text(request.text, building, llm=backends)
        explanation = explain_mission(mission, building, cells=host.session.proposition_cells)
        return Understood(mission, explanation, check_mission_in_scene(mission, building))


def checks_from_start(host: SceneHost, understood: Understood, request: ExplainRequest) -> SceneCheck:
    """The scene checks of ``understood`` from the request's start too (the start cell's label, what is
    reachable from it): the grid and labels of the request's radii, from the scene's warm session."""
    from sgplan.starts import start_cell

    assert request.start is not None
    session, options = host.session, request.options
    radii = session.radii(options.robot_radius_m, options.reach_radius_m)
    grid = session.grid(radii.robot_m)
    cell, _ = start_cell(host.building, grid, request.start.spec())
    return check_mission_in_scene(
        understood.mission,
        host.building,
        cell,
        grid=grid,
        labels=session.labels(understood.mission, radii.reach_m),
        profile=options.profile,
    )
