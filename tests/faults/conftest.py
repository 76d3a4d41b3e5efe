"""Valid inputs of every format, made once per session; each fault case damages a fresh copy."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.api import add_guidance
from sgplan.mission import compile_mission, save_mission_folder
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.demo import demo_building
from sgplan.scene.native import write_native_scene
from tests.faults.inputs import MISSION_FORMULA, scene_graph_dict, write_npz
from tests.scene.synthetic import synthetic_scene


@pytest.fixture(scope="session")
def templates(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """One valid input of each kind: ``authors`` / ``native`` scene folders, a ``mission`` folder for the
    demo building, a raw scene-graph ``npz``."""
    root = tmp_path_factory.mktemp("fault-templates")
    authors = synthetic_scene().write(root / "authors")
    native = write_native_scene(load_authors_scene(authors), root / "native")
    building = demo_building()
    mission, _ = add_guidance(compile_mission(MISSION_FORMULA), building)
    mission_dir = save_mission_folder(mission, root / "mission")
    npz = root / "3DSceneGraph_Tiny.npz"
    write_npz(npz, scene_graph_dict())
    return {"authors": authors, "native": native, "mission": mission_dir, "npz": npz}
