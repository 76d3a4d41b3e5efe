"""The scene builder: a user-built building plans, draws and round-trips; every bad input is refused."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import sgplan
from sgplan.errors import SceneError
from sgplan.scene.builder import BuildingBuilder
from sgplan.scene.native import read_native_scene, write_native_scene


def duplex() -> tuple[BuildingBuilder, dict[str, int]]:
    b = BuildingBuilder("duplex", size_m=(6.0, 5.0), robot_radius_m=0.1, reach_radius_m=0.5)
    b.add_floor(), b.add_floor()
    ids = {"hall": b.add_room(0, "corridor", box=(0, 0, 6, 1.6)),
           "kitchen": b.add_room(0, "kitchen", polygon=[(0, 1.6), (3.5, 1.6), (3.5, 5), (0, 5)])}
    b.add_door(ids["hall"], ids["kitchen"], at=(1.5, 1.6))
    ids["sink"] = b.add_object(ids["kitchen"], "sink", box=(0.4, 4.2, 1.0, 4.8), height_m=0.9)
    ids["stairs"] = b.add_staircase(0, box=(3.5, 1.6, 6, 5), portal=(4.5, 2.2), steps=(3.7, 3.2, 5.8, 4.8))
    b.add_door(ids["hall"], ids["stairs"], at=(4.5, 1.6))
    ids["bed"] = b.add_room(1, "bedroom", box=(0, 0, 3.5, 5))
    b.add_door(ids["stairs"], ids["bed"], at=(np.float32(3.5), 2.2))          # numpy numbers are fine
    b.add_object(ids["bed"], "bed", box=(np.float64(0.5), 3, 2.5, 4.8), height_m=0.6)
    b.add_start(1.0, 0.8, np.int64(0))
    return b, ids


def test_a_built_two_floor_building_plans_draws_and_round_trips(tmp_path: Path) -> None:
    b, ids = duplex()
    building = b.build()
    sink, bed = building.object(id=ids["sink"]), building.room(id=ids["bed"])
    assert building.room(id=ids["hall"]).connected_room_ids == (ids["kitchen"], ids["stairs"])
    assert sorted({building.uuid, *(f.uuid for f in building.floors), *(r.uuid for r in building.rooms()),
                   *(o.uuid for o in building.objects())}) == list(range(1, 10))  # unique, assigned
    mission = sgplan.mission_from_formula(f'F("reach({sink.key})" & F "enter({bed.key})")', building)
    result = sgplan.plan(building, mission)
    assert result.status == "optimal" and result.verified and {c[2] for c in result.cells} == {0, 1}
    assert [e.entity for e in result.events if e.kind == "proposition"] == ["sink", "bedroom"]
    assert [p.name for p in result.draw(tmp_path / "png", automaton=False)] == [
        "plan_floor_0.png", "plan_floor_0.svg", "plan_floor_1.png", "plan_floor_1.svg",
    ]  # what `plan --draw` writes
    building.initial_cells = [tuple(np.int64(v) for v in building.initial_cells[0])]  # numpy ints write too
    again = read_native_scene(write_native_scene(building, tmp_path / "scene"))
    for room in building.rooms():
        twin = again.room(id=room.id)
        assert twin.uuid == room.uuid and twin.connected_room_uuids == room.connected_room_uuids
        assert all(np.array_equal(twin.door_cells[k], v) for k, v in room.door_cells.items())
    assert all(np.array_equal(f.cat_map, g.cat_map) for f, g in zip(building.floors, again.floors))
    assert sgplan.plan(again, mission).cost_m == pytest.approx(result.cost_m, abs=1e-9)


def _builder() -> BuildingBuilder:
    b = BuildingBuilder("t", size_m=(4.0, 4.0))
    b.add_floor()
    b.add_room(0, "kitchen", box=(0, 0, 2, 4))
    return b


@pytest.mark.parametrize("call, fragment", [
    (lambda b: b.add_room(0, "hall", box=(1, 1, 3, 3)), "overlaps room 1 (kitchen) on floor 0"),
    (lambda b: b.add_room(3, "hall", box=(2, 0, 4, 4)), "no floor 3"),
    (lambda b: b.add_room(0, "", box=(2, 0, 4, 4)), "non-empty string"),
    (lambda b: b.add_room(0, "hall", box=(2, 0, 2, 4)), "x0 < x1"),
    (lambda b: b.add_room(0, "hall", box=(9, 9, 10, 10)), "holds no cell"),
    (lambda b: b.add_room(0, "hall", polygon=[(2, 0), (4, 0)]), "three or more"),
    (lambda b: b.add_room(0, "hall", box=(2, 0, float("nan"), 4)), "finite number"),
    (lambda b: b.add_room(0, "hall", cells=np.ones((3, 3), dtype=bool)), "bool array of the grid's shape"),
    (lambda b: b.add_room(0, "hall", box=(2, 0, 4, 4), cells=np.ones((80, 80), dtype=bool)), "exactly one"),
    (lambda b: b.add_object(1, "sink", box=(1.5, 0, 2.5, 1)), "reaches outside room 1"),
    (lambda b: b.add_object(7, "sink", box=(0, 0, 1, 1)), "no room 7"),
    (lambda b: b.add_object(1, "sink", box=(0, 0, 1, 1), height_m=0), "height_m must be a finite number > 0"),
    (lambda b: b.add_staircase(0, box=(2, 0, 4, 4), portal=(3, 3)), "add floor 1 first"),
    (lambda b: b.add_floor(ground_z_m=-1.0), "must be above floor 0"),
    (lambda b: b.add_start(9.0, 9.0, 0), "off the grid"),
])
def test_bad_parts_are_refused_where_they_are_added(call, fragment: str) -> None:
    with pytest.raises(SceneError) as error:
        call(_builder())
    assert fragment in str(error.value)


def test_bad_assemblies_are_refused_when_built() -> None:
    b = _builder()
    hall = b.add_room(0, "corridor", box=(2, 0, 4, 4))
    b.add_door(1, hall, at=(1.0, 1.0))  # inside the kitchen, not on the wall between the rooms
    with pytest.raises(SceneError, match="opens no passage"):
        b.build()
    with pytest.raises(SceneError, match="has no floors"):
        BuildingBuilder("empty", size_m=(1.0, 1.0)).build()
    b = _builder()
    b.add_floor()
    with pytest.raises(SceneError, match=r"portal .* lies outside the staircase"):
        b.add_staircase(0, box=(2, 0, 4, 4), portal=(1.0, 1.0))
    b.add_staircase(0, box=(2, 0, 4, 4), portal=(3.0, 2.0), cost_m=0.5)
    with pytest.raises(SceneError, match="below the straight-line distance"):
        b.build()
    with pytest.raises(SceneError, match="size_m"):
        BuildingBuilder("x", size_m=(0, 1))
