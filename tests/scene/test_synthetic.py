"""Procedural buildings and the demo building: determinism, structural invariants, plannability."""

from __future__ import annotations

import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import SceneError
from sgplan.scene.demo import (
    DEMO_REACH_RADIUS_M,
    DEMO_ROBOT_RADIUS_M,
    DEMO_STARTS,
    deepest_start_cells,
    demo_building,
)
from sgplan.scene.grid import build_occupancy_grid, floor_heights_m
from sgplan.scene.labels import Proposition, label_raster
from sgplan.scene.model import Building, CatCode
from sgplan.scene.synthetic import RoomSpec, building_from_specs, generate_building
from tests.scene.distances import grid_distances
from tests.scene.small_buildings import random_small_building


def check_invariants(building: Building) -> None:
    """Everything a loader guarantees, checked on a generated building."""
    rooms = sorted(building.rooms(), key=lambda r: r.id)
    objects = sorted(building.objects(), key=lambda o: o.id)
    # uuids: building 1; rooms in id order, each floor's uuid right after its first room; then objects.
    expected, seen, uuid = {}, set(), 2
    for room in rooms:
        expected[("room", room.id)] = uuid
        uuid += 1
        if room.floor not in seen:
            seen.add(room.floor)
            expected[("floor", room.floor)] = uuid
            uuid += 1
    for obj in objects:
        expected[("object", obj.id)] = uuid
        uuid += 1
    actual = {("room", r.id): r.uuid for r in rooms} | {("object", o.id): o.uuid for o in objects}
    actual |= {("floor", f.index): f.uuid for f in building.floors}
    assert building.uuid == 1 and actual == expected
    for room in rooms:
        floor = building.floors[room.floor]
        assert floor.rooms[room.id] is room
        assert (floor.room_map == room.id).any()
        assert room.connected_room_uuids == tuple(building.room(id=i).uuid for i in room.connected_room_ids)
        for other in room.connected_room_ids:
            assert room.id in building.room(id=other).connected_room_ids
        assert set(room.door_cells) == set(room.connected_room_ids)
        for neighbour, cells in room.door_cells.items():
            assert cells.ndim == 2 and cells.shape[1] == 2 and len(cells)
            # Door cells: ground cells of the neighbour, 4-adjacent to this room, on some floor.
            ok = False
            for f in building.floors:
                r, c = cells[:, 0], cells[:, 1]
                if not ((f.room_map[r, c] == neighbour).all() and (f.cat_map[r, c] == CatCode.GROUND).all()):
                    continue
                padded = np.pad(f.room_map == room.id, 1)
                touch = padded[r, c + 1] | padded[r + 2, c + 1] | padded[r + 1, c] | padded[r + 1, c + 2]
                ok = ok or bool(touch.all())
            assert ok, (room.key, neighbour)
        for obj in room.objects.values():
            cat = floor.cat_map
            r0, c0 = obj.grid_min
            r1, c1 = obj.grid_max
            assert (cat[r0 : r1 + 1, c0 : c1 + 1] == obj.id).all()
            assert (cat == obj.id).sum() == (r1 - r0 + 1) * (c1 - c0 + 1)
            assert (floor.room_map[cat == obj.id] == room.id).all()
            assert obj.room_uuid == room.uuid and obj.name
    heights = floor_heights_m(building)
    for lower, upper in zip(building.floors, building.floors[1:]):
        up, down = lower.up_stairs, upper.down_stairs
        assert up is not None and down is not None and up.room_id == down.room_id and up.cost_m == down.cost_m
        stair = building.room(id=up.room_id)
        assert stair.is_staircase and stair.floor == lower.index
        for floor, end, code in ((lower, up, CatCode.STAIRS_UP), (upper, down, CatCode.STAIRS_DOWN)):
            assert floor.cat_map[end.portal] == CatCode.GROUND and floor.room_map[end.portal] == stair.id
            assert (floor.cat_map[floor.room_map == stair.id] == code).any()
        a = np.array([*lower.cell_to_xy(up.portal), heights[lower.index]])
        b = np.array([*upper.cell_to_xy(down.portal), heights[upper.index]])
        assert up.cost_m >= np.linalg.norm(a - b)


@settings(max_examples=40)
@given(seed=st.integers(0, 2**32 - 1))
def test_random_small_buildings_are_valid(seed: int) -> None:
    building = random_small_building(seed)
    check_invariants(building)
    assert 1 <= building.num_floors <= 2
    assert len(list(building.objects())) <= 6
    rows, cols = building.grid_shape
    assert rows <= 30 and cols <= 60
    assert (building.robot_radius_m, building.reach_radius_m) == (0.0, 0.5)


@settings(max_examples=6)
@given(
    floors=st.integers(1, 3), rooms=st.integers(1, 7), objects=st.integers(0, 20), seed=st.integers(0, 1000)
)
def test_generated_buildings_are_valid(floors: int, rooms: int, objects: int, seed: int) -> None:
    building = generate_building(
        num_floors=floors, rooms_per_floor=rooms, num_objects=objects, seed=seed, cell_m=0.1
    )
    check_invariants(building)
    assert building.num_floors == floors
    assert len(list(building.rooms())) == floors * (rooms + 1) + floors - 1
    assert len(list(building.objects())) <= objects


def test_same_seed_same_building() -> None:
    def fingerprint(b: Building) -> tuple:
        return (
            [f.cat_map.tobytes() + f.room_map.tobytes() for f in b.floors],
            [(r.id, r.uuid, r.name, r.connected_room_ids) for r in b.rooms()],
            [(o.id, o.uuid, o.name, o.grid_min, o.grid_max) for o in b.objects()],
            [(f.up_stairs, f.ground_z_m) for f in b.floors],
        )

    assert fingerprint(random_small_building(11)) == fingerprint(random_small_building(11))
    assert fingerprint(generate_building(seed=5)) == fingerprint(generate_building(seed=5))
    assert fingerprint(generate_building(seed=5)) != fingerprint(generate_building(seed=6))
    assert fingerprint(demo_building()) == fingerprint(demo_building())


def test_random_small_building_is_fast() -> None:
    random_small_building(0)
    start = time.perf_counter()
    for seed in range(100):
        random_small_building(seed)
    per_building = (time.perf_counter() - start) / 100
    assert per_building < 0.005 * 3  # 5 ms target (about 1.5 ms measured); slack for a busy CI machine


def test_generator_rejects_bad_input() -> None:
    with pytest.raises(SceneError):
        generate_building(num_floors=0)
    with pytest.raises(SceneError):
        generate_building(rooms_per_floor=0)
    with pytest.raises(SceneError, match="unknown object class"):
        building_from_specs([[RoomSpec("kitchen", ("spaceship",))]])
    with pytest.raises(SceneError, match="generated automatically"):
        building_from_specs([[RoomSpec("staircase")]])
    with pytest.raises(SceneError, match="cell size"):
        building_from_specs([[RoomSpec("kitchen")]], cell_m=0.0)


def test_demo_building_content() -> None:
    building = demo_building()
    check_invariants(building)
    assert building.num_floors == 2
    assert len(list(building.rooms())) == 11 and len(list(building.objects())) == 28
    assert building.resolution_m == (0.05, 0.05)
    assert (building.robot_radius_m, building.reach_radius_m) == (DEMO_ROBOT_RADIUS_M, DEMO_REACH_RADIUS_M)

    def classes(category: str) -> set[str]:
        return {o.name for r in building.rooms_named(category) for o in r.objects.values()}

    assert {"refrigerator", "oven", "sink"} <= classes("kitchen")
    assert {"couch", "tv"} <= classes("living_room")
    assert {"dining table", "chair"} <= classes("dining_room")
    assert {"toilet", "sink"} <= classes("bathroom")
    assert len(building.rooms_named("bedroom")) == 2
    assert all("bed" in {o.name for o in r.objects.values()} for r in building.rooms_named("bedroom"))


def test_demo_starts_are_the_deepest_cells_of_their_rooms() -> None:
    """The stored initial cells are what :func:`deepest_start_cells` derives from the generated house."""
    building = demo_building()
    assert building.initial_cells == list(DEMO_STARTS) == deepest_start_cells(building)


def test_demo_building_is_plannable() -> None:
    """From every initial cell, every room and every object is reachable with the default robot radius."""
    building = demo_building()
    grid = build_occupancy_grid(building, building.robot_radius_m)
    assert len(building.initial_cells) == 5
    assert all(grid.traversable[f, r, c] for r, c, f in building.initial_cells)
    props = [Proposition("enter", r.uuid) for r in building.rooms()]
    objects = [Proposition("reach", o.uuid) for o in building.objects()]
    dist = grid_distances(grid, building.initial_cells[:1])
    for batch in (props, objects[:16], objects[16:]):
        labels = label_raster(building, batch)
        reachable = np.isfinite(dist)
        for bit, prop in enumerate(batch):
            assert (((labels >> bit) & 1).astype(bool) & reachable).any(), prop.name
    assert np.isfinite(dist[1]).any() and np.nanmax(np.where(np.isfinite(dist), dist, np.nan)) < 60.0
