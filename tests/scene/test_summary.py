"""Scene summaries: data first, then text lines."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

from sgplan.scene.demo import demo_building
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.summary import summarize, summary_lines


def test_demo_summary_data_and_text() -> None:
    building = demo_building()
    summary = summarize(building)
    assert summary.name == "demo-house" and summary.grid_shape == building.grid_shape
    assert (summary.num_rooms, summary.num_objects) == (11, 28)
    assert summary.robot_radius_m == building.robot_radius_m
    grid = build_occupancy_grid(building, building.robot_radius_m)
    assert [f.free_cells for f in summary.floors] == grid.traversable.sum(axis=(1, 2)).tolist()
    assert sum(summary.floors[0].component_sizes) == summary.floors[0].free_cells
    (stairs,) = summary.stairs
    assert stairs.cost_m == building.floors[0].up_stairs.cost_m
    corridor = next(r for r in summary.floors[0].rooms if r.category == "corridor")
    assert len(corridor.connected) == 5 and all(key.startswith("room_") for key in corridor.connected)
    kitchen = next(r for r in summary.floors[0].rooms if r.category == "kitchen")
    assert any(item.startswith("refrigerator object_") for item in kitchen.objects)
    json.dumps(dataclasses.asdict(summary))  # plain data all the way down

    text = "\n".join(summary_lines(summary))
    assert "2 floors, 11 rooms, 28 objects" in text
    assert f"{kitchen.key} kitchen" in text and "refrigerator object_" in text
    assert "stairs floor 0" in text and "stairs up portal" in text
    assert "objects:" not in "\n".join(summary_lines(summary, objects=False))
    zero = summarize(building, build_occupancy_grid(building, 0.0))
    assert zero.robot_radius_m == 0.0 and zero.floors[0].free_cells > summary.floors[0].free_cells


@pytest.mark.gibson
def test_benevolence_summary(gibson_root: Path) -> None:
    from sgplan.scene.authors import load_authors_scene

    summary = summarize(load_authors_scene(gibson_root / "Benevolence"))
    assert [f.free_cells for f in summary.floors] == [93_302, 177_258, 106_263]
    assert [len(f.rooms) for f in summary.floors] == [5, 5, 6]
    assert summary.num_objects == 41
    utility = next(r for f in summary.floors for r in f.rooms if r.category == "utility_room")
    assert utility.connected == ()
    assert [f.up_portal for f in summary.floors] == [(69, 741), (72, 726), None]


@pytest.mark.gibson
def test_summary_of_building_without_maps(gibson_root: Path) -> None:
    from sgplan.errors import SceneError
    from sgplan.scene.gibson_npz import load_gibson_npz

    building = load_gibson_npz(gibson_root / "3DSceneGraph_Benevolence.npz")
    summary = summarize(building)
    assert summary.robot_radius_m is None and all(f.free_cells is None for f in summary.floors)
    assert summary.num_objects > 0 and summary.stairs == ()
    assert "no maps" in "\n".join(summary_lines(summary))
    with pytest.raises(SceneError, match="no maps"):
        build_occupancy_grid(building, 0.1)
