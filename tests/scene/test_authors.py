"""The authors' scene-folder loader: a synthetic folder (happy path and every kind of bad input) and the
three Gibson scenes against the counts of reference-algorithm.md §1.1 and §10."""

from __future__ import annotations

import tracemalloc
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from sgplan.errors import SceneError
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.model import CatCode

from .synthetic import SyntheticScene, synthetic_scene


def test_synthetic_scene_loads(tmp_path: Path) -> None:
    folder = synthetic_scene().write(tmp_path / "tiny")
    building = load_authors_scene(folder)
    assert (building.id, building.uuid, building.name, building.source) == (9, 1, "Tiny", folder)
    assert [sorted(f.rooms) for f in building.floors] == [[1, 2, 3], [4]]
    assert building.grid_shape == (12, 16)
    assert (building.robot_radius_m, building.reach_radius_m) == (0.1, 0.3)
    assert building.initial_cells == [(2, 10, 0), (3, 10, 1)]
    kitchen = building.room(uuid=2)
    # uuids are looked up through the ids, not taken index-aligned from connected_room_uuids
    assert kitchen.connected_room_ids == (2, 3)
    assert kitchen.connected_room_uuids == (4, 5)
    assert building.room(id=3).connected_room_uuids == (2, 6)
    assert kitchen.door_cells[2].tolist() == [[1, 8], [2, 8]] and kitchen.door_cells[2].dtype == np.int32
    fridge = building.object(uuid=8)
    assert (fridge.id, fridge.name, fridge.room_id, fridge.room_uuid) == (7, "refrigerator", 1, 2)
    assert fridge.action_affordance == ("open", "close")
    assert building.floor_of_object(building.object(id=8)) == 1
    floor0, floor1 = building.floors
    assert floor0.cat_map.dtype == np.int16 and floor0.room_map.dtype == np.int16
    assert floor0.cat_map[1, 1] == 7 and floor0.cat_map[0, 5] == CatCode.WALL
    assert floor0.cat_map[11, 0] == CatCode.STAIRS_UP and floor1.cat_map[11, 0] == CatCode.STAIRS_DOWN
    assert floor0.room_map[11, 15] == -5 and floor1.room_map[7, 1] == 3
    assert floor0.up_stairs is not None and floor1.down_stairs is not None
    assert (floor0.up_stairs.room_uuid, floor0.up_stairs.portal, floor0.up_stairs.cost_m) == (5, (6, 2), 3.5)
    assert floor1.down_stairs.portal == (6, 5)
    assert floor0.down_stairs is None and floor1.up_stairs is None
    assert floor0.cell_to_xy((0, 0)) == pytest.approx((-0.55, -0.75))
    assert floor1.ground_z_m == 3.0 and floor0.has_maps


def test_building_yaml_path_and_optional_files(tmp_path: Path) -> None:
    scene = synthetic_scene()
    scene.radius_config = scene.initial_positions = None
    folder = scene.write(tmp_path / "tiny")
    building = load_authors_scene(folder / "building.yaml")
    assert building.robot_radius_m is None and building.reach_radius_m is None
    assert building.initial_cells == []


def test_radius_config_is_parsed_not_executed(tmp_path: Path) -> None:
    scene = synthetic_scene()
    scene.radius_config = "ROBOT_RADIUS=$(touch pwned)\n"
    folder = scene.write(tmp_path / "tiny")
    with pytest.raises(SceneError, match=r"radius_config.bash: line 1: ROBOT_RADIUS must be a number"):
        load_authors_scene(folder)
    assert not (folder / "pwned").exists() and not Path("pwned").exists()


Mutation = Callable[[SyntheticScene, Path], None]


def _floor0(scene: SyntheticScene) -> dict:
    return scene.document["floors"][0]


def _kitchen(scene: SyntheticScene) -> dict:
    return _floor0(scene)["rooms"][1]


def _remove_cat_map(scene: SyntheticScene, folder: Path) -> None:
    (folder / "cat_maps" / "1.png").unlink()


def _corrupt_png(scene: SyntheticScene, folder: Path) -> None:
    data = (folder / "room_maps" / "0.png").read_bytes()
    (folder / "room_maps" / "0.png").write_bytes(data[: len(data) // 2])


def _rgb_png(scene: SyntheticScene, folder: Path) -> None:
    Image.new("RGB", (16, 12)).save(folder / "cat_maps" / "0.png")


def _wrong_size(scene: SyntheticScene, folder: Path) -> None:
    Image.fromarray(np.full((12, 15), 5, np.uint8)).save(folder / "room_maps" / "1.png")


def _unknown_object_in_map(scene: SyntheticScene, folder: Path) -> None:
    scene.cat_maps[0][9, 9] = 42
    scene.write(folder)


def _object_of_other_floor_in_map(scene: SyntheticScene, folder: Path) -> None:
    scene.cat_maps[0][9, 9] = 8  # the bed, declared on floor 1
    scene.write(folder)


def _unknown_room_in_map(scene: SyntheticScene, folder: Path) -> None:
    scene.room_maps[1][0, 0] = 2  # the corridor of floor 0
    scene.write(folder)


def _set(path: tuple, value: object) -> Callable[[SyntheticScene], None]:
    def mutate(scene: SyntheticScene) -> None:
        node = scene.document
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value

    return mutate


def _delete(path: tuple) -> Callable[[SyntheticScene], None]:
    def mutate(scene: SyntheticScene) -> None:
        node = scene.document
        for key in path[:-1]:
            node = node[key]
        del node[path[-1]]

    return mutate


KITCHEN = ("floors", 0, "rooms", 1)
FRIDGE = (*KITCHEN, "objects", 7)

# (mutation of the document before writing, pattern the error message must match)
BAD_DOCUMENTS = {
    "room on unknown floor": (
        _set((*KITCHEN, "parent_id"), 5),
        r"room 1 \(floor 0\): parent_id 5 .*unknown floor",
    ),
    "room under wrong floor": (
        _set((*KITCHEN, "parent_id"), 1),
        r"room 1 \(floor 0\): parent_id 1 does not name",
    ),
    "non-numeric location": (
        _set((*KITCHEN, "location"), [1.0, "two", 3.0]),
        r"room 1 .*'location' must be a list of 3",
    ),
    "non-numeric resolution": (
        _set(("floors", 1, "grid_map_resolution"), "fine"),
        r"floor 1: field 'grid_map_resolution'",
    ),
    "boolean id": (_set((*FRIDGE, "uuid"), True), r"object 7 \(room 1\): field 'uuid' must be an integer"),
    "missing field": (_delete((*FRIDGE, "name")), r"object 7 \(room 1\): missing field 'name'"),
    "object parent": (_set((*FRIDGE, "parent_id"), 2), r"object 7 \(room 1\): parent_id 2 is not its room 1"),
    "object key": (_set((*FRIDGE, "id"), 17), r"object 7 \(room 1\): field 'id' is 17"),
    "unknown connection": (_set((*KITCHEN, "connected_room_ids"), [2, 99]), r"unknown room id\(s\) \[99\]"),
    "uuids disagree": (
        _set((*KITCHEN, "connected_room_uuids"), [4, 6]),
        r"connected_room_uuids \[4, 6\] are not",
    ),
    "door off grid": (
        _set((*KITCHEN, "door_grids"), {2: [[1, 80]]}),
        r"door_grids\[2\] cell \[1, 80\] is off",
    ),
    "door unknown room": (
        _set((*KITCHEN, "door_grids"), {12: [[1, 8]]}),
        r"door_grids names unknown room id 12",
    ),
    "bbox off grid": (
        _set((*KITCHEN, "grid_map_max"), [12, 3]),
        r"'grid_map_max' \[12, 3\] is off the 12x16",
    ),
    "floor keys": (_set(("num_floors",), 3), r"building: field 'floors' must be keyed 0..2"),
    "floor id": (_set(("floors", 1, "id"), 4), r"floor 1: field 'id' is 4"),
    "grid sizes differ": (_set(("floors", 1, "grid_map_size"), [12, 17]), r"share one grid_map_size"),
    "duplicate uuid": (_set((*FRIDGE, "uuid"), 6), r"room 4 and object 7 share uuid 6"),
    "stairs mismatch": (
        _set(("floors", 1, "down_stairs_cost"), 3.0),
        r"floor 0's up stairs .* do not match floor 1",
    ),
    "stairs without portal": (
        _set(("floors", 0, "up_stairs_portal"), None),
        r"floor 0: up_stairs_id is 3 but",
    ),
    "stairs unknown room": (
        _set(("floors", 0, "up_stairs_id"), 33),
        r"floor 0: up_stairs_id 33 is not a room",
    ),
    "floors not a mapping": (_set(("floors",), [1, 2]), r"building: field 'floors' must be a mapping"),
}


@pytest.mark.parametrize("case", sorted(BAD_DOCUMENTS))
def test_bad_building_yaml(tmp_path: Path, case: str) -> None:
    mutate, pattern = BAD_DOCUMENTS[case]
    scene = synthetic_scene()
    mutate(scene)
    folder = scene.write(tmp_path / "tiny")
    with pytest.raises(SceneError, match=pattern) as caught:
        load_authors_scene(folder)
    assert str(caught.value).startswith(str(folder / "building.yaml"))


BAD_FILES: dict[str, tuple[Mutation, str, str]] = {
    # (mutation of the written folder, file the message must start with, pattern)
    "missing map file": (
        _remove_cat_map, "building.yaml", r"floor 1: field 'cat_map' names .*1.png, which does not exist",
    ),
    "corrupt png": (_corrupt_png, "room_maps/0.png", r"cannot decode map"),
    "colour png": (_rgb_png, "cat_maps/0.png", r"8-bit grayscale PNG \(mode L\), got mode RGB"),
    "wrong map size": (_wrong_size, "room_maps/1.png", r"map is 12x15 .* floor 1 has grid_map_size 12x16"),
    "unknown object id in map": (
        _unknown_object_in_map, "cat_maps/0.png", r"object id\(s\) \[42\] that floor 0",
    ),
    "object of another floor": (_object_of_other_floor_in_map, "cat_maps/0.png", r"object id\(s\) \[8\]"),
    "unknown room id in map": (_unknown_room_in_map, "room_maps/1.png", r"room id\(s\) \[2\] that floor 1"),
    "invalid yaml": (
        lambda s, f: (f / "building.yaml").write_text("floors: [unclosed\n"),
        "building.yaml",
        r"invalid YAML at line \d+",
    ),
    "bad initial position": (
        lambda s, f: (f / "initial_positions.yaml").write_text("- [2, 10, 0]\n- [2, 10, 2]\n"),
        "initial_positions.yaml",
        r"entry 1 \[2, 10, 2\] is off the grid",
    ),
    "non-numeric initial position": (
        lambda s, f: (f / "initial_positions.yaml").write_text("- [2, x, 0]\n"),
        "initial_positions.yaml",
        r"entry 0 must be \[row, col, floor\] integers",
    ),
    "negative radius": (
        lambda s, f: (f / "radius_config.bash").write_text("OBJECT_REACH_RADIUS=-1\n"),
        "radius_config.bash",
        r"line 1: OBJECT_REACH_RADIUS must be a positive number",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_FILES))
def test_bad_scene_files(tmp_path: Path, case: str) -> None:
    mutate, file, pattern = BAD_FILES[case]
    scene = synthetic_scene()
    folder = scene.write(tmp_path / "tiny")
    mutate(scene, folder)
    with pytest.raises(SceneError, match=pattern) as caught:
        load_authors_scene(folder)
    assert str(caught.value).startswith(str(folder / file))


def test_missing_paths(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match=r"nowhere: scene path does not exist"):
        load_authors_scene(tmp_path / "nowhere")
    (tmp_path / "empty").mkdir()
    with pytest.raises(SceneError, match=r"empty: scene folder has no building.yaml"):
        load_authors_scene(tmp_path / "empty")
    (tmp_path / "other.yaml").write_text("{}")
    with pytest.raises(SceneError, match=r"other.yaml: not an authors' scene"):
        load_authors_scene(tmp_path / "other.yaml")


# -- the Gibson scenes ---------------------------------------------------------------------------------

GIBSON = {
    # rooms per floor, staircases, objects per floor, grid, radii, floor uuids, room uuids, object uuids
    "Allensville": dict(
        rooms=[11], stairs=0, objects=[33], grid=(1017, 927), radii=(0.15, 0.7), floor_uuids=[3],
        room_uuids={2, *range(4, 14)}, object_uuids=set(range(14, 47)),
        portals=[(None, None)], costs=[],
        cells=[(363_193, 144_940, 316_132, 118_494, 0, 0)],
    ),
    "Benevolence": dict(
        rooms=[5, 5, 6], stairs=2, objects=[3, 23, 15], grid=(599, 1085), radii=(0.2, 0.7),
        floor_uuids=[3, 11, 5], room_uuids={2, 4, *range(6, 11), *range(12, 21)},
        object_uuids=set(range(21, 62)),
        portals=[((69, 741), None), ((72, 726), (74, 381)), (None, (86, 397))], costs=[4.4679, 4.2050],
        cells=[
            (152_474, 8_114, 54_766, 426_205, 8_356, 0),
            (286_949, 76_095, 111_825, 153_109, 11_657, 10_280),
            (236_288, 88_142, 119_736, 174_894, 0, 30_855),
        ],
    ),
    "Collierville": dict(
        rooms=[4, 6, 4], stairs=2, objects=[6, 29, 8], grid=(583, 1049), radii=(0.08, 0.5),
        floor_uuids=[9, 3, 5], room_uuids={2, 4, *range(6, 9), *range(10, 19)},
        object_uuids=set(range(19, 62)),
        portals=[((487, 279), None), ((502, 197), (504, 600)), (None, (461, 577))], costs=[4.1787, 4.6494],
        cells=[
            (207_321, 14_206, 88_862, 288_517, 12_661, 0),
            (232_265, 74_117, 115_452, 160_510, 13_698, 15_525),
            (176_596, 85_928, 72_100, 239_129, 0, 37_814),
        ],
    ),
}


@pytest.mark.gibson
@pytest.mark.parametrize("scene", sorted(GIBSON))
def test_gibson_scene(gibson_root: Path, scene: str) -> None:
    expected = GIBSON[scene]
    building = load_authors_scene(gibson_root / scene)
    assert building.name == scene
    assert [len(f.rooms) for f in building.floors] == expected["rooms"]
    assert len(building.rooms_named("staircase")) == expected["stairs"]
    assert [sum(len(r.objects) for r in f.rooms.values()) for f in building.floors] == expected["objects"]
    assert building.grid_shape == expected["grid"]
    assert all(f.cat_map.shape == f.room_map.shape == expected["grid"] for f in building.floors)
    assert (building.robot_radius_m, building.reach_radius_m) == expected["radii"]
    assert len(building.initial_cells) == 5
    assert [f.uuid for f in building.floors] == expected["floor_uuids"]
    assert {r.uuid for r in building.rooms()} == expected["room_uuids"]
    assert {o.uuid for o in building.objects()} == expected["object_uuids"]
    portals = [
        (f.up_stairs.portal if f.up_stairs else None, f.down_stairs.portal if f.down_stairs else None)
        for f in building.floors
    ]
    assert portals == expected["portals"]
    costs = [f.up_stairs.cost_m for f in building.floors if f.up_stairs is not None]
    assert costs == pytest.approx(expected["costs"], abs=1e-4)
    for floor, counts in zip(building.floors, expected["cells"]):
        cat = floor.cat_map
        found = (
            (cat == CatCode.GROUND).sum(), (cat > 0).sum(), (cat == CatCode.WALL).sum(),
            (cat == CatCode.OUTSIDE).sum(), (cat == CatCode.STAIRS_UP).sum(),
            (cat == CatCode.STAIRS_DOWN).sum(),
        )
        assert found == counts
    for room in building.rooms():
        # connections are resolved through ids: each uuid is the uuid of the id at the same position
        assert room.connected_room_uuids == tuple(building.room(id=i).uuid for i in room.connected_room_ids)
        for neighbour, cells in room.door_cells.items():
            assert cells.ndim == 2 and cells.shape[1] == 2 and len(cells) > 0
            assert building.has_room(building.room(id=neighbour).uuid)


@pytest.mark.gibson
def test_benevolence_loads_within_a_memory_bound(gibson_root: Path) -> None:
    """Loading holds well under 1 GB of Python allocations (its speed is measured in
    benchmarks/scene_load.py, not here: a timed test fails on a loaded machine)."""
    load_authors_scene(gibson_root / "Benevolence")  # warm the imports and the file cache
    tracemalloc.start()
    load_authors_scene(gibson_root / "Benevolence")
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert peak < 1 << 30
