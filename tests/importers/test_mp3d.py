"""The Matterport3D .house importer on a small house written here (and the real one when present)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import pytest

from sgplan.errors import SceneError
from sgplan.formats import load_scene
from sgplan.importers.assemble import Settings
from sgplan.importers.mp3d import import_house, read_house
from sgplan.scene.native import read_native_scene, write_native_scene
from tests.shared_data import scene_example

from .helpers import free_cells, planned_and_exact_cost, room_named

SETTINGS = Settings(resolution_m=0.1, robot_radius_m=0.0, reach_radius_m=0.3)


def house_text(door: bool = True, gap_m: float = 0.2, extra: str = "") -> str:
    """Bedroom x [0, 3] and kitchen x [3 + gap, 6], both y [0, 3]; a bed, a ceiling light, maybe a door."""
    x1 = 3.0 + gap_m
    vertices = [(0, 0), (3, 0), (3, 3), (0, 3), (x1, 0), (6, 0), (6, 3), (x1, 3)]
    objects = [
        "O 0 0 1 1 1 0.3  1 0 0  0 1 0  0.5 0.5 0.3  0 0 0 0 0 0 0 0",  # bed, on the floor
        "O 1 1 2 4.5 1.5 2.4  1 0 0  0 1 0  0.3 0.3 0.05  0 0 0 0 0 0 0 0",  # light under the ceiling
    ]
    if door:  # a door in the gap: 0.8 m wide along y, 2 m high, 5 cm thick along x
        objects.append(f"O 2 0 3 {3 + gap_m / 2} 1.5 1.0  0 0 1  0 1 0  1.0 0.4 0.05  0 0 0 0 0 0 0 0")
    lines = [
        "ASCII 1.1",
        f"H - - 0 0 {len(vertices)} 2 0 {len(objects)} 4 2 0 1 0 0 0 0 0 0 0 0 6 3 2.5 0 0 0 0 0",
        "L 0 2 - 3 1.5 0  0 0 0 6 3 2.5 0 0 0 0 0",
        "R 0 0 0 0 b 1.5 1.5 0  0 0 0 3 3 2.5  2.5 0 0 0 0",
        "R 1 0 0 0 k 4.5 1.5 0  3.2 0 0 6 3 2.5  2.5 0 0 0 0",
        "S 0 0 0 F 1.5 1.5 0  0 0 1  0 0 0 3 3 0  0 0 0 0 0",
        "S 1 1 0 F 4.5 1.5 0  0 0 1  3.2 0 0 6 3 0  0 0 0 0 0",
    ]
    lines += [f"V {k} {k // 4} F {x} {y} 0  0 0 1  0 0 0" for k, (x, y) in enumerate(vertices)]
    lines += [
        "C 0 1 wall 1 wall 0 0 0 0 0",
        "C 1 2 bed 11 bed 0 0 0 0 0",
        "C 2 3 light 28 lighting 0 0 0 0 0",
        "C 3 4 door 4 door 0 0 0 0 0",
    ]
    return "\n".join(lines + objects) + "\n" + extra


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "small.house"
    path.write_text(text)
    return path


def test_rooms_walls_door_objects_and_free_cells(tmp_path: Path) -> None:
    result = import_house(write(tmp_path, house_text()), SETTINGS)
    building = result.building
    bedroom, kitchen = room_named(building, "bedroom"), room_named(building, "kitchen")
    assert bedroom.connected_room_ids == (kitchen.id,) and kitchen.connected_room_ids == (bedroom.id,)
    assert [o.name for o in bedroom.objects.values()] == ["bed"]
    assert "light" in " ".join(result.notes) and not kitchen.objects  # the ceiling light blocks nothing
    # 30 x 30 + 28 x 30 floor cells, the door's 2 x 8 cells through the 0.2 m wall, minus the bed's 10 x 10
    assert free_cells(building) == 900 + 840 + 16 - 100
    assert building.initial_cells[0][2] == 0 and len(building.initial_cells) == 2


def test_without_a_door_the_wall_separates_and_a_narrow_gap_is_open(tmp_path: Path) -> None:
    walled = import_house(write(tmp_path, house_text(door=False)), SETTINGS).building
    assert room_named(walled, "bedroom").connected_room_ids == ()
    open_plan = import_house(write(tmp_path, house_text(door=False, gap_m=0.1)), SETTINGS).building
    assert room_named(open_plan, "bedroom").connected_room_ids == (room_named(open_plan, "kitchen").id,)


def test_planned_cost_matches_the_exact_solver(tmp_path: Path) -> None:
    building = import_house(write(tmp_path, house_text()), SETTINGS).building
    kitchen = room_named(building, "kitchen")
    start = next(c for c in building.initial_cells if building.floors[0].room_map[c[0], c[1]] != kitchen.id)
    cost, exact = planned_and_exact_cost(building, f'F "enter({kitchen.key})"', start)
    assert cost == pytest.approx(exact) and exact > 1.0


def test_levels_become_floors_lowest_first(tmp_path: Path) -> None:
    text = house_text(door=False).replace(" 4 2 0 1 ", " 4 2 0 2 ")  # two levels in the H counts
    text = text.replace("L 0 2 -", "L 1 1 - 3 1.5 3  0 0 3 6 3 5.5 0 0 0 0 0\nL 0 1 -")
    text = text.replace("R 1 0 0 0 k", "R 1 1 0 0 k").replace("S 1 1 0 F 4.5 1.5 0 ", "S 1 1 0 F 4.5 1.5 3 ")
    result = import_house(write(tmp_path, text), SETTINGS)
    building = result.building
    assert [[r.name for r in f.rooms.values()] for f in building.floors] == [["bedroom"], ["kitchen"]]
    assert building.floors[1].ground_z_m == 3.0 and any("not joined" in n for n in result.notes)


def test_native_round_trip_and_direct_use(tmp_path: Path) -> None:
    path = write(tmp_path, house_text())
    # A robot radius read back from the native format, as given (here a non-zero one).
    building = import_house(path, replace(SETTINGS, robot_radius_m=0.1)).building
    again = read_native_scene(write_native_scene(building, tmp_path / "scene"))
    assert [r.name for r in again.rooms()] == [r.name for r in building.rooms()]
    assert again.initial_cells == building.initial_cells
    assert sorted(r.name for r in load_scene(path).rooms()) == ["bedroom", "kitchen"]


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda t: t.replace("ASCII 1.1", "hello"), "first line"),
        (lambda t: t.replace("R 1 0 0 0 k", "R 1 3 0 0 k"), "level 3"),
        (lambda t: t.replace("R 1 0 0 0 k", "R 1 0 0 0 q"), "label 'q'"),
        (
            lambda t: t.replace("V 5 1 F 6 0 0", "V 5 1 F 3.2 0 0").replace(
                "V 6 1 F 6 3 0", "V 6 1 F 3.2 3 0"
            ),
            "degenerate",
        ),
        (lambda t: t.replace("O 0 0 1 1 1", "O 0 0 9 1 1"), "category 9"),
        (lambda t: t.replace("O 0 0 1 1 1 0.3", "O 0 0 1 1 x 0.3"), "not a number"),
        (lambda t: "\n".join(line for line in t.splitlines() if not line.startswith("V 7")), "declares"),
        (
            lambda t: t.replace("R 0 0 0 0 b 1.5 1.5 0  0 0 0 3 3 2.5  2.5 0 0 0 0", "R 0 0 0 0 b 1.5"),
            "needs 16 fields",
        ),
    ],
)
def test_malformed_files_give_clear_errors(tmp_path: Path, edit: Callable[[str], str], message: str) -> None:
    with pytest.raises(SceneError, match=message):
        import_house(write(tmp_path, edit(house_text())), SETTINGS)


def test_real_house_imports_with_connected_rooms() -> None:
    real = scene_example("example_mp3d_scene.house")
    building = import_house(real).building
    names = sorted(r.name for r in building.rooms())
    assert names.count("bathroom") == 2 and "kitchen" in names and "lobby" in names
    assert building.rooms_named("lobby")[0].floor == building.initial_cells[0][2]
    assert all(r.connected_room_ids for r in building.rooms())


def test_notes_name_objects_as_the_file_does_and_flag_rooms_mostly_shut_off() -> None:
    """The left-out objects are the file's O records, not sgplan's object_<uuid> (a different object_60 is
    in the building); the kitchen's galley, behind a gap read as a wall, is flagged."""
    notes = import_house(scene_example("example_mp3d_scene.house")).notes
    left_out = next(n for n in notes if "left out" in n)
    assert "toilet paper (O record 60)" in left_out and "they get no object_<uuid>" in left_out
    assert "object 60" not in left_out
    shut = [n for n in notes if "cut off" in n]
    assert len(shut) == 1 and shut[0].startswith("room_12 kitchen: 680 of its 695 free cells (98%) are cut")


def test_a_room_without_a_way_in_is_noted(tmp_path: Path) -> None:
    walled = import_house(write(tmp_path, house_text(door=False)), SETTINGS).notes
    # the kitchen's 840 free cells are the largest area; the bedroom's 800 (its bed takes 100) lie apart
    assert [n.split(":")[0] for n in walled if "cut off" in n] == ["room_2 bedroom"]
    assert not [n for n in import_house(write(tmp_path, house_text()), SETTINGS).notes if "cut off" in n]


def test_reader_agrees_with_spark_dsg_on_the_real_house() -> None:
    real = scene_example("example_mp3d_scene.house")
    mp3d = pytest.importorskip(
        "spark_dsg.mp3d", reason="spark-dsg is not installed (pip install 'sgplan[hydra]')"
    )
    house = read_house(real)
    info = mp3d.load_mp3d_info(str(real))
    assert len(info["R"]) == len(house.regions) and len(info["O"]) == len(house.objects)
    assert sorted(r["label"] for r in info["R"]) == sorted(r.label for r in house.regions.values())
