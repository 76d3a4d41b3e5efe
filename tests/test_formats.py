"""sgplan.formats.load_scene picks the reader by what the path is (sgplan's, the authors', an importer's)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sgplan.errors import SceneError
from sgplan.formats import load_scene
from sgplan.scene.native import write_native_scene

from .scene.synthetic import assert_same_building, synthetic_scene


def test_dispatch(tmp_path: Path) -> None:
    authors = synthetic_scene().write(tmp_path / "authors")
    building = load_scene(authors)
    assert_same_building(building, load_scene(authors / "building.yaml"))
    native = write_native_scene(building, tmp_path / "native")
    assert_same_building(building, load_scene(native))
    assert_same_building(building, load_scene(native / "scene.json"))
    graph = {
        "building": {"id": 3, "name": "Raw"},
        "room": {1: {"id": 1, "floor_number": "A", "scene_category": "lobby", "location": [0, 0, 0],
                     "size": [1, 1, 1]}},
        "object": {},
    }
    np.savez(tmp_path / "raw.npz", output=np.array(graph, dtype=object))
    raw = load_scene(tmp_path / "raw.npz")
    assert raw.name == "Raw" and not raw.floors[0].has_maps


def test_unknown_paths(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match=r"missing: scene path does not exist"):
        load_scene(tmp_path / "missing")
    with pytest.raises(SceneError, match=r"not a scene: expected a folder holding building.yaml"):
        load_scene(tmp_path)
    (tmp_path / "notes.txt").write_text("hello")
    with pytest.raises(SceneError, match=r"notes.txt: not a scene"):
        load_scene(tmp_path / "notes.txt")


@pytest.mark.gibson
def test_gibson_paths(gibson_root: Path) -> None:
    assert load_scene(gibson_root / "Allensville").floors[0].has_maps
    assert load_scene(gibson_root / "3DSceneGraph_Allensville.npz").name == "Allensville"
