"""Floor drawings: files written, colours where they belong, path overlay, errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from sgplan.errors import SceneError
from sgplan.scene.demo import demo_building
from sgplan.scene.distances import grid_distances
from sgplan.scene.draw import draw_building, draw_floor, floor_image, room_colour
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.model import CatCode


def test_floor_image_colours() -> None:
    building = demo_building()
    grid = build_occupancy_grid(building, building.robot_radius_m)
    floor = building.floors[0]
    image = floor_image(building, 0)
    assert image.shape == (*floor.shape, 3) and image.min() >= 0 and image.max() <= 1
    walls = image[floor.cat_map == CatCode.WALL]
    assert (walls.max(axis=1) < 0.3).all()  # dark
    outside = image[floor.cat_map == CatCode.OUTSIDE]
    assert (outside.min(axis=1) > 0.9).all()  # light
    kitchen = building.rooms_named("kitchen")[0]
    ground = (floor.room_map == kitchen.id) & (floor.cat_map == CatCode.GROUND)
    np.testing.assert_allclose(image[ground], np.broadcast_to(room_colour(kitchen.id), image[ground].shape))
    objects = image[floor.cat_map > 0]
    assert len(objects) and np.ptp(objects, axis=0).max() == 0  # one object colour
    shaded = floor_image(building, 0, grid)
    blocked = ground & ~grid.traversable[0]
    assert blocked.any() and (shaded[blocked].sum(axis=1) < image[blocked].sum(axis=1)).all()


def test_draw_building_writes_one_png_per_floor(tmp_path: Path) -> None:
    building = demo_building()
    grid = build_occupancy_grid(building, building.robot_radius_m)
    start = building.initial_cells[0]
    goal = building.initial_cells[-1]
    # A real path: walk down the distance field from the goal to the start.
    dist = grid_distances(grid, [start])
    path = [goal]
    while path[-1] != start:
        r, c, f = path[-1]
        link = next((s for s in grid.stairs if f == s.upper_floor and (r, c) == s.upper_cell), None)
        via_stairs = link is not None and dist[link.lower_floor][link.lower_cell] + link.cost_m
        if link is not None and via_stairs == pytest.approx(dist[f, r, c]):
            path.append((*link.lower_cell, link.lower_floor))
            continue
        window = dist[f, r - 1 : r + 2, c - 1 : c + 2]
        dr, dc = np.unravel_index(int(np.argmin(window)), window.shape)
        path.append((r + int(dr) - 1, c + int(dc) - 1, f))
    written = draw_building(building, tmp_path / "out", grid=grid, path=path[::-1])
    assert [p.name for p in written] == ["floor_0.png", "floor_1.png"]
    for png in written:
        with Image.open(png) as image:
            assert image.format == "PNG" and image.width > 500 and image.height > 500
            pixels = np.asarray(image.convert("RGB"))
        # The path is drawn in red on both floors.
        red = (pixels[..., 0] > 200) & (pixels[..., 1] < 80) & (pixels[..., 2] < 80)
        assert red.sum() > 100


def test_draw_errors(tmp_path: Path) -> None:
    building = demo_building()
    with pytest.raises(SceneError, match="no floor 5"):
        draw_floor(building, 5)
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(SceneError, match="cannot create"):
        draw_building(building, blocker / "sub")


@pytest.mark.gibson
def test_draw_benevolence(gibson_root: Path, tmp_path: Path) -> None:
    from sgplan.scene.authors import load_authors_scene

    building = load_authors_scene(gibson_root / "Benevolence")
    written = draw_building(building, tmp_path, grid=build_occupancy_grid(building, building.robot_radius_m))
    assert len(written) == 3 and all(p.stat().st_size > 20_000 for p in written)
