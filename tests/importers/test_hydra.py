"""The Hydra importer on scene graphs built here with the spark-dsg API (and the real one when present)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sgplan.errors import SceneError
from sgplan.formats import load_scene
from sgplan.importers.assemble import Settings
from sgplan.importers.hydra import import_dsg
from sgplan.importers.labelspace import read_label_map
from tests.shared_data import scene_example

from .helpers import free_cells, planned_and_exact_cost

dsg = pytest.importorskip("spark_dsg", reason="spark-dsg is not installed here (pip install 'sgplan[hydra]')")

SETTINGS = Settings(resolution_m=0.1, robot_radius_m=0.0, reach_radius_m=0.3)
RADIUS = 0.5
PLACES = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0), (4.0, 0.0), (5.0, 0.0)]
CHAIR = ((1.0, 0.0), (0.4, 0.4, 0.8))  # centre (x, y), box size; it stands on the ground (z = 0)
LAMP = ((4.0, 0.0), (0.3, 0.3, 0.2))  # hangs at 2.4 m


def build_graph(
    path: Path,
    rooms: int = 2,
    objects: bool = True,
    mesh: bool = False,
    upstairs_m: float = 0.0,
    children: bool = True,
) -> Path:
    """Six places in a row, 1 m apart, 0.5 m of free space each; places 0-2 in room 0, 3-5 in room 1.

    ``upstairs_m`` lifts room 1's places by that much (another floor when above the floor gap).
    """
    graph = dsg.DynamicSceneGraph()
    for k, (x, y) in enumerate(PLACES):
        attributes = dsg.PlaceNodeAttributes()
        attributes.position = np.array([x, y, 1.0 + (upstairs_m if k >= 3 else 0.0)])
        attributes.distance = RADIUS
        graph.add_node(dsg.DsgLayers.PLACES, dsg.NodeSymbol("p", k).value, attributes)
        if k:
            graph.insert_edge(dsg.NodeSymbol("p", k - 1).value, dsg.NodeSymbol("p", k).value)
    for r in range(rooms):
        attributes = dsg.RoomNodeAttributes()
        attributes.position = np.array([1.0 + 3 * r, 0.0, 1.0])
        attributes.semantic_label = r
        graph.add_node(dsg.DsgLayers.ROOMS, dsg.NodeSymbol("R", r).value, attributes)
    for k in range(len(PLACES)):
        if rooms and children:
            graph.insert_edge(dsg.NodeSymbol("R", min(k // 3, rooms - 1)).value, dsg.NodeSymbol("p", k).value)
    if objects:
        for k, ((x, y), size, z, label) in enumerate([(*CHAIR, 0.4, 5), (*LAMP, 2.4, 11)]):
            attributes = dsg.ObjectNodeAttributes()
            attributes.semantic_label = label
            attributes.position = np.array([x, y, z])
            attributes.bounding_box = dsg.BoundingBox(
                np.array(size, dtype=np.float32), np.array([x, y, z], dtype=np.float32)
            )
            graph.add_node(dsg.DsgLayers.OBJECTS, dsg.NodeSymbol("O", k).value, attributes)
    if mesh:
        graph.mesh = floor_mesh()
    graph.save(str(path))
    return path


def floor_mesh() -> object:
    """Floor vertices (z = 0) four per 0.1 m cell over x [-0.5, 5.5], y [-0.5, 0.5]; a 0.4 m block at x =
    3."""
    fx, fy = np.meshgrid(np.arange(-0.475, 5.5, 0.05), np.arange(-0.475, 0.5, 0.05), indexing="ij")
    bx, by = np.meshgrid(np.arange(2.825, 3.2, 0.05), np.arange(-0.175, 0.2, 0.05), indexing="ij")
    points = np.concatenate(
        [
            np.column_stack([fx.ravel(), fy.ravel(), np.zeros(fx.size)]),
            np.column_stack([bx.ravel(), by.ravel(), np.full(bx.size, 0.5)]),
        ]
    )
    mesh = dsg.Mesh()
    mesh.set_vertices(np.hstack([points, np.zeros_like(points)]).T)  # rows: x, y, z, r, g, b
    return mesh


def labels(
    tmp_path: Path, text: str = "objects: {5: chair, 11: lamp}\nrooms: {0: kitchen, 1: living room}\n"
) -> object:
    path = tmp_path / "labels.yaml"
    path.write_text(text)
    return read_label_map(path)


def expected_free_cells(res: float) -> int:
    """Cells of a 0.1 m grid within 0.5 m of the row of places, counted by brute force, minus the chair."""
    frame_lo = np.array([0.0 - RADIUS - 0.5, 0.0 - RADIUS - 0.5])
    xs = frame_lo[0] + (np.arange(int(np.ceil((5 + 2 * RADIUS + 1) / res))) + 0.5) * res
    ys = frame_lo[1] + (np.arange(int(np.ceil((2 * RADIUS + 1) / res))) + 0.5) * res
    x, y = np.meshgrid(xs, ys, indexing="ij")
    along = np.clip(x, 0.0, 5.0)  # nearest point of the segment from place 0 to place 5
    free = (x - along) ** 2 + y**2 <= RADIUS**2
    chair = (np.abs(x - CHAIR[0][0]) < 0.2) & (np.abs(y - CHAIR[0][1]) < 0.2)
    return int((free & ~chair).sum())


def test_rooms_objects_floors_and_free_cells(tmp_path: Path) -> None:
    result = import_dsg(build_graph(tmp_path / "g.json"), labels(tmp_path), SETTINGS)
    building = result.building
    kitchen, living = building.rooms_named("kitchen")[0], building.rooms_named("living_room")[0]
    assert kitchen.connected_room_ids == (living.id,)
    assert [o.name for o in kitchen.objects.values()] == ["chair"]
    assert building.num_floors == 1 and building.floors[0].ground_z_m == pytest.approx(0.0)
    assert "lamp" in " ".join(result.notes)  # it hangs above free floor: nothing on the map holds it
    assert free_cells(building) == expected_free_cells(0.1)


def test_planned_cost_matches_the_exact_solver(tmp_path: Path) -> None:
    building = import_dsg(build_graph(tmp_path / "g.json"), labels(tmp_path), SETTINGS).building
    living = building.rooms_named("living_room")[0]
    start = next(c for c in building.initial_cells if building.floors[0].room_map[c[0], c[1]] != living.id)
    cost, exact = planned_and_exact_cost(building, f'F "enter({living.key})"', start)
    assert cost == pytest.approx(exact) and exact > 0.5


def test_rooms_far_apart_in_height_are_floors(tmp_path: Path) -> None:
    result = import_dsg(build_graph(tmp_path / "g.json", upstairs_m=3.0), labels(tmp_path), SETTINGS)
    building = result.building
    assert building.num_floors == 2 and any("not joined" in note for note in result.notes)
    assert [r.name for r in building.floors[1].rooms.values()] == ["living_room"]
    assert len(building.initial_cells) == 2 and {c[2] for c in building.initial_cells} == {0, 1}


def test_mesh_gives_the_free_space(tmp_path: Path) -> None:
    result = import_dsg(build_graph(tmp_path / "g.json", mesh=True), labels(tmp_path), SETTINGS)
    assert any("mesh" in note for note in result.notes)
    # 60 x 10 floor cells, minus the 4 x 4 block the mesh shows and the chair's 4 x 4 footprint
    assert free_cells(result.building) == 600 - 16 - 16


def test_rooms_without_children_take_the_places_nearest_them(tmp_path: Path) -> None:
    building = import_dsg(
        build_graph(tmp_path / "g.json", children=False), labels(tmp_path), SETTINGS
    ).building
    kitchen, living = building.rooms_named("kitchen")[0], building.rooms_named("living_room")[0]
    assert kitchen.connected_room_ids == (living.id,) and free_cells(building) == expected_free_cells(0.1)


def test_unsegmented_scene_is_one_room_with_a_note(tmp_path: Path) -> None:
    result = import_dsg(build_graph(tmp_path / "g.json", rooms=0), labels(tmp_path), SETTINGS)
    assert [r.name for r in result.building.rooms()] == ["room"]
    assert any("no rooms" in note for note in result.notes)
    single = import_dsg(build_graph(tmp_path / "h.json", rooms=1), labels(tmp_path), SETTINGS)
    assert any("single room" in note for note in single.notes)


def test_label_files_in_every_shape(tmp_path: Path) -> None:
    hydra = labels(
        tmp_path,
        "total_semantic_labels: 12\nlabel_names:\n  - {label: 5, name: chair}\n  - {label: 11, name: lamp}\n",
    )
    assert hydra.object_name(5) == "chair" and hydra.room_name(0) == "room"
    flat = labels(tmp_path, "5: dining_table\n")
    assert flat.object_name(5) == "dining table"
    (tmp_path / "l.csv").write_text("id,name\n5,chair\n11,lamp\n")
    assert read_label_map(tmp_path / "l.csv").object_name(11) == "lamp"
    with pytest.raises(SceneError, match="not an integer label"):
        labels(tmp_path, "chair: 5\n")


def test_errors_name_unknown_labels_and_missing_parts(tmp_path: Path) -> None:
    path = build_graph(tmp_path / "g.json")
    with pytest.raises(SceneError, match=r"label\(s\) \[11\]"):
        import_dsg(path, labels(tmp_path, "5: chair\n"), SETTINGS)
    with pytest.raises(SceneError, match="no label file"):
        import_dsg(path, None, SETTINGS)
    empty = dsg.DynamicSceneGraph()
    empty.save(str(tmp_path / "empty.json"))
    with pytest.raises(SceneError, match="places"):
        import_dsg(tmp_path / "empty.json", None, SETTINGS)
    (tmp_path / "bad.json").write_text('{"directed": false, "nodes": [')
    with pytest.raises(SceneError, match="spark-dsg cannot read"):
        import_dsg(tmp_path / "bad.json", None, SETTINGS)


def test_direct_use_with_labels_beside(tmp_path: Path) -> None:
    path = build_graph(tmp_path / "g.json")
    labels(tmp_path)  # writes labels.yaml beside g.json
    assert sorted(r.name for r in load_scene(path).rooms()) == ["kitchen", "living_room"]


def test_real_apartment(tmp_path: Path) -> None:
    real = scene_example("apartment_dsg.json")
    result = import_dsg(real, labels(tmp_path, "5: chair\n11: lamp\n16: table\n"))
    building = result.building
    assert [r.name for r in building.rooms()] == ["room"] and any("single room" in n for n in result.notes)
    assert sorted(o.name for o in building.objects()).count("chair") == 3
    assert free_cells(building) > 10_000
