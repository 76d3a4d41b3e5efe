"""The mission arguments of the commands that plan or judge a mission (``plan``, ``monitor``): a mission
folder, a formula, or natural language translated with ``--llm``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from sgplan.commands.common import say
from sgplan.commands.translate import backend_note, open_backends_from_args
from sgplan.english import count
from sgplan.errors import MissionError, SgplanError

if TYPE_CHECKING:
    from sgplan.llm.backends import Backends
    from sgplan.mission import Mission
    from sgplan.scene.model import Building
    from sgplan.starts import StartSpec


def add_mission_arguments(parser: argparse.ArgumentParser) -> None:
    """``--mission-dir`` | ``--formula`` | ``--text`` (one required) and ``--aps``."""
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument(
        "--mission-dir", metavar="DIR",
        help="mission folder (automaton.aut, ap_desc.yaml, llm_heuristic.yaml)",
    )
    what.add_argument("--formula", metavar="F", help="LTL formula: token list, Spot infix or LBT prefix")
    what.add_argument(
        "--text", metavar="MISSION", help="the mission in natural language (translated with --llm)"
    )
    parser.add_argument(
        "--aps", metavar="FILE", help="ap_desc.yaml giving the formula's proposition names a meaning"
    )


def mission_from_args(args: argparse.Namespace, building: Building, start: StartSpec,
                      save_to: str | None = None) -> tuple[Mission, Backends | None]:
    """The mission of ``--mission-dir`` (read with ``args.profile``), ``--formula`` or ``--text``
    (translated by the ``--llm`` backends, the offline translator told the floor of ``start``; with
    ``save_to``, the mission folder is written there), and the backends opened for it (``None`` unless
    ``--text``)."""
    import sgplan

    for option, value in (
        ("--mission-dir", args.mission_dir), ("--formula", args.formula), ("--text", args.text),
    ):
        if value is not None and not value.strip():
            raise MissionError(f"{option} is empty: give a {option[2:].replace('-dir', ' folder')}")
    if args.mission_dir is not None:
        _check_mission_dir(args.mission_dir)
        return sgplan.load_mission(args.mission_dir, profile=args.profile), None
    if args.formula is not None:
        return sgplan.mission_from_formula(args.formula, aps=args.aps), None
    backends = _for_start_floor(open_backends_from_args(args), building, start)
    say(f"translating with {backends.translator.name} ({backend_note(backends)})")
    mission = sgplan.mission_from_text(args.text, building, llm=backends, save_to=save_to)
    if save_to:
        say(f"wrote the mission folder {save_to}")
    say(f"formula: {mission.formula} ({count(mission.automaton.num_states, 'automaton state')})")
    return mission, backends


def _for_start_floor(backends: Backends, building: Building, start: StartSpec) -> Backends:
    """``backends`` with the translator told the start's floor, so that *upstairs* / *downstairs* are read
    relative to it by a translator that can (``MissionTranslator.starting_on``; a language model's prompt
    does not carry it)."""
    from dataclasses import replace

    from sgplan.starts import start_floor

    return replace(backends, translator=backends.translator.starting_on(start_floor(building, start)))


def _check_mission_dir(path: str) -> None:
    """Point a Gibson mission folder given by a path that does not exist here (the README's
    ``../shared/...`` from a clone elsewhere) to where the Gibson data sgplan finds holds it."""
    from sgplan.datasets import SCENES, find_gibson_root

    folder = Path(path).expanduser()
    parts = folder.parts
    if folder.exists() or len(parts) < 3 or parts[-3] not in SCENES or parts[-2] != "missions":
        return
    try:
        root = find_gibson_root()
    except SgplanError:
        return
    found = None if root is None else root / parts[-3] / "missions" / parts[-1]
    if found is not None and found.is_dir():
        raise MissionError(f"mission folder does not exist; the Gibson data sgplan finds holds it at {found}",
                           folder)
