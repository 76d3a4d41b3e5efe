"""Occupancy grid: the authors' footprint kernel and inflation, grid construction, exact distances.

The Gibson tests check the numbers of reference-algorithm.md §10 (free cells and 8-connected components
per floor, app kernel with each scene's radius_config radius) and §11 (the authors' gtest costs on
Benevolence, r = 0.1 m, gtest kernel).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import ndimage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from sgplan.errors import PlanningError, SceneError
from sgplan.scene.footprint import FootprintKernel, footprint_kernel, footprint_vertices, inflate
from sgplan.scene.grid import (
    OccupancyGrid,
    build_occupancy_grid,
    component_sizes,
    floor_heights_m,
    stairs_links,
)
from sgplan.scene.model import CatCode, StairsEnd
from sgplan.scene.synthetic import generate_building
from tests.scene.distances import grid_distances
from tests.scene.small_buildings import random_small_building

# Floor 0 geometry of the three scenes (building.yaml), to check kernels without the data.
GEOMETRY = {
    "Allensville": ((-1.22132, -1.2061899999999999), (0.009993166175024583, 0.00998801510248112)),
    "Benevolence": ((-3.9349700000000003, -8.69993), (0.009985776293823039, 0.009991059907834101)),
    "Collierville": ((-3.5129900000000003, -2.19346), (0.009995334476843911, 0.010004318398474737)),
}


# --- footprint -------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("scene", "radius", "cells"),
    [("Allensville", 0.15, 766), ("Benevolence", 0.2, 1329), ("Collierville", 0.08, 234)],
)
def test_app_kernel_sizes_match_reference(scene: str, radius: float, cells: int) -> None:
    origin, res = GEOMETRY[scene]
    kernel = footprint_kernel(radius, origin, res)
    assert kernel.size == cells
    # Roughly a disk of radius r/res cells around the anchor.
    offsets = kernel.offsets * np.asarray(res)
    assert np.hypot(offsets[:, 0], offsets[:, 1]).max() < radius + 2 * max(res)


def inflate_reference(obstacles: np.ndarray, kernel: FootprintKernel) -> np.ndarray:
    """Slow, direct twin of :func:`inflate` (``scipy.ndimage.binary_dilation``): its test oracle."""
    offsets = kernel.offsets
    half = int(np.abs(offsets).max()) if len(offsets) else 0
    # scipy's dilation mirrors its structure about the centre (a true Minkowski sum), OpenCV's does not:
    # feed scipy the mirrored kernel, padded so that the anchor sits at the centre.
    structure = np.zeros((2 * half + 1, 2 * half + 1), dtype=bool)
    structure[half - offsets[:, 0], half - offsets[:, 1]] = True
    return ndimage.binary_dilation(obstacles, structure=structure)


def test_footprint_variants() -> None:
    app, gtest = footprint_vertices(0.1, "app"), footprint_vertices(0.1, "gtest")
    assert app.shape == gtest.shape == (360, 2)
    np.testing.assert_allclose(gtest[0], gtest[-1], atol=1e-15)  # 0 and 2*pi both present
    assert not np.allclose(app[0], app[-1])
    np.testing.assert_allclose(np.hypot(*app.T), 0.1)
    with pytest.raises(ValueError):
        footprint_vertices(0.1, "other")  # type: ignore[arg-type]
    with pytest.raises(SceneError, match="radius"):
        footprint_kernel(-0.1, (0, 0), (0.01, 0.01))


def test_inflate_uses_opencv_convention() -> None:
    """``out[p] = any(obstacle[p + d])``: one obstacle cell o spreads to o - d for every offset d."""
    kernel = footprint_kernel(0.05, (-0.013, -0.027), (0.01, 0.01))
    obstacles = np.zeros((40, 40), dtype=bool)
    obstacles[20, 20] = True
    expected = {(20 - dr, 20 - dc) for dr, dc in kernel.offsets.tolist()}
    assert set(map(tuple, np.argwhere(inflate(obstacles, kernel)).tolist())) == expected


@settings(max_examples=40)
@given(
    seed=st.integers(0, 2**32 - 1),
    radius=st.floats(0.005, 0.12),
    origin=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    variant=st.sampled_from(["app", "gtest"]),
)
def test_fast_inflation_equals_binary_dilation(
    seed: int, radius: float, origin: tuple[float, float], variant: str
) -> None:
    rng = np.random.default_rng(seed)
    obstacles = rng.random((37, 53)) < rng.uniform(0.001, 0.3)
    kernel = footprint_kernel(radius, origin, (0.01, 0.0123), variant)  # type: ignore[arg-type]
    np.testing.assert_array_equal(inflate(obstacles, kernel), inflate_reference(obstacles, kernel))


# --- grid construction -------------------------------------------------------------------------------


def test_zero_radius_grid_is_ground_in_rooms_plus_portals() -> None:
    building = generate_building(num_floors=2, rooms_per_floor=3, num_objects=6, seed=3)
    grid = build_occupancy_grid(building, 0.0)
    assert grid.shape == (2, *building.grid_shape)
    for floor in building.floors:
        expected = (floor.cat_map == CatCode.GROUND) & (floor.room_map > 0)
        np.testing.assert_array_equal(grid.traversable[floor.index], expected)
        np.testing.assert_array_equal(grid.room_map[floor.index], floor.room_map)
    (link,) = grid.stairs
    assert (link.lower_floor, link.upper_floor) == (0, 1)
    assert link.lower_cell == building.floors[0].up_stairs.portal
    assert link.cost_m == building.floors[0].up_stairs.cost_m
    assert grid.origin_m == building.floors[0].origin_m and grid.resolution_m == building.resolution_m


def test_inflation_spares_stairs_and_forces_portals_free() -> None:
    building = generate_building(num_floors=2, rooms_per_floor=2, num_objects=0, seed=5)
    floor = building.floors[0]
    # Put a portal right against a wall: inflation would block it, the grid must force it free.
    wall = np.argwhere(floor.cat_map == CatCode.WALL)
    r, c = next(
        (int(r), int(c))
        for r, c in wall
        if floor.cat_map[r + 1, c] == CatCode.GROUND and floor.room_map[r + 1, c] > 0
    )
    up = floor.up_stairs
    floor.up_stairs = StairsEnd(up.room_id, up.room_uuid, (r + 1, c), up.cost_m)
    down = building.floors[1].down_stairs
    building.floors[1].down_stairs = StairsEnd(up.room_id, up.room_uuid, down.portal, up.cost_m)
    grid = build_occupancy_grid(building, 0.2)
    assert grid.traversable[0, r + 1, c]
    assert not build_occupancy_grid(building, 0.2).traversable[0, r + 1, c + 2]  # its neighbour is blocked
    # Ground right next to the stairs (and 0.2 m away from anything else) stays free: stairs never inflate.
    stairs = floor.cat_map == CatCode.STAIRS_UP
    near_stairs = np.zeros_like(stairs)
    near_stairs[1:] |= stairs[:-1]
    near_stairs &= floor.cat_map == CatCode.GROUND
    assert near_stairs.any()
    ground_only = build_occupancy_grid(building, 0.0).traversable[0]
    assert grid.traversable[0][near_stairs].sum() > 0.5 * ground_only[near_stairs].sum()
    # Stairs stay obstacles.
    assert not grid.traversable[0][stairs].any()


def test_bad_radius_and_inconsistent_stairs() -> None:
    building = generate_building(num_floors=2, rooms_per_floor=1, num_objects=0, seed=1)
    with pytest.raises(SceneError, match="radius"):
        build_occupancy_grid(building, -0.1)
    with pytest.raises(SceneError, match="radius"):
        build_occupancy_grid(building, float("nan"))
    up = building.floors[0].up_stairs
    building.floors[0].up_stairs = StairsEnd(up.room_id, up.room_uuid, up.portal, up.cost_m + 1.0)
    with pytest.raises(SceneError, match="differs by direction"):
        stairs_links(building)
    building.floors[0].up_stairs = None
    with pytest.raises(SceneError, match="floor 0 up stairs are missing"):
        stairs_links(building)
    building.floors[0].up_stairs = StairsEnd(up.room_id, up.room_uuid, (10_000, 3), up.cost_m)
    with pytest.raises(SceneError, match="outside"):
        build_occupancy_grid(building, 0.0)


def test_floor_heights_use_smallest_gap() -> None:
    building = generate_building(num_floors=3, rooms_per_floor=1, num_objects=0, seed=2)
    ground = [f.ground_z_m for f in building.floors]
    gap = min(ground[1] - ground[0], ground[2] - ground[1])
    np.testing.assert_allclose(floor_heights_m(building), [ground[0], ground[0] + gap, ground[0] + 2 * gap])
    one = generate_building(num_floors=1, rooms_per_floor=1, num_objects=0, seed=2)
    np.testing.assert_allclose(floor_heights_m(one), [one.floors[0].ground_z_m])


# --- exact distances -------------------------------------------------------------------------------


def _oracle_distances(grid: OccupancyGrid, source: tuple[int, int, int]) -> np.ndarray:
    """Independent oracle: the same graph as a scipy sparse matrix, solved by csgraph.dijkstra."""
    floors, rows, cols = grid.shape
    index = np.arange(floors * rows * cols).reshape(floors, rows, cols)
    res_x, res_y = grid.resolution_m
    heads, tails, weights = [], [], []
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            if dr == dc == 0:
                continue
            src = index[:, max(0, -dr) : rows - max(0, dr), max(0, -dc) : cols - max(0, dc)]
            dst = index[:, max(0, dr) : rows + min(0, dr) or None, max(0, dc) : cols + min(0, dc) or None]
            ok = grid.traversable.ravel()[dst.ravel()]
            heads.append(src.ravel()[ok])
            tails.append(dst.ravel()[ok])
            weights.append(np.full(int(ok.sum()), np.hypot(dr * res_x, dc * res_y)))
    for link in grid.stairs:
        a = index[link.lower_floor, link.lower_cell[0], link.lower_cell[1]]
        b = index[link.upper_floor, link.upper_cell[0], link.upper_cell[1]]
        heads.append(np.array([a, b]))
        tails.append(np.array([b, a]))
        weights.append(np.array([link.cost_m, link.cost_m]))
    n = floors * rows * cols
    edges = (np.concatenate(heads), np.concatenate(tails))
    matrix = coo_matrix((np.concatenate(weights), edges), shape=(n, n)).tocsr()
    start = index[source[2], source[0], source[1]]
    return dijkstra(matrix, indices=start).reshape(floors, rows, cols)


@settings(max_examples=30)
@given(seed=st.integers(0, 2**32 - 1), pick=st.integers(0, 10**6))
def test_grid_distances_match_sparse_dijkstra(seed: int, pick: int) -> None:
    building = random_small_building(seed)
    grid = build_occupancy_grid(building, 0.0)
    free = np.argwhere(grid.traversable)
    floor, row, col = (int(v) for v in free[pick % len(free)])
    ours = grid_distances(grid, [(row, col, floor)])
    np.testing.assert_allclose(ours, _oracle_distances(grid, (row, col, floor)), rtol=0, atol=1e-9)


def test_grid_distances_multi_source_and_untraversable_source() -> None:
    building = generate_building(num_floors=2, rooms_per_floor=2, num_objects=2, seed=4)
    grid = build_occupancy_grid(building, 0.15)
    a, b = (10, 10, 0), (int(grid.stairs[0].upper_cell[0]), int(grid.stairs[0].upper_cell[1]), 1)
    both = grid_distances(grid, [a, b])
    np.testing.assert_allclose(both, np.minimum(grid_distances(grid, [a]), grid_distances(grid, [b])))
    assert not grid.traversable[0, 10, 10] and both[0, 10, 10] == 0.0  # a source need not be traversable
    assert np.isinf(both[0][building.floors[0].cat_map == CatCode.WALL]).all()
    with pytest.raises(PlanningError, match="outside the grid"):
        grid_distances(grid, [(0, 0, 5)])
    with pytest.raises(PlanningError, match="at least one"):
        grid_distances(grid, [])


# --- Gibson scenes ---------------------------------------------------------------------------------

FREE_CELLS = {
    "Allensville": ([209_285], [[207_488, 1_453, 189, 155]]),
    "Benevolence": ([93_302, 177_258, 106_263], [[93_302], [177_258], [96_352, 6_915, 1_679, 1_317]]),
    "Collierville": ([174_846, 194_988, 133_512], [[174_846], [194_988], [133_503, 9]]),
}


@pytest.mark.gibson
@pytest.mark.parametrize("scene", sorted(FREE_CELLS))
def test_gibson_free_cells_and_components(gibson_root: Path, scene: str) -> None:
    from sgplan.scene.authors import load_authors_scene

    building = load_authors_scene(gibson_root / scene)
    grid = build_occupancy_grid(building, building.robot_radius_m)
    free, components = FREE_CELLS[scene]
    assert grid.traversable.sum(axis=(1, 2)).tolist() == free
    assert [c.tolist() for c in component_sizes(grid)] == components
    for link in grid.stairs:  # portals are free after inflation
        assert grid.traversable[link.lower_floor][link.lower_cell]
        assert grid.traversable[link.upper_floor][link.upper_cell]


@pytest.mark.gibson
def test_benevolence_reproduces_authors_gtest_costs(gibson_root: Path) -> None:
    from sgplan.scene.authors import load_authors_scene

    building = load_authors_scene(gibson_root / "Benevolence")
    grid = build_occupancy_grid(building, 0.1, footprint="gtest")
    dist = grid_distances(grid, [(400, 900, 1)])
    assert dist[1, 450, 200] == pytest.approx(8.701223, abs=1e-6)
    assert dist[2, 400, 800] == pytest.approx(15.485639, abs=1e-6)
    assert [(s.lower_floor, s.lower_cell, s.upper_cell) for s in grid.stairs] == [
        (0, (69, 741), (74, 381)),
        (1, (72, 726), (86, 397)),
    ]
    assert [round(s.cost_m, 4) for s in grid.stairs] == [4.4679, 4.2050]
