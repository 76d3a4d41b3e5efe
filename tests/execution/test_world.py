"""Applying scene changes to a building: what each kind does to the rasters and objects, the errors of
changes that cannot apply, and the incremental occupancy grid against a full rebuild."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sgplan.errors import SceneError
from sgplan.execution.changes import (
    AddObject,
    Area,
    Block,
    CloseDoor,
    MoveObject,
    OpenDoor,
    RemoveObject,
    Unblock,
)
from sgplan.execution.regrid import regrid
from sgplan.execution.world import SceneState
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.model import CatCode
from tests.execution.buildings import flat, house


def _cats(building):
    return np.stack([floor.cat_map for floor in building.floors])


def _check_delta(before, after, delta):
    """The delta names exactly the cells whose category changed."""
    changed = {f: np.flatnonzero(b.cat_map != a.cat_map) for f, (b, a) in
               enumerate(zip(before.building.floors, after.building.floors))}
    for f, cells in changed.items():
        assert np.array_equal(delta.cells.get(f, np.zeros(0, np.int64)), cells)


def test_closing_a_door_cuts_the_rooms_apart_and_opening_it_restores_them():
    state = SceneState.of(flat())
    closed, delta = state.apply(CloseDoor(("kitchen", "corridor")))
    _check_delta(state, closed, delta)
    assert "closed the door between the kitchen (room_4, floor 0) and the corridor (room_3, floor 0)" in \
        delta.description
    room_map = closed.building.floors[0].room_map
    grid = build_occupancy_grid(closed.building, 0.0)
    # No move leads from a free kitchen cell to a free corridor cell any more.
    free = grid.traversable[0]
    kitchen, corridor = free & (room_map == 4), free & (room_map == 3)
    from scipy import ndimage
    assert not (ndimage.binary_dilation(kitchen, np.ones((3, 3), bool)) & corridor).any()
    opened, delta = closed.apply(OpenDoor(("room_3", "kitchen")))
    _check_delta(closed, opened, delta)
    assert np.array_equal(_cats(opened.building), _cats(state.building))


@pytest.mark.parametrize(("change", "message"), [
    (CloseDoor(("kitchen", "garage")), "close door: building 'flat' has no room called 'garage'"),
    (CloseDoor(("kitchen", "room_4")), "are the same room, the kitchen (room_4, floor 0)"),
    (OpenDoor(("kitchen", "bedroom")), "is not closed (closed doors: none)"),
    (Block(Area(0, box_m=(10.0, 10.0, 11.0, 11.0))),
     "lies outside floor 0's map (x 0.00..4.00 m, y 0.00..6.00 m)"),
    (Block(Area(3, box_m=(0.0, 0.0, 1.0, 1.0))), "floor 3 does not exist (floors 0..0)"),
    (Block(Area(0, box_m=(3.35, 0.35, 3.75, 0.75))), "holds no free ground"),
    (Unblock(name="trolley"), "no block is named 'trolley' (blocks: none)"),
    (Unblock(area=Area(0, box_m=(0.0, 0.0, 1.0, 1.0))), "no block covers the box"),
    (MoveObject("object_99", (1.0, 1.0)), "building 'flat' has no object object_99"),
    (MoveObject("sink", (0.0, 0.0)), "moved to (0, 0) m would leave floor 0's map"),
    (MoveObject("sink", (1.5, 1.0)), "would stand in a wall at cell"),
    (MoveObject("sink", (3.1, 5.0)), "would overlap the bed (object_7, in the bedroom room_5, floor 0)"),
    (AddObject("crate", (30.0, 1.0), 0, (0.3, 0.3)), "a crate of 0.3 x 0.3 m at (30, 1) m covers no cell"),
    (AddObject("ottoman", (30.0, 1.0), 0, (0.3, 0.3)), "an ottoman of 0.3 x 0.3 m at (30, 1) m covers no"),
    (AddObject("trolley", (1.5, 4.0), 0, (0.4, 0.4)), "would stand in a wall"),
    (RemoveObject("chair"), "has no object called 'chair' (objects: bed, plant, sink)"),
])
def test_changes_that_cannot_apply_say_why(change, message):
    with pytest.raises(SceneError) as error:
        SceneState.of(flat()).apply(change)
    assert message in str(error.value)


def test_no_door_between_rooms_that_do_not_touch():
    with pytest.raises(SceneError, match=r"no door between the office .* and the kitchen"):
        SceneState.of(house()).apply(CloseDoor(("office", "kitchen")))


def test_a_door_closes_once_and_blocks_are_named_once():
    state, _ = SceneState.of(flat()).apply(CloseDoor(("kitchen", "corridor")))
    with pytest.raises(SceneError, match="is closed already"):
        state.apply(CloseDoor(("corridor", "kitchen")))
    state, _ = state.apply(Block(Area(0, box_m=(0.2, 1.0, 1.2, 1.4)), "trolley"))
    with pytest.raises(SceneError, match="a block named 'trolley' stands already"):
        state.apply(Block(Area(0, box_m=(0.2, 2.0, 1.2, 2.4)), "trolley"))
    assert [b.name for b in state.blocks] == ["door room_3/room_4", "trolley"]


def test_a_block_holds_whatever_the_scene_puts_under_it():
    state = SceneState.of(flat())
    plant = state.building.object(uuid=8)
    state, _ = state.apply(Block(Area(0, box_m=(0.1, 2.8, 0.8, 3.5)), "cordon"))
    cat = state.building.floors[0].cat_map
    assert (cat == plant.id).sum() == 9 and (state.scene_cats[0] == plant.id).sum() == 9  # the plant stays
    moved, delta = state.apply(MoveObject("plant", (0.7, 1.0)))
    _check_delta(state, moved, delta)
    assert delta.objects == {8}
    # Where the plant stood is free ground in the scene, and a wall under the cordon.
    was = np.flatnonzero(state.scene_cats[0] == plant.id)
    assert (moved.scene_cats[0].reshape(-1)[was] == CatCode.GROUND).all()
    assert (moved.building.floors[0].cat_map.reshape(-1)[was] == CatCode.WALL).all()
    unblocked, _ = moved.apply(Unblock(area=Area(0, box_m=(0.0, 2.0, 1.5, 4.0))))
    assert (unblocked.building.floors[0].cat_map.reshape(-1)[was] == CatCode.GROUND).all()
    assert unblocked.blocks == ()


def test_moving_an_object_to_another_room_moves_its_footprint_and_membership():
    state = SceneState.of(flat())
    sink = state.building.object(uuid=6)
    before = int((state.building.floors[0].cat_map == sink.id).sum())
    moved, delta = state.apply(MoveObject("object_6", (2.0, 4.0)))
    new = moved.building.object(uuid=6)
    assert new.room_uuid == 5 and moved.building.room(uuid=5).objects[new.id] is new
    assert sink.id not in moved.building.room(uuid=4).objects
    assert int((moved.building.floors[0].cat_map == sink.id).sum()) == before
    assert np.allclose(new.location_m[:2], (2.0, 4.0), atol=0.1)
    assert "to (2, 4) m in the bedroom (room_5, floor 0)" in delta.description
    assert state.building.object(uuid=6).room_uuid == 4  # the old state is untouched


def test_added_and_removed_objects():
    state = SceneState.of(flat())
    added, delta = state.apply(AddObject("trolley", (0.7, 2.0), 0, (0.4, 0.6)))
    trolley = added.building.object(uuid=9)
    assert (trolley.id, trolley.name, trolley.room_uuid) == (4, "trolley", 3)
    assert delta.objects == {9} and delta.num_cells == 4 * 6
    removed, delta = added.apply(RemoveObject("trolley"))
    assert not removed.building.has_object(9)
    assert np.array_equal(_cats(removed.building), _cats(state.building))


def random_changes(rng, state, grid, count):
    """Up to ``count`` random changes applied one after the other (one that cannot apply is skipped): per
    change applied, ``(state, delta, grid, change)``: the scene after it, its delta, the grid regridded
    and the grid's change."""
    for _ in range(count):
        try:
            state, delta = state.apply(_random_change(rng, state))
        except SceneError:
            continue
        grid, change = regrid(grid, state.building, delta.cells)
        yield state, delta, grid, change


def _random_change(rng, state):
    building = state.building
    floor = int(rng.integers(building.num_floors))
    rows, cols = building.grid_shape
    x0, y0 = rng.uniform(0, rows * 0.1), rng.uniform(0, cols * 0.1)
    box = (x0, y0, x0 + rng.uniform(0.1, 1.2), y0 + rng.uniform(0.1, 1.2))
    rooms = [r.key for r in building.rooms() if r.connected_room_ids]
    objects = [o.key for o in building.objects()]
    kind = int(rng.integers(7))
    if kind == 0 and rooms:
        a = rooms[int(rng.integers(len(rooms)))]
        others = building.room(uuid=int(a[5:])).connected_room_ids
        b = building.room(id=others[int(rng.integers(len(others)))]).key
        return (CloseDoor if rng.random() < 0.6 else OpenDoor)((a, b))
    if kind == 1:
        return Block(Area(floor, box_m=box))
    if kind == 2:
        return Unblock(area=Area(floor, box_m=box))
    if kind == 3 and objects:
        return MoveObject(objects[int(rng.integers(len(objects)))], (box[0], box[1]), floor)
    if kind == 4:
        return AddObject("box", (box[0], box[1]), floor, (0.3, 0.5))
    if kind == 5 and objects:
        return RemoveObject(objects[int(rng.integers(len(objects)))])
    names = [b.name for b in state.blocks if b.door is None]
    return Unblock(name=names[0]) if names else Block(Area(floor, box_m=box), "named")


@given(st.integers(0, 2**32 - 1), st.sampled_from([0.0, 0.15]))
def test_any_sequence_of_changes_regrids_like_a_full_build(seed, radius):
    rng = np.random.default_rng(seed)
    state = SceneState.of(house(robot_radius_m=radius))
    grid = build_occupancy_grid(state.building, radius)
    for _ in range(12):
        try:
            new, delta = state.apply(_random_change(rng, state))
        except SceneError:
            continue
        _check_delta(state, new, delta)
        grid, _ = regrid(grid, new.building, delta.cells)
        full = build_occupancy_grid(new.building, radius)
        assert np.array_equal(grid.traversable, full.traversable)
        state = new


def test_a_newer_scene_graph_replaces_maps_and_objects_and_keeps_the_blocks(tmp_path):
    from sgplan.execution.changes import NewSceneGraph
    from sgplan.scene.native import write_native_scene

    state = SceneState.of(flat())
    newer, _ = state.apply(MoveObject("sink", (2.0, 2.0)))
    newer, _ = newer.apply(AddObject("crate", (0.7, 5.0), 0, (0.4, 0.4)))
    newer, _ = newer.apply(RemoveObject("plant"))
    write_native_scene(newer.building, tmp_path / "newer")
    closed, _ = state.apply(CloseDoor(("kitchen", "bedroom")))
    after, delta = closed.apply(NewSceneGraph(str(tmp_path / "newer"), tolerance_m=0.05))
    assert delta.objects == {6, 8, 9}
    assert "added the crate (object_9, in the corridor room_3, floor 0)" in delta.description
    assert "removed object_8" in delta.description and "moved the sink (object_6" in delta.description
    assert np.array_equal(after.scene_cats[0], newer.building.floors[0].cat_map)
    assert [b.name for b in after.blocks] == ["door room_4/room_5"]
    assert sorted(o.uuid for o in after.building.objects()) == [6, 7, 9]
    _check_delta(closed, after, delta)


def test_a_scene_graph_of_another_building_is_refused():
    from sgplan.execution.diff import diff_buildings

    with pytest.raises(SceneError, match="floors of"):
        diff_buildings(flat(), house())


def test_an_objects_reach_changes_with_the_cells_a_removed_neighbour_leaves_it():
    state, _ = SceneState.of(flat()).apply(AddObject("lamp", (2.4, 5.0), 0, (0.2, 0.4)))
    state, delta = state.apply(RemoveObject("lamp"))
    assert delta.objects == {9, 7}  # the lamp, and the bed that fills part of where it stood


@given(st.integers(0, 2**32 - 1))
def test_a_doors_cells_are_those_of_either_room_beside_the_other(seed):
    """boundary_cells: exactly the cells of room a with an 8-neighbour in room b and those of b beside a,
    on random room maps (rooms touching the map's edge too)."""
    from sgplan.execution.areas import boundary_cells

    rng = np.random.default_rng(seed)
    room_map = rng.integers(0, 4, size=(int(rng.integers(1, 12)), int(rng.integers(1, 12))))
    rows, cols = room_map.shape
    expected = []
    for r in range(rows):
        for c in range(cols):
            other = {1: 2, 2: 1}.get(int(room_map[r, c]))
            near = room_map[max(r - 1, 0) : r + 2, max(c - 1, 0) : c + 2]
            if other is not None and (near == other).any():
                expected.append(r * cols + c)
    assert boundary_cells(room_map, 1, 2).tolist() == expected
