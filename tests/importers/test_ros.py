"""The ROS map_server importer on a map and rooms file written here."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from sgplan.errors import SceneError
from sgplan.formats import load_scene
from sgplan.importers.assemble import Settings
from sgplan.importers.detect import import_scene
from sgplan.importers.ros import import_ros_map, read_map
from sgplan.scene.model import CatCode

from .helpers import free_cells, planned_and_exact_cost, room_named

SETTINGS = Settings(robot_radius_m=0.0, reach_radius_m=0.2)
ROOMS = """rooms:
  - name: kitchen
    polygon: [[-1, -2], [1.5, -2], [1.5, 1], [-1, 1]]
  - name: Living Room
    polygon: [[1.5, -2], [4, -2], [4, 1], [1.5, 1]]
objects:
  - name: refrigerator
    box: {center: [0.0, 0.0], size: [0.4, 0.6], height: 1.8}
  - name: couch
    position: [3.0, -1.0]
    room: living room
"""


def write_map(
    folder: Path, *, door: bool = True, negate: int = 0, extra: str = "", rooms: str = ROOMS
) -> Path:
    """A 100 x 60 pixel map at 5 cm: walls around two rooms split by a wall with (maybe) a door."""
    image = np.full((60, 100), 205, np.uint8)  # unknown
    image[5:55, 5:95] = 0
    image[6:54, 6:94] = 254
    image[6:54, 49:51] = 0
    if door:
        image[25:35, 49:51] = 254
    Image.fromarray(255 - image if negate else image).save(folder / "map.pgm")
    (folder / "map.yaml").write_text(
        f"image: map.pgm\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: {negate}\n"
        f"occupied_thresh: 0.65\nfree_thresh: 0.196\n{extra}"
    )
    (folder / "rooms.yaml").write_text(rooms)
    return folder / "map.yaml"


def test_map_orientation_and_thresholds(tmp_path: Path) -> None:
    codes, origin, resolution = read_map(write_map(tmp_path))
    assert codes.shape == (100, 60) and origin == (-1.0, -2.0) and resolution == 0.05
    # image pixel (row 6, col 6) is the free cell nearest the top-left corner: x = -0.7, y = 0.7
    assert codes[6, 60 - 1 - 6] == CatCode.GROUND and codes[5, 60 - 1 - 6] == CatCode.WALL
    assert codes[0, 0] == CatCode.OUTSIDE
    negated, _, _ = read_map(write_map(tmp_path, negate=1))
    assert (negated == codes).all()


def test_rooms_objects_connections_and_free_cells(tmp_path: Path) -> None:
    building = import_ros_map(write_map(tmp_path), tmp_path / "rooms.yaml", SETTINGS).building
    kitchen, living = room_named(building, "kitchen"), room_named(building, "living_room")
    assert kitchen.connected_room_ids == (living.id,)
    assert [o.name for o in kitchen.objects.values()] == ["refrigerator"]
    assert [o.name for o in living.objects.values()] == ["couch"]
    # free pixels: 48 x 88, minus the 2-pixel wall except its 10-pixel door, minus 8 x 12 fridge and 1 couch
    # cell
    assert free_cells(building) == 48 * 88 - 2 * 48 + 2 * 10 - 8 * 12 - 1
    walled = import_ros_map(write_map(tmp_path, door=False), tmp_path / "rooms.yaml", SETTINGS).building
    assert room_named(walled, "kitchen").connected_room_ids == ()


def test_planned_cost_matches_the_exact_solver(tmp_path: Path) -> None:
    building = import_ros_map(write_map(tmp_path), tmp_path / "rooms.yaml", SETTINGS).building
    couch = building.objects_named("couch")[0]
    start = building.initial_cells[0]
    cost, exact = planned_and_exact_cost(building, f'F "reach({couch.key})"', start)
    assert cost == pytest.approx(exact) and exact > 1.0


def test_direct_use_finds_the_rooms_file_beside_the_map(tmp_path: Path) -> None:
    path = write_map(tmp_path)
    assert sorted(r.name for r in load_scene(path).rooms()) == ["kitchen", "living_room"]
    (tmp_path / "rooms.yaml").unlink()
    with pytest.raises(SceneError, match="needs a rooms file"):
        import_scene("ros", path)


@pytest.mark.parametrize(
    ("extra", "rooms", "message"),
    [
        ("mode: fancy\n", ROOMS, "mode"),
        ("", "rooms: []\n", "non-empty list"),
        ("", "rooms:\n  - name: hall\n    polygon: [[0, 0], [1, 1]]\n", "degenerate"),
        ("", "rooms:\n  - name: hall\n    polygon: [[50, 50], [51, 50], [51, 51]]\n", "covers no cell"),
        ("", "rooms:\n  - polygon: [[0, 0], [1, 0], [1, 1]]\n", "needs a 'name'"),
        ("", ROOMS.replace("room: living room", "room: attic"), "attic"),
        ("", ROOMS.replace("position: [3.0, -1.0]", "position: [3.0]"), "position"),
    ],
)
def test_malformed_inputs_give_clear_errors(tmp_path: Path, extra: str, rooms: str, message: str) -> None:
    path = write_map(tmp_path, extra=extra, rooms=rooms)
    with pytest.raises(SceneError, match=message):
        import_ros_map(path, tmp_path / "rooms.yaml", SETTINGS)


def test_rotated_or_missing_image_is_refused(tmp_path: Path) -> None:
    path = write_map(tmp_path)
    path.write_text(path.read_text().replace("origin: [-1.0, -2.0, 0.0]", "origin: [-1.0, -2.0, 0.5]"))
    with pytest.raises(SceneError, match="yaw"):
        read_map(path)
    path.write_text(path.read_text().replace("0.5]", "0.0]").replace("map.pgm", "nothing.pgm"))
    with pytest.raises(SceneError, match="does not exist"):
        read_map(path)
