"""Argument helpers shared by sub-commands: naming a scene, the Gibson data folder, checked numbers,
console output."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from sgplan.datasets import ENV_VAR, SCENES, scene_dir
from sgplan.errors import SceneError
from sgplan.limits import MAX_REACH_RADIUS_M, MAX_ROBOT_RADIUS_M, MAX_SECONDS
from sgplan.scene.model import Building

DEMO = "demo"


def add_scene_arguments(parser: argparse.ArgumentParser, *, positional: bool = False) -> None:
    """Add the scene argument (``SCENE`` or ``--scene``) and ``--data``."""
    help_text = (
        f"scene folder (authors' building.yaml layout, sgplan's format, or a raw .npz), a Gibson scene name "
        f"({', '.join(SCENES)}) looked up under --data, or '{DEMO}' for the embedded demo building"
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
    """The building named by a scene argument (see :func:`add_scene_arguments`)."""
    from sgplan.scene.loading import load_scene

    if spec == DEMO:
        from sgplan.scene.demo import demo_building

        return demo_building()
    path = Path(spec).expanduser()
    try:
        exists = path.exists()
    except OSError as error:  # e.g. a parent folder that cannot be searched
        raise SceneError(f"cannot read the scene: {error.strerror or error}", path) from None
    if exists:
        return load_scene(path)
    if spec in SCENES:
        return load_scene(scene_dir(spec, data))
    raise SceneError(f"scene {spec!r} is neither an existing path, a Gibson scene name ({', '.join(SCENES)}) nor '{DEMO}'")


def say(message: str) -> None:
    """Progress and status lines go to stderr, so stdout stays clean for results."""
    print(message, file=sys.stderr, flush=True)


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


def robot_radius(text: str) -> float:
    """argparse type: a robot radius in metres in (0, :data:`MAX_ROBOT_RADIUS_M`]."""
    return _number(text, float, allow_zero=False, maximum=MAX_ROBOT_RADIUS_M,
                   what=f"a radius in metres > 0 and <= {MAX_ROBOT_RADIUS_M:g}")


def reach_radius(text: str) -> float:
    """argparse type: a reach radius in metres in [0, :data:`MAX_REACH_RADIUS_M`]."""
    return _number(text, float, allow_zero=True, maximum=MAX_REACH_RADIUS_M,
                   what=f"a radius in metres >= 0 and <= {MAX_REACH_RADIUS_M:g}")
