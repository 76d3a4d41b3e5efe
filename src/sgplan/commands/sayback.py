"""Saying back what will be planned, for the commands that plan or translate.

Three small steps, each one call from a command: :func:`say_back` prints the mission's explanation
(and asks, with ``--confirm``), :func:`check_folder_fits` refuses a mission folder made for another
scene, :func:`check_before_planning` runs the scene-aware checks that need no start. Each stores
what it found in the command's JSON record when one is given.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from sgplan.commands.common import say
from sgplan.errors import ConfirmationError

if TYPE_CHECKING:
    from sgplan.api import Session
    from sgplan.explain import Explanation
    from sgplan.explain.checks import SceneCheck
    from sgplan.mission import Mission
    from sgplan.scene.model import Building


def say_back(mission: Mission, building: Building, record: dict[str, Any] | None = None, *,
             confirm: bool = False, ask: Callable[[str], str] | None = None,
             stream: TextIO | None = None, session: Session | None = None,
             reach_radius_m: float | None = None, reach_model: str | None = None) -> Explanation:
    """Print the explanation of ``mission`` (to ``stream``, default stdout), store it as
    ``record["explanation"]``, and with ``confirm`` ask before going on (``ask``: default ``input`` on a
    terminal). With ``session`` (of ``building``), where the propositions hold is kept there for the plan;
    objects are reached within ``reach_radius_m`` (default the scene's) under ``reach_model`` (the plan's;
    default :func:`~sgplan.explain.explain_mission`'s).

    Raises
    ------
    ConfirmationError
        ``confirm`` without a terminal to ask on (it never blocks), or an answer other than yes.
    """
    from sgplan.explain import explain_mission

    explanation = explain_mission(mission, building, reach_radius_m=reach_radius_m, reach_model=reach_model,
                                  cells=None if session is None else session.proposition_cells)
    print(explanation.text, file=stream or sys.stdout, flush=True)
    if record is not None:
        record["explanation"] = explanation.to_dict()
    if confirm:
        _confirm(ask)
    return explanation


def _confirm(ask: Callable[[str], str] | None) -> None:
    if ask is None:
        if not (sys.stdin.isatty() and sys.stderr.isatty()):
            raise ConfirmationError(
                "--confirm asks before planning, but there is no terminal to ask on; run it in a terminal, "
                "or leave out --confirm (the explanation is printed and recorded either way)"
            )
        ask = input
    try:
        answer = ask("Plan this mission? [y/N] ")
    except EOFError:
        answer = ""
    if answer.strip().lower() not in ("y", "yes"):
        raise ConfirmationError("not planned: the mission was not confirmed")


def check_folder_fits(folder: str | Path, mission: Mission, building: Building, *, force: bool = False,
                      record: dict[str, Any] | None = None) -> None:
    """Refuse a mission folder made for another scene (see
    :func:`sgplan.mission.identity.ensure_folder_fits_scene`); with ``force`` say so and go on."""
    from sgplan.mission.identity import ensure_folder_fits_scene

    fit = ensure_folder_fits_scene(folder, mission.propositions, building, force=force)
    for note in fit.notes:
        say(f"note: {note}")
    if record is not None:
        record["scene_fit"] = {
            "checked_through": fit.source, "mismatches": list(fit.mismatches), "forced": force,
        }


def check_before_planning(mission: Mission, building: Building, record: dict[str, Any] | None = None, *,
                          stop: bool = True) -> SceneCheck:
    """Run the start-independent scene checks (:func:`sgplan.explain.checks.check_mission_in_scene`) on a
    mission about to be saved or planned, say the findings (:meth:`SceneCheck.report`: with ``stop`` the
    first error is raised, without it said as a warning) and store them as ``record["scene_check"]``."""
    from sgplan.explain.checks import check_mission_in_scene

    check = check_mission_in_scene(mission, building)
    if record is not None:
        record["scene_check"] = check.to_dict()
    check.report(stop=stop)
    return check
