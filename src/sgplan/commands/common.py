"""Argument helpers shared by sub-commands: naming a scene, the Gibson data folder, the semantics profile,
the reach model, checked numbers and lists, the options every command takes (``--debug``, ``--quiet``,
``--verbose``), and console output through :mod:`logging`."""

from __future__ import annotations

import argparse
import contextlib
import logging
import math
import sys
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sgplan.datasets import ENV_VAR, SCENES
from sgplan.errors import OutputError
from sgplan.limits import MAX_REACH_RADIUS_M, MAX_ROBOT_RADIUS_M, MAX_SECONDS
from sgplan.planning.setups import PROFILE_REACH_MODELS, PROFILES, REACH_MODELS

if TYPE_CHECKING:
    from sgplan.options import PlanOptions
    from sgplan.scene.model import Building

DEMO = "demo"
DEFAULT_PROFILE = "ltlf"
"""The semantics profile of every command (plan, guide, bench): LTL over finite traces, the start cell's
label read. ``--profile authors`` reproduces the authors' C++ (and the paper's numbers) for comparison."""
log = logging.getLogger("sgplan")


def add_scene_arguments(parser: argparse.ArgumentParser, *, positional: bool = False) -> None:
    """Add the scene argument (``SCENE`` or ``--scene``) and ``--data``."""
    help_text = (
        f"scene folder (authors' building.yaml layout, sgplan's format, or a raw .npz); a scene of another "
        "tool, imported on the fly: a Matterport3D .house file, a ROS map.yaml (with rooms.yaml or "
        "<stem>_rooms.yaml beside it) or a Hydra .json (with its labels file beside it); a Gibson scene name "
        f"({', '.join(SCENES)}; any case) looked up under --data; or '{DEMO}' for the embedded demo building"
    )
    if positional:
        parser.add_argument("scene", metavar="SCENE", help=help_text)
    else:
        parser.add_argument("--scene", required=True, metavar="SCENE", help=help_text)
    parser.add_argument(
        "--data", metavar="DIR", default=None,
        help=f"folder holding the Gibson scenes (default: ${ENV_VAR}, else ../shared/datasets/gibson-3dsg)",
    )


def load_scene_arg(spec: str, data: str | None = None) -> Building:
    """The building named by a scene argument (see :func:`add_scene_arguments` and
    :func:`sgplan.load_scene`)."""
    from sgplan.api import load_scene

    return load_scene(spec, data)


def add_profile_argument(parser: argparse.ArgumentParser, *, default: str | None = DEFAULT_PROFILE,
                         extra_help: str = "") -> None:
    """``--profile ltlf|authors`` (any case), the same on every command; default :data:`DEFAULT_PROFILE`."""
    parser.add_argument(
        "--profile",
        type=str.lower,
        choices=PROFILES,
        default=default,
        help=f"semantics: ltlf (default; start label read, missing automaton edges reject) or authors (the "
        "authors' C++ and the paper's numbers: start label not read, missing edges keep the "
        f"state){extra_help}",
    )


def add_reach_model_argument(parser: argparse.ArgumentParser, *, extra_help: str = "") -> None:
    """``--reach-model box|visible`` (any case; default: the profile's), stored as the planning option
    ``reach_model``, the same on every command."""
    defaults = ", ".join(f"{model} under {profile}" for profile, model in PROFILE_REACH_MODELS.items())
    parser.add_argument(
        "--reach-model", dest="reach_model", type=str.lower, choices=REACH_MODELS, default=None,
        help="where an object counts as reached: visible (within the reach radius and in sight: walls "
        f"block) or box (the authors' square window, which reaches through walls); default: the profile's "
        f"({defaults}){extra_help}",
    )


def plan_options(args: argparse.Namespace, **fixed: Any) -> PlanOptions:
    """The planning options (:class:`sgplan.PlanOptions`) a command's arguments give: every option the
    command has an argument for under the option's own name (``--robot-radius`` stores ``robot_radius_m``)
    and the user gave, then ``fixed`` ones; checked as the API checks them."""
    from sgplan.options import PlanOptions

    given = {name: value for name in PlanOptions.names() if (value := getattr(args, name, None)) is not None}
    return PlanOptions(**(given | fixed))


def add_axes_argument(parser: argparse.ArgumentParser | argparse._ArgumentGroup) -> None:
    """``--axes metres|cells``: what the pictures' axes say (:mod:`sgplan.scene.draw_axes`)."""
    parser.add_argument("--axes", choices=("metres", "cells"), default="metres",
                        help="pictures' axes: metres in the map frame (x right, y up, as RViz shows it; "
                        "default) or the grid's rows and columns (to read off a --start ROW,COL,FLOOR)")


def split_list(values: Iterable[str] | None) -> list[str] | None:
    """The items of a list option given space- or comma-separated (``--scenes a b`` = ``--scenes a,b``)."""
    if values is None:
        return None
    return [item for value in values for item in (part.strip() for part in value.split(",")) if item]


def add_common_options(parser: argparse.ArgumentParser, *, top: bool) -> None:
    """``--debug``, ``--quiet``, ``--verbose``: on the top-level parser (``top``) and again on every
    sub-command, where they default to "not given" so ``sgplan plan --debug`` and ``sgplan --debug plan``
    mean the same."""
    defaults = {"default": False} if top else {"default": argparse.SUPPRESS}
    group = parser.add_argument_group("output") if top else parser
    group.add_argument("--debug", action="store_true", help="show tracebacks for sgplan errors", **defaults)
    group.add_argument("--quiet", "-q", action="store_true", help="print only results, warnings and errors",
                       **defaults)
    group.add_argument("--verbose", "-v", action="store_true", help="also print debugging detail", **defaults)


def configure_logging(args: argparse.Namespace) -> None:
    """Progress and status lines go to stderr through the ``sgplan`` logger, so stdout stays clean for
    results: INFO and above by default, WARNING and above with ``--quiet``, everything with ``--verbose``."""
    level = logging.WARNING if args.quiet else logging.DEBUG if args.verbose else logging.INFO
    handler = _StderrHandler()
    handler.setFormatter(logging.Formatter("%(message)s"))
    log.handlers[:] = [handler]
    log.setLevel(level)
    log.propagate = False


class _StderrHandler(logging.StreamHandler):
    """Writes to whatever ``sys.stderr`` is when a line is logged (tests and callers may swap it)."""

    def emit(self, record: logging.LogRecord) -> None:
        self.stream = sys.stderr
        super().emit(record)


def say(message: str) -> None:
    """A progress or status line (logged at INFO on the ``sgplan`` logger: stderr, hidden by ``--quiet``)."""
    log.info(message)


def _number(text: str, kind: type, *, allow_zero: bool, what: str, maximum: float = math.inf) -> float:
    try:
        value = kind(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not {what}") from None
    if not math.isfinite(value) or value < 0 or (value == 0 and not allow_zero) or value > maximum:
        raise argparse.ArgumentTypeError(f"{text!r} is not {what}")
    return value


def positive_int(text: str) -> int:
    """argparse type: an integer >= 1."""
    return int(_number(text, int, allow_zero=False, what="a whole number >= 1"))


def non_negative_int(text: str) -> int:
    """argparse type: an integer >= 0."""
    return int(_number(text, int, allow_zero=True, what="a whole number >= 0"))


def positive_number(text: str) -> float:
    """argparse type: a finite number > 0."""
    return _number(text, float, allow_zero=False, what="a finite number > 0")


def positive_seconds(text: str) -> float:
    """argparse type: a number of seconds in (0, :data:`MAX_SECONDS`]."""
    return _number(text, float, allow_zero=False, maximum=MAX_SECONDS,
                   what=f"a number of seconds > 0 and <= {MAX_SECONDS:g}")


def non_negative_metres(text: str) -> float:
    """argparse type: a finite number of metres >= 0."""
    return _number(text, float, allow_zero=True, what="a finite number of metres >= 0")


def robot_radius(text: str) -> float:
    """argparse type: a robot radius in metres in [0, :data:`MAX_ROBOT_RADIUS_M`] (0: a point robot, no
    inflation; the same bounds as a scene file's)."""
    return _number(text, float, allow_zero=True, maximum=MAX_ROBOT_RADIUS_M,
                   what=f"a radius in metres >= 0 and <= {MAX_ROBOT_RADIUS_M:g}")


def reach_radius(text: str) -> float:
    """argparse type: a reach radius in metres in (0, :data:`MAX_REACH_RADIUS_M`] (0 would reach nothing)."""
    return _number(text, float, allow_zero=False, maximum=MAX_REACH_RADIUS_M,
                   what=f"a radius in metres > 0 and <= {MAX_REACH_RADIUS_M:g}")


def write_json_record(target: str | None, record: dict[str, Any]) -> None:
    """Write a command's JSON record to ``target`` (a file, atomically; ``-``: stdout; ``None``: nowhere)."""
    if not target:
        return
    from sgplan.outputs.jsontext import record_json

    text = record_json(record)
    if target == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    from sgplan.result import write_text

    say(f"wrote {write_text(target, text)}")


@contextlib.contextmanager
def holding_draw_folder(args: argparse.Namespace) -> Iterator[None]:
    """Hold the command's ``--draw`` folder (if it has one) for the whole command, from before any work:
    a second process drawing into the same folder meanwhile is refused at its start, naming the first
    (:func:`sgplan.files.claim_folder`), instead of both silently overwriting each other's drawings.

    Raises
    ------
    OutputError
        The folder is held by another process, or cannot be made.
    """
    folder = getattr(args, "draw", None)
    with contextlib.ExitStack() as held:
        if folder:
            from sgplan.files import FolderInUse, claim_folder

            try:
                held.enter_context(claim_folder(Path(folder)))
            except FolderInUse as busy:
                holder = busy.holder_pid or "unknown"
                raise OutputError(
                    f"--draw {folder}: another sgplan process (pid {holder}) is drawing into this folder "
                    "now; wait for it to finish or choose another --draw folder"
                ) from None
            except OSError as error:
                reason = "it is a file" if isinstance(error, FileExistsError) else error.strerror or error
                raise OutputError(f"--draw {folder}: cannot use this folder: {reason}") from None
        yield
