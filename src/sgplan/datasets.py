"""Where the public Gibson 3D Scene Graph data lives on this machine.

sgplan never ships that data. It is looked up, in order, at an explicit path, at the directory named by
the ``SGPLAN_GIBSON_DIR`` environment variable, then at ``../shared/datasets/gibson-3dsg`` relative to the
current directory and to the source checkout.
"""

from __future__ import annotations

import os
from pathlib import Path

from sgplan.errors import SceneError

ENV_VAR = "SGPLAN_GIBSON_DIR"
SCENES = ("Allensville", "Benevolence", "Collierville")
_RELATIVE = Path("..") / "shared" / "datasets" / "gibson-3dsg"


def find_gibson_root(explicit: str | Path | None = None) -> Path | None:
    """The Gibson data folder (holding ``Allensville/``, ``Benevolence/``, ...), or ``None`` if absent.

    An ``explicit`` path, or the environment variable, that does not exist raises :class:`SceneError`
    rather than falling back silently.
    """
    for given, origin in ((explicit, "the given path"), (os.environ.get(ENV_VAR), f"${ENV_VAR}")):
        if given:
            path = Path(given).expanduser()
            if not path.is_dir():
                raise SceneError(f"Gibson data folder {path} (from {origin}) does not exist")
            return path
    checkout = Path(__file__).resolve().parents[2]
    for base in (Path.cwd(), checkout):
        candidate = (base / _RELATIVE).resolve()
        if candidate.is_dir():
            return candidate
    return None


def scene_dir(name: str, root: str | Path | None = None) -> Path:
    """The folder of one Gibson scene, e.g. ``scene_dir("Benevolence")``; a clear error if absent."""
    base = find_gibson_root(root)
    if base is None:
        raise SceneError(
            f"cannot find the Gibson data for scene {name!r}: set {ENV_VAR} to the folder that holds "
            f"{', '.join(SCENES)} (e.g. ../shared/datasets/gibson-3dsg)"
        )
    path = base / name
    if not path.is_dir():
        raise SceneError(f"no scene {name!r} under {base} (expected one of {', '.join(SCENES)})")
    return path
