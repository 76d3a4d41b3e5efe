"""The raw 3D Scene Graph npz reader: safe unpickling, uuid assignment, and agreement with building.yaml."""

from __future__ import annotations

import io
import os
import zipfile
from pathlib import Path

import numpy as np
import pytest

from sgplan.errors import SceneError
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.gibson_npz import load_gibson_npz, read_scene_graph_dict


def _room(room_id: int, floor: str, category: str) -> dict:
    return {
        "id": room_id, "floor_number": floor, "scene_category": category,
        "location": np.array([1.0, 2.0, 0.5]), "size": np.array([3.0, 4.0, 2.5]), "volume": 30.0,
        "floor_area": 12.0, "parent_building": 77,
    }


def _object(object_id: int, room_id: int, name: str) -> dict:
    return {
        "id": object_id, "class_": name, "parent_room": room_id, "location": np.array([1.0, 2.0, 0.3]),
        "size": np.array([0.5, 0.5, 0.5]), "action_affordance": ["open", "close"],
        "surface_coverage": np.float64(0.4), "material": ["wood", None], "tactile_texture": None,
    }


def _graph() -> dict:
    """Rooms in file order 5 (B), 2 (A), 9 (B), 3 (A); objects 4 (in 2), 1 (in 9)."""
    return {
        "building": {"id": 77, "name": "Mini", "num_floors": 2, "voxel_centers": np.zeros((10, 3))},
        "room": {5: _room(5, "B", "kitchen"), 2: _room(2, "A", "lobby"), 9: _room(9, "B", "bedroom"),
                 3: _room(3, "A", "bathroom")},
        "object": {4: _object(4, 2, "chair"), 1: _object(1, 9, "bed")},
        "camera": {0: {"name": "cam", "pose": np.eye(4)}},
    }


def _write_npz(path: Path, value: object) -> Path:
    np.savez_compressed(path, output=np.array(value, dtype=object))
    return path


class _Evil:
    def __init__(self, command: str) -> None:
        self.command = command

    def __reduce__(self) -> tuple:
        return (os.system, (self.command,))


def test_graph_and_uuids(tmp_path: Path) -> None:
    building = load_gibson_npz(_write_npz(tmp_path / "mini.npz", _graph()))
    assert (building.id, building.uuid, building.name) == (77, 1, "Mini")
    # floors by letter; each room takes the next uuid and its floor, when new, the one after it
    assert [(f.index, f.name, f.uuid) for f in building.floors] == [(0, "A", 5), (1, "B", 3)]
    assert [(r.id, r.uuid, r.floor, r.name) for r in building.rooms()] == [
        (2, 4, 0, "lobby"), (3, 7, 0, "bathroom"), (5, 2, 1, "kitchen"), (9, 6, 1, "bedroom"),
    ]
    assert [(o.id, o.uuid, o.room_id, o.room_uuid, o.name) for o in building.objects()] == [
        (4, 8, 2, 4, "chair"), (1, 9, 9, 6, "bed"),
    ]
    assert building.object(uuid=8).action_affordance == ("open", "close")
    assert building.room(id=5).location_m.tolist() == [1.0, 2.0, 0.5]
    floor = building.floors[0]
    assert not floor.has_maps and floor.shape == (0, 0) and floor.up_stairs is None
    assert all(not r.connected_room_ids and not r.door_cells for r in building.rooms())


def test_reading_stops_before_unused_items(tmp_path: Path) -> None:
    graph = _graph()
    graph["camera"] = {0: _Evil("true")}
    path = _write_npz(tmp_path / "mini.npz", graph)
    # the camera item follows the three graph items, so it is never unpickled...
    assert load_gibson_npz(path).name == "Mini"
    assert set(read_scene_graph_dict(path)) == {"building", "room", "object"}
    # ...but reading everything does reach it, and refuses it
    with pytest.raises(SceneError, match=r"references posix.system"):
        read_scene_graph_dict(path, keys=None)


def test_graph_items_last_are_read_fully(tmp_path: Path) -> None:
    graph = _graph()
    reordered = {"camera": graph.pop("camera"), **graph}
    assert load_gibson_npz(_write_npz(tmp_path / "mini.npz", reordered)).name == "Mini"


@pytest.mark.parametrize(
    "payload, forbidden",
    [
        (_Evil("touch pwned"), "posix.system"),
        (eval, "builtins.eval"),
        (zipfile.ZipFile, "zipfile.ZipFile"),
    ],
)
def test_forbidden_globals_are_refused(tmp_path: Path, payload: object, forbidden: str) -> None:
    graph = _graph()
    graph["building"]["name"] = payload
    path = _write_npz(tmp_path / "evil.npz", graph)
    with pytest.raises(SceneError, match=rf"evil.npz: refusing to unpickle: the file references {forbidden}"):
        load_gibson_npz(path)
    assert not (tmp_path / "pwned").exists() and not Path("pwned").exists()


def test_codecs_other_than_latin1_are_refused(tmp_path: Path) -> None:
    # a hand-written protocol-2 pickle: _codecs.encode("x", "zlib_codec")
    pickled = b"\x80\x02c_codecs\nencode\nq\x00X\x01\x00\x00\x00xX\n\x00\x00\x00zlib_codecq\x01\x86R."
    header = io.BytesIO()
    np.lib.format.write_array_header_1_0(header, {"descr": "|O", "fortran_order": False, "shape": ()})
    path = tmp_path / "codec.npz"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("output.npy", header.getvalue() + pickled)
    with pytest.raises(
        SceneError, match=r"codec.npz: corrupt pickle in output.npy: .*only admitted for latin1"
    ):
        load_gibson_npz(path)


def test_truncated_and_corrupt_files(tmp_path: Path) -> None:
    whole = _write_npz(tmp_path / "whole.npz", _graph()).read_bytes()
    (tmp_path / "cut.npz").write_bytes(whole[: len(whole) // 2])
    with pytest.raises(SceneError, match=r"cut.npz: not a readable npz \(corrupt or truncated\)"):
        load_gibson_npz(tmp_path / "cut.npz")
    (tmp_path / "noise.npz").write_bytes(np.random.default_rng(0).bytes(4096))
    with pytest.raises(SceneError, match=r"noise.npz: not a readable npz"):
        load_gibson_npz(tmp_path / "noise.npz")
    # a valid zip whose pickle stream is cut short
    uncompressed = tmp_path / "plain.npz"
    np.savez(uncompressed, output=np.array(_graph(), dtype=object))
    with zipfile.ZipFile(uncompressed) as archive:
        data = archive.read("output.npy")
    with zipfile.ZipFile(tmp_path / "short.npz", "w") as archive:
        archive.writestr("output.npy", data[:300])
    with pytest.raises(SceneError, match=r"short.npz: "):
        load_gibson_npz(tmp_path / "short.npz")


def test_wrong_content(tmp_path: Path) -> None:
    np.savez(tmp_path / "numbers.npz", output=np.zeros(3))
    with pytest.raises(
        SceneError, match=r"numbers.npz: corrupt pickle .* got dtype float64 and shape \(3,\)"
    ):
        load_gibson_npz(tmp_path / "numbers.npz")
    np.savez(tmp_path / "other.npz", scene=np.zeros(3))
    with pytest.raises(SceneError, match=r"other.npz: npz has no 'output' array"):
        load_gibson_npz(tmp_path / "other.npz")
    _write_npz(tmp_path / "list.npz", [1, 2])
    with pytest.raises(SceneError, match=r"list.npz: corrupt pickle .* got dtype object and shape \(2,\)"):
        load_gibson_npz(tmp_path / "list.npz")
    with pytest.raises(
        SceneError, match=r"absent.npz: cannot read the raw scene graph file: it does not exist"
    ):
        load_gibson_npz(tmp_path / "absent.npz")


@pytest.mark.parametrize(
    "edit, pattern",
    [
        (lambda g: g["object"][1].update(parent_room=42), r"object 1: parent_room 42 is not a room"),
        (lambda g: g["room"][5].update(floor_number=2), r"room 5: field 'floor_number' must be a string"),
        (
            lambda g: g["room"][5].update(location=np.zeros(2)),
            r"room 5: field 'location' must be a list of 3",
        ),
        (lambda g: g["room"][5].update(id=6), r"room 5: field 'id' is 6 but the node is keyed 5"),
        (lambda g: g.pop("object"), r"has no \['object'\] item"),
        (lambda g: g["building"].pop("name"), r"building: missing field 'name'"),
    ],
)
def test_bad_fields(tmp_path: Path, edit, pattern: str) -> None:
    graph = _graph()
    edit(graph)
    with pytest.raises(SceneError, match=pattern):
        load_gibson_npz(_write_npz(tmp_path / "bad.npz", graph))


@pytest.mark.gibson
@pytest.mark.parametrize("scene", ["Allensville", "Benevolence", "Collierville"])
def test_gibson_npz_matches_building_yaml(gibson_root: Path, scene: str) -> None:
    graph = load_gibson_npz(gibson_root / f"3DSceneGraph_{scene}.npz")
    authors = load_authors_scene(gibson_root / scene)
    assert (graph.id, graph.name) == (authors.id, authors.name)
    assert [(f.index, f.name, f.uuid) for f in graph.floors] == [
        (f.index, f.name, f.uuid) for f in authors.floors
    ]

    def rooms(b):
        return sorted(
            (r.uuid, r.id, r.name, r.floor, tuple(r.location_m), tuple(r.size_m)) for r in b.rooms()
        )

    def objects(b):
        return sorted(
            (o.uuid, o.id, o.name, o.room_id, o.room_uuid, o.action_affordance) for o in b.objects()
        )

    assert rooms(graph) == rooms(authors)
    assert objects(graph) == objects(authors)
