"""The scene model: look-ups, uniqueness checks, raster consistency and the grid frame."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sgplan.errors import SceneError
from sgplan.scene.model import NO_ROOM, Building, CatCode, Floor, Room, SceneObject, StairsEnd


def _room(room_id: int, uuid: int, name: str, floor: int) -> Room:
    return Room(room_id, uuid, name, floor, np.zeros(3), np.ones(3), (0, 0), (1, 1))


def _object(object_id: int, uuid: int, name: str, room: Room) -> SceneObject:
    return SceneObject(object_id, uuid, name, room.id, room.uuid, np.zeros(3), np.ones(3), (0, 0), (0, 0))


def _floor(index: int, uuid: int, rooms: list[Room], shape: tuple[int, int] = (4, 5)) -> Floor:
    floor = Floor(
        index, "AB"[index], uuid, (-1.0, 2.0), (0.5, 0.25), 0.0,
        np.zeros(shape, np.int16), np.full(shape, NO_ROOM, np.int16),
    )
    floor.rooms = {r.id: r for r in rooms}
    return floor


def _building() -> Building:
    kitchen, hall = _room(1, 2, "kitchen", 0), _room(2, 4, "Corridor", 0)
    stairs, bedroom = _room(3, 5, "staircase", 0), _room(4, 7, "bedroom", 1)
    kitchen.objects = {5: _object(5, 8, "Sink", kitchen), 6: _object(6, 9, "sink", kitchen)}
    bedroom.objects = {1: _object(1, 10, "bed", bedroom)}
    return Building(9, 1, "Tiny", [_floor(0, 3, [kitchen, hall, stairs]), _floor(1, 6, [bedroom])])


def test_lookups() -> None:
    building = _building()
    assert building.num_floors == 2 and building.grid_shape == (4, 5) and building.resolution_m == (0.5, 0.25)
    assert building.room(id=2).uuid == 4 and building.room(uuid=7).id == 4
    assert building.object(id=1).key == "object_10" and building.object(uuid=8).id == 5
    assert building.room(uuid=5).is_staircase and building.room(uuid=5).key == "room_5"
    assert building.has_room(7) and not building.has_room(8) and building.has_object(8)
    assert [r.id for r in building.rooms()] == [1, 2, 3, 4]
    assert [o.id for o in building.objects()] == [5, 6, 1]
    assert [r.id for r in building.rooms_named("corridor")] == [2]
    assert building.rooms_named("bedroom", floor=0) == []
    assert [o.id for o in building.objects_named("SINK")] == [5, 6]
    assert building.objects_named("sink", room_uuid=7) == []
    assert building.floor_of_object(building.object(id=1)) == 1
    with pytest.raises(SceneError, match=r"building 'Tiny' has no room with uuid 3"):
        building.room(uuid=3)  # a floor's uuid, not a room's
    with pytest.raises(SceneError, match=r"building 'Tiny' has no object with id 2"):
        building.object(id=2)


@pytest.mark.parametrize(
    "edit, pattern",
    [
        (lambda b: b.floors[1].rooms[4].__setattr__("uuid", 2), r"room 4 and room 1 share uuid 2"),
        (lambda b: b.floors[1].rooms[4].__setattr__("uuid", 6), r"room 4 and floor 1 share uuid 6"),
        (lambda b: b.floors[1].rooms[4].__setattr__("uuid", 1), r"room 4 and building 'Tiny' share uuid 1"),
        (lambda b: b.floors[1].rooms[4].__setattr__("id", 2), r"two rooms have id 2"),
        (lambda b: b.floors[1].rooms[4].objects[1].__setattr__("id", 6), r"two objects have id 6"),
        (lambda b: b.floors[1].__setattr__("index", 0), r"floor at position 1 has index 0"),
    ],
)
def test_index_rejects_ambiguity(edit, pattern: str) -> None:
    building = _building()
    edit(building)
    with pytest.raises(SceneError, match=pattern):
        building._index()


def test_maps_and_declared_ids() -> None:
    building = _building()
    floor0, floor1 = building.floors
    assert floor0.has_maps and floor0.shape == (4, 5)
    floor0.cat_map[0, 0], floor0.cat_map[0, 1], floor0.cat_map[0, 2] = 5, 1, CatCode.WALL
    floor0.room_map[1, :] = [1, 2, 3, 4, NO_ROOM]
    assert floor0.undeclared_map_ids() == ([1], [4])
    floor1.room_map[2, 2] = 3  # the staircase of floor 0, drawn on floor 1 too: only with down stairs
    assert floor1.undeclared_map_ids() == ([], [3])
    floor1.down_stairs = StairsEnd(3, 5, (2, 2), 3.0)
    assert floor1.undeclared_map_ids() == ([], [])
    empty = Floor(0, "A", 3, (0.0, 0.0), (0.0, 0.0), float("nan"), np.zeros((0, 0), np.int16),
                  np.zeros((0, 0), np.int16))
    assert not empty.has_maps and empty.shape == (0, 0) and empty.undeclared_map_ids() == ([], [])


@given(row=st.integers(-50, 50), col=st.integers(-50, 50))
def test_cell_centre_round_trip(row: int, col: int) -> None:
    floor = _building().floors[0]
    x, y = floor.cell_to_xy((row, col))
    assert floor.xy_to_cell(x, y) == (row, col)
    assert (x, y) == pytest.approx((-1.0 + (row + 0.5) * 0.5, 2.0 + (col + 0.5) * 0.25))
