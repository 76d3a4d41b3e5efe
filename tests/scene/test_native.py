"""sgplan's native scene format: round trips and bad input."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from sgplan.errors import SceneError
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.gibson_npz import load_gibson_npz
from sgplan.scene.model import Building
from sgplan.scene.native import read_native_scene, write_native_scene

from .synthetic import assert_same_building, synthetic_scene


@pytest.fixture
def tiny(tmp_path: Path) -> Building:
    return load_authors_scene(synthetic_scene().write(tmp_path / "authors"))


def test_round_trip_synthetic(tmp_path: Path, tiny: Building) -> None:
    folder = write_native_scene(tiny, tmp_path / "native")
    assert sorted(p.name for p in folder.iterdir()) == ["rasters.npz", "scene.json"]
    again = read_native_scene(folder)
    assert_same_building(tiny, again)
    assert again.source == folder
    assert again.room(uuid=2).connected_room_uuids == (4, 5)
    # reading the JSON file itself works too, and a second write is byte-identical
    assert_same_building(tiny, read_native_scene(folder / "scene.json"))
    write_native_scene(again, tmp_path / "second")
    assert (tmp_path / "second" / "scene.json").read_bytes() == (folder / "scene.json").read_bytes()


def test_document_shape(tmp_path: Path, tiny: Building) -> None:
    document = json.loads((write_native_scene(tiny, tmp_path / "native") / "scene.json").read_text())
    assert (document["format"], document["version"], document["rasters"]) == (
        "sgplan-scene", 1, "rasters.npz",
    )
    floor = document["floors"][0]
    assert floor["grid_shape"] == [12, 16] and floor["up_stairs"]["portal"] == [6, 2]
    assert [r["id"] for r in floor["rooms"]] == [1, 2, 3]
    with np.load(tmp_path / "native" / "rasters.npz") as arrays:
        assert sorted(arrays.files) == ["cat_map_0", "cat_map_1", "door_cells", "room_map_0", "room_map_1"]
        assert arrays["door_cells"].tolist()[:2] == [[1, 2, 1, 8], [1, 2, 2, 8]]


def test_round_trip_graph_without_rasters(tmp_path: Path, tiny: Building) -> None:
    for floor in tiny.floors:
        floor.cat_map = floor.room_map = np.zeros((0, 0), np.int16)
        floor.up_stairs = floor.down_stairs = None
        floor.ground_z_m = float("nan")
    for room in tiny.rooms():
        room.door_cells = {}
    folder = write_native_scene(tiny, tmp_path / "native")
    assert not (folder / "rasters.npz").exists()
    again = read_native_scene(folder)
    assert_same_building(tiny, again)
    assert not again.floors[0].has_maps


@pytest.mark.gibson
def test_round_trip_gibson(gibson_root: Path, tmp_path: Path) -> None:
    for building in (
        load_authors_scene(gibson_root / "Benevolence"),
        load_gibson_npz(gibson_root / "3DSceneGraph_Allensville.npz"),
    ):
        folder = write_native_scene(building, tmp_path / building.name)
        assert_same_building(building, read_native_scene(folder))


Edit = Callable[[Path], None]


def _doc(change: Callable[[dict], object]) -> Edit:
    """An edit of the written scene.json document."""

    def edit(folder: Path) -> None:
        document = json.loads((folder / "scene.json").read_text())
        change(document)
        (folder / "scene.json").write_text(json.dumps(document))

    return edit


def _edit_npz(**changes: object) -> Edit:
    def edit(folder: Path) -> None:
        with np.load(folder / "rasters.npz") as archive:
            arrays = {key: archive[key] for key in archive.files}
        arrays.update(changes)
        np.savez_compressed(folder / "rasters.npz", **arrays)

    return edit


def _room(document: dict, floor: int = 0, index: int = 0) -> dict:
    return document["floors"][floor]["rooms"][index]


BAD: dict[str, tuple[Edit, str, str]] = {
    # edit of the written folder, file the message starts with, pattern
    "other format": (
        _doc(lambda d: d.update(format="x")), "scene.json", r"scene: not an sgplan-scene document",
    ),
    "newer version": (_doc(lambda d: d.update(version=9)), "scene.json", r"version 9 is newer"),
    "missing field": (
        _doc(lambda d: _room(d).pop("uuid")), "scene.json", r"room 1 \(floor 0\): missing field 'uuid'",
    ),
    "non-numeric": (
        _doc(lambda d: _room(d)["objects"][0].update(size_m=[1, "big", 2])),
        "scene.json",
        r"object 7 \(room 1\): field 'size_m' must be a list of 3",
    ),
    "floor index": (
        _doc(lambda d: d["floors"][1].update(index=3)), "scene.json", r"floor 1: field 'index' is 3",
    ),
    "bad connection": (
        _doc(lambda d: _room(d).update(connected_room_uuids=[4, 6])),
        "scene.json",
        r"room 1: connection \(id 3, uuid 6\) does not name a room",
    ),
    "stairs room": (
        _doc(lambda d: d["floors"][0]["up_stairs"].update(room_uuid=2)),
        "scene.json",
        r"floor 0: stairs \(room id 3, uuid 2\) do not name a room",
    ),
    "duplicate uuid": (
        _doc(lambda d: _room(d, 1).update(uuid=2)),
        "scene.json",
        r"room 4 and room 1 share uuid 2",
    ),
    "missing rasters file": (
        lambda f: (f / "rasters.npz").unlink(),
        "scene.json",
        r"field 'rasters' names .*rasters.npz, which does not exist",
    ),
    "raster shape": (
        _edit_npz(cat_map_1=np.zeros((12, 15), np.int16)),
        "rasters.npz",
        r"array 'cat_map_1' is int16 \(12, 15\), expected int16 \(12, 16\)",
    ),
    "raster dtype": (_edit_npz(room_map_0=np.zeros((12, 16))), "rasters.npz", r"'room_map_0' is float64"),
    "undeclared object": (
        _edit_npz(cat_map_0=np.full((12, 16), 99, np.int16)),
        "rasters.npz",
        r"floor 0's rasters hold object id\(s\) \[99\]",
    ),
    "pickled array": (
        _edit_npz(door_cells=np.array([{"a": 1}], dtype=object)),
        "rasters.npz",
        r"not a readable npz of plain arrays",
    ),
    "door off grid": (
        _edit_npz(door_cells=np.array([[1, 2, 40, 0]], np.int32)),
        "rasters.npz",
        r"door cells of room 1 towards room 2 are off the grid",
    ),
    "corrupt npz": (
        lambda f: (f / "rasters.npz").write_bytes(b"PK\x03\x04 broken"),
        "rasters.npz",
        r"not a readable npz",
    ),
    "invalid json": (
        lambda f: (f / "scene.json").write_text("{"),
        "scene.json",
        r"invalid JSON at line 1",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_native_scene(tmp_path: Path, tiny: Building, case: str) -> None:
    edit, file, pattern = BAD[case]
    folder = write_native_scene(tiny, tmp_path / "native")
    edit(folder)
    with pytest.raises(SceneError, match=pattern) as caught:
        read_native_scene(folder)
    assert str(caught.value).startswith(str(folder / file))


def test_missing_paths(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match=r"nowhere: scene path does not exist"):
        read_native_scene(tmp_path / "nowhere")
    with pytest.raises(SceneError, match=r"scene folder has no scene.json"):
        read_native_scene(tmp_path)
