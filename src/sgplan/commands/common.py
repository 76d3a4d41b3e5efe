"""Argument helpers shared by sub-commands: naming a scene, the Gibson data folder, console output."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from sgplan.datasets import ENV_VAR, SCENES, scene_dir
from sgplan.errors import SceneError
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
    if path.exists():
        return load_scene(path)
    if spec in SCENES:
        return load_scene(scene_dir(spec, data))
    raise SceneError(f"scene {spec!r} is neither an existing path, a Gibson scene name ({', '.join(SCENES)}) nor '{DEMO}'")


def say(message: str) -> None:
    """Progress and status lines go to stderr, so stdout stays clean for results."""
    print(message, file=sys.stderr, flush=True)
