"""The one way tests reach the data beside the checkout (``../shared``): the Gibson scenes and the example
files of other tools. Each accessor skips the calling test, with the reason, where the data is absent (a
clone without ``../shared``, the newcomer's case), so no test fails for want of data.

Call them inside a test (or a fixture), never at import or collection time.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest

from sgplan.datasets import find_gibson_root
from sgplan.scene.model import Building

EXAMPLES = Path(__file__).resolve().parents[1] / ".." / "shared" / "datasets" / "scene-examples"
"""The example files of other tools (a Hydra scene graph, a Matterport3D house); see its README."""

NO_GIBSON = "Gibson data not found (set SGPLAN_GIBSON_DIR or place ../shared beside the repo)"


def gibson_root() -> Path:
    """The Gibson data folder; skips the test when it is absent."""
    root = find_gibson_root()
    if root is None:
        pytest.skip(NO_GIBSON)
    return root


@cache
def _gibson_building(scene: str, root: Path) -> Building:
    from sgplan.scene.authors import load_authors_scene

    return load_authors_scene(root / scene)


def scene_building(scene: str) -> Building:
    """``"demo"`` (the embedded demo building, always there) or a Gibson scene by name, loaded once per
    test session; a Gibson scene skips the test when the data is absent."""
    if scene == "demo":
        from sgplan.scene.demo import demo_building

        return demo_building()
    return _gibson_building(scene, gibson_root())


def scene_example(name: str) -> Path:
    """The example file ``name`` of ``../shared/datasets/scene-examples``; skips the test when absent."""
    path = EXAMPLES / name
    if not path.is_file():
        pytest.skip(f"{name} is not in ../shared/datasets/scene-examples (a clone without the data)")
    return path
