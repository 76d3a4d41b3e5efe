"""A tiny two-floor scene in the authors' folder format, written by tests into ``tmp_path``.

Grid 12 x 16 cells of 0.1 m. Floor 0: kitchen (id 1) with a fridge (object 7), corridor (id 2),
staircase (id 3) going up. Floor 1: bedroom (id 4) with a bed (object 8); the staircase's top part.
uuids follow the authors' rule (building 1, rooms in order, a floor's uuid right after its first room).
Tests mutate the returned YAML document and rasters before writing to produce bad input.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from PIL import Image

from sgplan.scene.model import Building

ROWS, COLS = 12, 16


def _room(
    room_id: int, uuid: int, name: str, floor: int, floor_uuid: int, box: tuple[int, int, int, int]
) -> dict[str, Any]:
    return {
        "id": room_id,
        "uuid": uuid,
        "name": name,
        "type": "kRoom",
        "parent_id": floor,
        "parent_uuid": floor_uuid,
        "parent_building": 9,
        "location": [0.1 * (box[0] + box[2]) / 2, 0.1 * (box[1] + box[3]) / 2, 1.2],
        "size": [0.1 * (box[2] - box[0]), 0.1 * (box[3] - box[1]), 2.4],
        "grid_map_min": [box[0], box[1]],
        "grid_map_max": [box[2], box[3]],
        "connected_room_ids": [],
        "connected_room_uuids": [],
        "door_grids": {},
        "objects": {},
        "num_objects": 0,
    }


def _object(
    object_id: int, uuid: int, name: str, room: dict[str, Any], box: tuple[int, int, int, int]
) -> dict[str, Any]:
    return {
        "id": object_id,
        "uuid": uuid,
        "name": name,
        "type": "kObject",
        "parent_id": room["id"],
        "parent_uuid": room["uuid"],
        "location": [0.1 * (box[0] + box[2]) / 2, 0.1 * (box[1] + box[3]) / 2, 0.5],
        "size": [0.2, 0.2, 1.0],
        "grid_map_min": [box[0], box[1]],
        "grid_map_max": [box[2], box[3]],
        "action_affordance": ["open", "close"],
        "material": ["metal", None],
    }


def _floor(index: int, uuid: int, rooms: list[dict[str, Any]]) -> dict[str, Any]:
    return {
        "id": index,
        "uuid": uuid,
        "name": "AB"[index],
        "type": "kFloor",
        "parent_id": 9,
        "parent_uuid": 1,
        "cat_map": f"cat_maps/{index}.png",
        "room_map": f"room_maps/{index}.png",
        "grid_map_origin": [-0.6, -0.8],
        "grid_map_resolution": [0.1, 0.1],
        "grid_map_size": [ROWS, COLS],
        "ground_z": 0.0 + 3.0 * index,
        "rooms": {r["id"]: r for r in rooms},
        "num_rooms": len(rooms),
        "up_stairs_id": -1,
        "up_stairs_uuid": -1,
        "up_stairs_portal": None,
        "up_stairs_cost": float("inf"),
        "down_stairs_id": -1,
        "down_stairs_uuid": -1,
        "down_stairs_portal": None,
        "down_stairs_cost": float("inf"),
    }


@dataclass
class SyntheticScene:
    """The document and decoded rasters of the tiny scene; :meth:`write` stores them as the authors do."""

    document: dict[str, Any]
    cat_maps: list[np.ndarray]
    room_maps: list[np.ndarray]
    radius_config: str | None = "ROBOT_RADIUS=0.1\nexport OBJECT_REACH_RADIUS=0.3  # metres\n"
    initial_positions: str | None = "- [2, 10, 0]\n- [3, 10, 1]\n"
    extra_files: dict[str, bytes] = field(default_factory=dict)

    def write(self, folder: Path) -> Path:
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "building.yaml").write_text(yaml.safe_dump(self.document, sort_keys=True))
        for kind, maps in (("cat_maps", self.cat_maps), ("room_maps", self.room_maps)):
            (folder / kind).mkdir(exist_ok=True)
            for index, raster in enumerate(maps):
                Image.fromarray((raster + 5).astype(np.uint8)).save(folder / kind / f"{index}.png")
        if self.radius_config is not None:
            (folder / "radius_config.bash").write_text(self.radius_config)
        if self.initial_positions is not None:
            (folder / "initial_positions.yaml").write_text(self.initial_positions)
        for name, content in self.extra_files.items():
            (folder / name).write_bytes(content)
        return folder


def synthetic_scene() -> SyntheticScene:
    """A fresh (mutable) copy of the tiny scene."""
    kitchen = _room(1, 2, "kitchen", 0, 3, (0, 0, 5, 7))
    corridor = _room(2, 4, "corridor", 0, 3, (0, 8, 5, 15))
    stairs = _room(3, 5, "staircase", 0, 3, (0, 0, 0, 0))
    bedroom = _room(4, 6, "bedroom", 1, 7, (0, 4, 11, 15))
    kitchen["objects"] = {7: _object(7, 8, "refrigerator", kitchen, (1, 1, 2, 2))}
    bedroom["objects"] = {8: _object(8, 9, "bed", bedroom, (2, 10, 4, 13))}
    # The uuid list is deliberately in another order than the id list, as in the authors' files.
    kitchen["connected_room_ids"], kitchen["connected_room_uuids"] = [2, 3], [5, 4]
    corridor["connected_room_ids"], corridor["connected_room_uuids"] = [1], [2]
    stairs["connected_room_ids"], stairs["connected_room_uuids"] = [1, 4], [6, 2]
    bedroom["connected_room_ids"], bedroom["connected_room_uuids"] = [3], [5]
    kitchen["door_grids"] = {2: [[1, 8], [2, 8]], 3: [[6, 1]]}
    corridor["door_grids"] = {1: [[1, 7], [2, 7]]}
    floor0 = _floor(0, 3, [kitchen, corridor, stairs])
    floor1 = _floor(1, 7, [bedroom])
    floor0.update(up_stairs_id=3, up_stairs_uuid=5, up_stairs_portal=[6, 2], up_stairs_cost=3.5)
    floor1.update(down_stairs_id=3, down_stairs_uuid=5, down_stairs_portal=[6, 5], down_stairs_cost=3.5)
    document = {
        "id": 9,
        "uuid": 1,
        "name": "Tiny",
        "type": "kBuilding",
        "parent_id": -1,
        "parent_uuid": -1,
        "num_floors": 2,
        "num_rooms": 4,
        "reference_point": [0.0, 0.0, 0.0],
        "size": [1.2, 1.6, 6.0],
        "floors": {0: floor0, 1: floor1},
    }

    room0 = np.full((ROWS, COLS), -5, np.int16)
    room0[0:6, 0:8], room0[0:6, 8:16], room0[6:12, 0:4] = 1, 2, 3
    cat0 = np.where(room0 > 0, 0, -5).astype(np.int16)
    cat0[6:12, 0:4] = -1
    cat0[6, 2] = 0
    cat0[1:3, 1:3] = 7
    cat0[0, :] = -3
    room1 = np.full((ROWS, COLS), -5, np.int16)
    room1[:, 4:16], room1[6:12, 0:4] = 4, 3
    cat1 = np.where(room1 > 0, 0, -5).astype(np.int16)
    cat1[6:12, 0:4] = -2
    cat1[2:5, 10:14] = 8
    return SyntheticScene(copy.deepcopy(document), [cat0, cat1], [room0, room1])


def assert_same_building(first: Building, second: Building) -> None:
    """Every stored fact of two buildings is equal (rasters and door cells element-wise); ``source`` aside."""
    assert _facts(first) == _facts(second)
    for a, b in zip(first.floors, second.floors):
        assert a.cat_map.dtype == b.cat_map.dtype and np.array_equal(a.cat_map, b.cat_map)
        assert a.room_map.dtype == b.room_map.dtype and np.array_equal(a.room_map, b.room_map)


def _facts(building: Building) -> object:
    def vector(v: np.ndarray) -> tuple:
        return tuple(float(x) for x in v)

    return (
        building.id, building.uuid, building.name, building.robot_radius_m, building.reach_radius_m,
        building.initial_cells,
        [
            (
                f.index, f.name, f.uuid, f.origin_m, f.resolution_m,
                "nan" if np.isnan(f.ground_z_m) else f.ground_z_m, f.shape, f.up_stairs, f.down_stairs,
                [
                    (
                        r.id, r.uuid, r.name, r.floor, vector(r.location_m), vector(r.size_m), r.grid_min,
                        r.grid_max, r.connected_room_ids, r.connected_room_uuids,
                        [(k, v.dtype.str, v.tolist()) for k, v in r.door_cells.items()],
                        [
                            (
                                o.id, o.uuid, o.name, o.room_id, o.room_uuid, vector(o.location_m),
                                vector(o.size_m), o.grid_min, o.grid_max, o.action_affordance,
                            )
                            for o in r.objects.values()
                        ],
                    )
                    for r in f.rooms.values()
                ],
            )
            for f in building.floors
        ],
    )
