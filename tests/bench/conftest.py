"""A tiny data folder in the Gibson layout (the demo building and three small missions), and one sweep
over it shared by the bench tests."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.api import add_guidance
from sgplan.bench.cases import Grid, discover, expand
from sgplan.bench.executors import LocalExecutor
from sgplan.bench.results import ResultStore
from sgplan.bench.sweep import run_sweep
from sgplan.mission import compile_mission, save_mission_folder
from sgplan.scene.demo import demo_building
from sgplan.scene.native import write_native_scene

SCENE = "demo-house"
MISSIONS = {
    "1": 'F "enter(room_5)"',  # the floor-0 bathroom
    "2": 'F ("reach(object_32)" & F "enter(room_7)")',  # the teddy bear upstairs, then the dining room
    "3": 'F "enter(room_5)" & G !"enter(room_5)"',  # no path satisfies it: unsatisfiable
}
BAD_START = 5
"""Index of an extra initial position at cell (0, 0, 0), which lies in no room: an invalid start."""

SWEEP = [
    Grid(missions=("1",), starts=(0, 1), setups=("ALL", "A*")),
    Grid(missions=("2",), starts=(0,), setups=("ALL",)),
    Grid(missions=("3",), starts=(0,), setups=("ALL",)),
    Grid(missions=("1",), starts=(BAD_START,), setups=("ALL",)),
]
"""Four optimal cases, one unsatisfiable, one invalid start (7 cases, a few seconds on 2 cores)."""


@pytest.fixture(scope="session")
def data_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("bench-data")
    building = demo_building()
    building.initial_cells = [*building.initial_cells, (0, 0, 0)]
    scene = write_native_scene(building, root / SCENE)
    for name, formula in MISSIONS.items():
        guided, _ = add_guidance(compile_mission(formula), building)
        save_mission_folder(guided, scene / "missions" / name)
    return root


@pytest.fixture(scope="session")
def swept(data_dir: Path, tmp_path_factory: pytest.TempPathFactory) -> tuple[list, ResultStore]:
    """The cases of :data:`SWEEP` run with the local executor (2 jobs) into a fresh results folder."""
    cases = expand(discover(data_dir), SWEEP, profile="authors")
    store = ResultStore(tmp_path_factory.mktemp("bench-out"))
    run_sweep(cases, store, LocalExecutor(2, timeout_s=300))
    return cases, store
