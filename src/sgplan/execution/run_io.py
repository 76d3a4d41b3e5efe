"""The pieces of a run's JSON-safe form, which :meth:`sgplan.execution.run.Run.to_dict` and
:meth:`~sgplan.execution.run.Run.from_dict` assemble with the options, the changes and amendments, the
robot's cell and automaton state, the monitor's counts and the events: the format and its version, the
scene the run goes on (by reference) and the mission (its automaton as HOA text, its propositions,
formula and guidance)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sgplan.errors import SgplanError
from sgplan.logic import parse_hoa, parse_infix, to_infix, write_hoa
from sgplan.mission import Mission
from sgplan.scene.labels import Proposition
from sgplan.scene.model import Building

if TYPE_CHECKING:
    from sgplan.api import Session

FORMAT = "sgplan-run"
VERSION = 1
"""The ``format`` and ``version`` of a saved run (:meth:`sgplan.execution.run.Run.to_dict`)."""


class RunFileError(SgplanError):
    """Saved run data that cannot be read back (another format or version, another scene)."""


def scene_reference(building: Building) -> str:
    """What :func:`sgplan.load_scene` loads ``building`` from: its folder or file, else its name
    (``demo`` for the embedded demo building)."""
    from sgplan.api import DEMO
    from sgplan.scene.demo import demo_building

    if building.source is not None:
        return str(building.source)
    return DEMO if building.name == demo_building().name else building.name


def mission_to_dict(mission: Mission) -> dict[str, Any]:
    """The mission as JSON-safe data (:func:`mission_from_dict` reads it back, state numbers kept)."""
    guidance = None
    if mission.guidance is not None:
        guidance = [[int(room), int(q), list(calls)] for room, per_state in mission.guidance.items()
                    for q, calls in per_state.items()]
    return {
        "text": mission.text, "grounded_text": mission.grounded_text,
        "formula": to_infix(mission.formula) if mission.formula is not None else None,
        "propositions": {ap: {"kind": p.kind, "uuid": p.uuid, "reach_radius_m": p.reach_radius_m}
                         for ap, p in mission.propositions.items()},
        "automaton": write_hoa(mission.automaton), "guidance": guidance, "notes": list(mission.notes),
    }


def mission_from_dict(data: Mapping[str, Any]) -> Mission:
    """The mission of :func:`mission_to_dict`'s data."""
    guidance: dict[int, dict[int, list[str]]] | None = None
    if data.get("guidance") is not None:
        guidance = {}
        for room, q, calls in data["guidance"]:
            guidance.setdefault(int(room), {})[int(q)] = list(calls)
    propositions = {ap: Proposition(p["kind"], int(p["uuid"]), p.get("reach_radius_m"))
                    for ap, p in data["propositions"].items()}
    formula = parse_infix(data["formula"]) if data.get("formula") else None
    return Mission(automaton=parse_hoa(data["automaton"]), propositions=propositions, formula=formula,
                   text=data.get("text"), grounded_text=data.get("grounded_text"), guidance=guidance,
                   notes=list(data.get("notes") or []))


def saved_session(data: Mapping[str, Any], session: Session | None) -> Session:
    """The session a saved run (:meth:`sgplan.execution.run.Run.to_dict`'s ``data``) goes on: ``session``
    when given, else a new one on the saved scene.

    Raises
    ------
    RunFileError
        ``data`` is not a saved run of this format and version, or ``session`` is on another scene.
    """
    from sgplan.api import Session, load_scene

    if not isinstance(data, Mapping) or data.get("format") != FORMAT:
        raise RunFileError(f"not a saved run (format {FORMAT!r} expected)")
    if data.get("version") != VERSION:
        raise RunFileError(f"saved run version {data.get('version')!r} is not supported (this sgplan reads "
                           f"version {VERSION})")
    if session is None:
        return Session(load_scene(data["scene"]))
    if scene_reference(session.building) != data["scene"] and Path(str(data["scene"])).name != \
            Path(scene_reference(session.building)).name:
        raise RunFileError(f"the run was saved on scene {data['scene']!r}, the session's is "
                           f"{scene_reference(session.building)!r}")
    return session
