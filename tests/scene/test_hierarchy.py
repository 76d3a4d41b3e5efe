"""The attribute hierarchy text for prompts."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.scene.authors import load_authors_scene
from sgplan.scene.gibson_npz import load_gibson_npz
from sgplan.scene.hierarchy import attribute_hierarchy

from .synthetic import synthetic_scene


def test_synthetic_hierarchy(tmp_path: Path) -> None:
    building = load_authors_scene(synthetic_scene().write(tmp_path / "tiny"))
    assert attribute_hierarchy(building) == (
        "Building Tiny: 2 floors, 4 rooms, 2 objects.\n"
        "Floor 0:\n"
        "  room_2: kitchen. Connects to: room_4, room_5. Objects: object_8 (refrigerator).\n"
        "  room_4: corridor. Connects to: room_2.\n"
        "  room_5: staircase. Connects to: room_2, room_6 (floor 1).\n"
        "Floor 1:\n"
        "  room_6: bedroom. Connects to: room_5 (floor 0). Objects: object_9 (bed).\n"
    )
    assert (
        attribute_hierarchy(building, connections=False, objects=False).splitlines()[2]
        == "  room_2: kitchen."
    )


def test_order_does_not_depend_on_insertion(tmp_path: Path) -> None:
    building = load_authors_scene(synthetic_scene().write(tmp_path / "tiny"))
    text = attribute_hierarchy(building)
    floor = building.floors[0]
    floor.rooms = dict(reversed(list(floor.rooms.items())))
    kitchen = building.room(id=1)
    kitchen.connected_room_ids, kitchen.connected_room_uuids = (3, 2), (5, 4)
    assert attribute_hierarchy(building) == text


@pytest.mark.gibson
def test_gibson_hierarchy(gibson_root: Path) -> None:
    building = load_authors_scene(gibson_root / "Benevolence")
    text = attribute_hierarchy(building)
    lines = text.splitlines()
    assert lines[0] == "Building Benevolence: 3 floors, 16 rooms, 41 objects."
    assert [line for line in lines if line.startswith("Floor")] == ["Floor 0:", "Floor 1:", "Floor 2:"]
    assert len(lines) == 1 + 3 + 16
    assert "  room_20: utility_room. Connects to: none." in lines
    assert "room_18: staircase. Connects to: room_10 (floor 1), room_17." in text
    assert all(f"{o.key} ({o.name})" in text for o in building.objects())
    assert len(text) < 2500  # compact: about 45 characters per entity
    # the graph-only npz gives the same rooms and objects, without connections
    from_npz = attribute_hierarchy(
        load_gibson_npz(gibson_root / "3DSceneGraph_Benevolence.npz"), connections=False
    )
    assert from_npz == attribute_hierarchy(building, connections=False)
