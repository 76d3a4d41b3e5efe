"""The compact cell graph and its compiled traversals (bucketed Dijkstra, flood fill) against scipy."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra as scipy_dijkstra

from sgplan.errors import SceneError
from sgplan.planning._dijkstra import (
    PRED_NONE,
    PRED_SOURCE,
    PRED_STAIRS,
    PRED_STEP,
    dijkstra,
    label_runs,
    next_cell,
)
from sgplan.planning.cells import STEPS, build_cell_graph
from sgplan.planning.domain import compact_labels, label_index_dtype, room_index_dtype, stop_counts
from sgplan.scene.grid import OccupancyGrid, StairsLink


def _random_grid(seed: int, res: tuple[float, float], stairs_cost: float) -> OccupancyGrid:
    """Two floors of random walls (about 30 % blocked) and one stairs link, at resolution ``res``."""
    rng = np.random.default_rng(seed)
    floors, rows, cols = 2, int(rng.integers(3, 14)), int(rng.integers(3, 14))
    traversable = rng.random((floors, rows, cols)) > 0.3
    low = (int(rng.integers(rows)), int(rng.integers(cols)))
    up = (int(rng.integers(rows)), int(rng.integers(cols)))
    traversable[0][low] = traversable[1][up] = True
    return OccupancyGrid(
        traversable=traversable,
        room_map=np.ones((floors, rows, cols), dtype=np.int16),
        resolution_m=res,
        origin_m=(0.0, 0.0),
        floor_z_m=np.array([0.0, 3.0]),
        stairs=(StairsLink(0, low, up, stairs_cost),),
        robot_radius_m=0.0,
    )


def _steps(graph) -> tuple[np.ndarray, ...]:
    """The arrays that give a cell's steps (``cell_at[cell_pos[c] + step_offset[k]]``)."""
    return graph.cell_at, graph.cell_pos, graph.step_offset


def _moves(graph) -> tuple[np.ndarray, ...]:
    """The cell graph's move arrays in the order the Dijkstra kernel takes them."""
    return (*_steps(graph), graph.step_cost, graph.stairs_first, graph.stairs_from, graph.stairs_to,
            graph.stairs_cost)


def _scipy_distances(grid: OccupancyGrid, graph, sources: np.ndarray) -> np.ndarray:
    """Distances over the compact cells, from an independently built sparse matrix (raster moves)."""
    heads, tails, weights = [], [], []
    floors, rows, cols = grid.shape
    for f in range(floors):
        for r in range(rows):
            for c in range(cols):
                a = graph.cell_id(r, c, f)
                for d_row, d_col in STEPS:
                    b = graph.cell_id(r + d_row, c + d_col, f)
                    if a >= 0 and b >= 0:
                        heads.append(a)
                        tails.append(b)
                        weights.append(np.hypot(d_row * grid.resolution_m[0], d_col * grid.resolution_m[1]))
    for link in grid.stairs:
        a = graph.cell_id(*link.lower_cell, link.lower_floor)
        b = graph.cell_id(*link.upper_cell, link.upper_floor)
        heads += [a, b]
        tails += [b, a]
        weights += [link.cost_m, link.cost_m]
    n = graph.num_cells
    matrix = coo_matrix((weights, (heads, tails)), shape=(n, n)).tocsr()
    return scipy_dijkstra(matrix, indices=sources, min_only=True)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**31 - 1),
    res=st.sampled_from([(0.05, 0.05), (0.05, 0.08), (0.1, 0.03)]),
    stairs_cost=st.sampled_from([4.0, 0.07, 0.001]),  # long, between the step costs, far below them
    num_sources=st.integers(1, 5),
)
def test_distances_match_scipy(seed: int, res, stairs_cost: float, num_sources: int) -> None:
    """Bucketed Dijkstra = scipy's heap Dijkstra (to float rounding) for any resolution and stairs cost,
    including stairs far cheaper than a step (many buckets) and several sources; flood = reachability;
    every predecessor chain is a shortest path."""
    grid = _random_grid(seed, res, stairs_cost)
    graph = build_cell_graph(grid)
    sources = np.random.default_rng(seed).choice(graph.num_cells, min(num_sources, graph.num_cells),
                                                 replace=False)
    ours = graph.distances(sources)
    theirs = _scipy_distances(grid, graph, sources)
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-9)
    assert np.array_equal(graph.reachable(int(sources[0])), np.isfinite(_scipy_distances(grid, graph,
                                                                                         sources[:1])))
    n = graph.num_cells
    assert np.array_equal(STEPS[::-1], -STEPS)  # a step code names the move back: 7 - k undoes k
    dist, pred, order = np.zeros(n), np.zeros(n, np.uint8), np.empty(n, np.int32)
    settled = dijkstra(
        *_moves(graph), 0, n, True, sources.astype(np.int64), np.zeros(0, np.int16), np.int32(-1), 0,
        dist, pred, order,
    )
    assert settled == int(np.isfinite(theirs).sum())
    assert np.all(np.diff(dist[order[:settled]]) >= -graph.step_cost.min())  # settled bucket by bucket
    assert set(np.flatnonzero(pred == PRED_SOURCE)) == set(sources.tolist())
    for cell in order[:settled]:  # every code names a move that realises the cell's distance
        code = int(pred[cell])
        if PRED_STEP <= code < PRED_STAIRS:
            nxt = int(next_cell(*_steps(graph), cell, code))
            assert np.isclose(dist[cell] - dist[nxt], graph.step_cost[code - PRED_STEP], atol=1e-9)
        elif code == PRED_STAIRS:
            into = graph.stairs_to == cell
            step = dist[cell] - dist[graph.stairs_from[into]]
            assert np.isclose(step, graph.stairs_cost[into], atol=1e-9).any()
        else:
            assert code == PRED_SOURCE and dist[cell] == 0.0
    # Label runs (steps only, as a map's run): the last cell of the equal-label stretch, walked naively.
    dist[:], pred[:] = 0.0, PRED_NONE
    settled = dijkstra(
        *_moves(graph), 0, n, False, sources.astype(np.int64), np.zeros(0, np.int16), np.int32(-1), 0,
        dist, pred, order,
    )
    labels = np.random.default_rng(seed + 1).integers(0, 3, n).astype(np.uint8)
    run = np.zeros(n, np.int32)
    label_runs(*_steps(graph), pred, n, labels, 0, run, np.empty(n, np.int32))

    def after(cell: int) -> int:
        return int(next_cell(*_steps(graph), cell, pred[cell])) if pred[cell] >= PRED_STEP else -1

    for cell in range(n):
        last = cell if pred[cell] else -1
        while last >= 0 and after(last) >= 0 and labels[after(last)] == labels[cell]:
            last = after(last)
        assert run[cell] == last + 1
    assert (run > 0).sum() == settled


def test_many_sources_and_early_stop_grow_the_queues() -> None:
    """More sources than the initial bucket capacity; an early stop leaves the stop room exact."""
    rows, cols = 60, 70
    grid = OccupancyGrid(
        traversable=np.ones((1, rows, cols), dtype=bool),
        room_map=np.ones((1, rows, cols), dtype=np.int16),
        resolution_m=(0.05, 0.05), origin_m=(0.0, 0.0), floor_z_m=np.array([0.0]), stairs=(),
        robot_radius_m=0.0,
    )
    graph = build_cell_graph(grid)
    sources = np.arange(0, graph.num_cells, 2)  # 2100 sources
    np.testing.assert_allclose(graph.distances(sources), _scipy_distances(grid, graph, sources), atol=1e-9)
    n = graph.num_cells
    cell_room = (graph.cell_col < 10).astype(np.int16)  # room 1: the first 10 columns
    dist, pred, order = np.zeros(n), np.zeros(n, np.uint8), np.empty(n, np.int32)
    source = np.array([graph.cell_id(30, 0, 0)], dtype=np.int64)
    settled = dijkstra(
        *_moves(graph), 0, n, False, source, cell_room, np.int32(1), int((cell_room == 1).sum()),
        dist, pred, order,
    )
    assert settled < n
    room = cell_room == 1
    assert (pred[room] > 0).all()
    np.testing.assert_allclose(dist[room], _scipy_distances(grid, graph, source)[room], atol=1e-9)


def test_empty_grid_and_extreme_room_ids() -> None:
    grid = _random_grid(5, (0.05, 0.05), 1.0)
    blocked = np.zeros_like(grid.traversable)
    empty = build_cell_graph(dataclasses.replace(grid, traversable=blocked, stairs=()))
    assert empty.num_cells == 0 and empty.cell_id(0, 0, 0) == -1 and list(empty.floor_offset) == [0, 0, 0]
    room_map = np.full(grid.shape, -(1 << 15), dtype=np.int16)
    room_map[1] = (1 << 15) - 1
    graph = build_cell_graph(dataclasses.replace(grid, room_map=room_map))
    index = np.full(grid.traversable.size, -1)
    index[graph.positions()] = np.arange(graph.num_cells)
    assert np.array_equal(graph.cell_ids(np.arange(grid.traversable.size)), index)
    with pytest.raises(SceneError, match="fit int16"):
        build_cell_graph(dataclasses.replace(grid, room_map=room_map.astype(np.int32) + 1))


def _rooms_and_stairs_grid(seed: int) -> OccupancyGrid:
    """1-3 floors of 1-12 x 1-12 cells, mostly traversable (the raster border included), random room ids
    (some negative, some of no traversable cell), and up to 3 stairs links between random portals."""
    rng = np.random.default_rng(seed)
    floors, rows, cols = int(rng.integers(1, 4)), int(rng.integers(1, 13)), int(rng.integers(1, 13))
    traversable = rng.random((floors, rows, cols)) > rng.choice([0.1, 0.4, 0.8])
    room_map = rng.choice(np.array([-7, 0, 2, 5, 9, 300], dtype=np.int16), size=(floors, rows, cols))
    stairs = []
    for _ in range(int(rng.integers(0, 4)) if floors > 1 else 0):
        lower = int(rng.integers(floors - 1))
        low = (int(rng.integers(rows)), int(rng.integers(cols)))
        up = (int(rng.integers(rows)), int(rng.integers(cols)))
        traversable[lower][low] = traversable[lower + 1][up] = True
        stairs.append(StairsLink(lower, low, up, float(rng.uniform(0.5, 5.0))))
    return OccupancyGrid(
        traversable=traversable, room_map=room_map, resolution_m=(0.05, 0.07), origin_m=(0.0, 0.0),
        floor_z_m=np.arange(floors) * 3.0, stairs=tuple(stairs), robot_radius_m=0.0,
    )


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**31 - 1))
def test_moves_equal_an_independent_numpy_neighbourhood(seed: int) -> None:
    """The padded raster index gives, for every cell (border cells included), exactly the 8-neighbourhood
    a plain numpy construction gives: cells numbered by (floor, room id, raster position), a step leads
    to the traversable cell at (row + d_row, col + d_col) of the same floor, whatever its room, and
    nowhere outside the raster; the stairs tables hold both directions of every link."""
    grid = _rooms_and_stairs_grid(seed)
    graph = build_cell_graph(grid)
    floors, rows, cols = grid.shape
    f, r, c = np.nonzero(grid.traversable)
    flat = np.ravel_multi_index((f, r, c), grid.shape)
    order = np.lexsort((flat, grid.room_map[f, r, c], f))
    number = np.full(grid.shape, -1, dtype=np.int64)
    number[f[order], r[order], c[order]] = np.arange(len(order))
    framed = np.pad(number, ((0, 0), (1, 1), (1, 1)), constant_values=-1)
    expected = np.stack(
        [framed[:, 1 + dr : 1 + dr + rows, 1 + dc : 1 + dc + cols][f[order], r[order], c[order]]
         for dr, dc in STEPS],
        axis=1,
    )
    assert graph.num_cells == len(order)
    assert np.array_equal(graph.neighbours(), expected)
    backwards = np.arange(graph.num_cells)[::-1]
    assert np.array_equal(graph.neighbours(backwards), expected[backwards])
    assert np.array_equal(graph.positions(), flat[order])
    assert np.array_equal(graph.cell_floor, f[order]) and graph.cell_floor.dtype == np.uint8
    assert np.array_equal(graph.floor_offset, np.searchsorted(f[order], np.arange(floors + 1)))
    assert graph.cell_pos.dtype == np.int32 and graph.cell_at.dtype == np.int32
    assert graph.cell_at.shape == (floors * (rows + 2) * (cols + 2),)
    assert (graph.cell_at >= 0).sum() == graph.num_cells  # the padding and blocked positions hold -1
    expected_stairs = sorted(
        move
        for link in grid.stairs
        for a, b in [(number[link.lower_floor][link.lower_cell], number[link.upper_floor][link.upper_cell])]
        for move in ((a, b, link.cost_m), (b, a, link.cost_m))
    )
    assert list(zip(graph.stairs_from.tolist(), graph.stairs_to.tolist(), graph.stairs_cost.tolist(),
                    strict=True)) == expected_stairs
    for cell in range(graph.num_cells):
        j, leaving = int(graph.stairs_first[cell]), []
        while 0 <= j < len(graph.stairs_from) and graph.stairs_from[j] == cell:
            leaving.append(j)
            j += 1
        assert leaving == np.flatnonzero(graph.stairs_from == cell).tolist()


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31 - 1))
def test_cell_ids_and_positions_round_trip(seed: int) -> None:
    """cell_ids is a lookup: every raster position gives its cell or -1 (blocked), positions() and
    cell_ids invert each other, cell_id is -1 outside the grid, rows / columns come back from cell_pos."""
    grid = _rooms_and_stairs_grid(seed)
    graph = build_cell_graph(grid)
    floors, rows, cols = grid.shape
    everywhere = graph.cell_ids(np.arange(grid.traversable.size))
    assert everywhere.dtype == np.int64
    assert np.array_equal(everywhere >= 0, grid.traversable.ravel())  # blocked positions: -1
    assert np.array_equal(graph.cell_ids(graph.positions()), np.arange(graph.num_cells))
    assert np.array_equal(everywhere[graph.positions()], np.arange(graph.num_cells))
    assert np.array_equal(graph.cell_at[graph.cell_pos], np.arange(graph.num_cells))
    f, r, c = np.unravel_index(graph.positions(), grid.shape)
    assert np.array_equal(graph.cell_row, r) and np.array_equal(graph.cell_col, c)
    for cell in range(graph.num_cells):
        assert graph.cell_id(int(r[cell]), int(c[cell]), int(f[cell])) == cell
    for floor, row, col in [(0, -1, 0), (0, 0, -1), (0, rows, 0), (0, 0, cols), (floors, 0, 0), (-1, 0, 0)]:
        assert graph.cell_id(row, col, floor) == -1
    for floor, row, col in zip(*np.nonzero(~grid.traversable), strict=True):
        assert graph.cell_id(int(row), int(col), int(floor)) == -1


def test_positions_of_a_raster_past_int32() -> None:
    """A padded raster of more than 2^31 positions stores cell_pos as int64; the position arithmetic
    (no array of that size needed) still inverts, and positions come back as int64."""
    shape = (3, 30_000, 30_000)
    floors, rows, cols = shape
    rng = np.random.default_rng(0)
    cells = np.sort(rng.choice(floors * rows * cols, 1000, replace=False))
    f, r, c = np.unravel_index(cells, shape)
    graph = dataclasses.replace(
        build_cell_graph(_random_grid(0, (0.05, 0.05), 1.0)), shape=shape,
        cell_pos=((f * (rows + 2) + r + 1) * (cols + 2) + c + 1).astype(np.int64),
        cell_floor=f.astype(np.uint8),
    )
    assert graph.padded(cells).max() >= 2**31
    assert np.array_equal(graph.padded(cells), graph.cell_pos)
    assert np.array_equal(graph.positions(), cells) and graph.positions().dtype == np.int64
    assert np.array_equal(graph.cell_row, r) and np.array_equal(graph.cell_col, c)


def test_stairs_must_cost_something() -> None:
    grid = _random_grid(1, (0.05, 0.05), 0.0)
    with pytest.raises(SceneError, match="must be positive"):
        build_cell_graph(grid)


def test_cell_centres_and_gather() -> None:
    grid = _random_grid(3, (0.05, 0.08), 1.0)
    grid.room_map[:] = np.where(np.arange(grid.shape[2]) < 4, 7, 2).astype(np.int16)  # two rooms
    graph = build_cell_graph(grid)
    f, r, c = np.unravel_index(graph.positions(), grid.shape)
    assert grid.traversable[f, r, c].all() and len(set(graph.positions())) == grid.traversable.sum()
    assert np.array_equal(graph.cell_floor, f) and np.array_equal(graph.cell_row, r)
    assert np.array_equal(graph.cell_col, c)
    # Numbered by floor, then room (ascending id), then raster order.
    order = np.lexsort((graph.positions(), grid.room_map[f, r, c], f))
    assert np.array_equal(order, np.arange(graph.num_cells))
    np.testing.assert_allclose(graph.cell_xyz[:, 0], (r + 0.5) * 0.05)
    np.testing.assert_allclose(graph.cell_xyz[:, 1], (c + 0.5) * 0.08)
    np.testing.assert_allclose(graph.cell_xyz[:, 2], np.array([0.0, 3.0])[f])
    raster = np.arange(np.prod(grid.shape)).reshape(grid.shape)
    assert np.array_equal(graph.gather(raster), raster[f, r, c])
    index = np.full(grid.traversable.size, -1)
    index[graph.positions()] = np.arange(graph.num_cells)
    assert np.array_equal(graph.cell_ids(np.arange(grid.traversable.size)), index)
    assert graph.cell_id(int(r[-1]), int(c[-1]), int(f[-1])) == graph.num_cells - 1



def test_centre_tables_give_the_per_cell_centres_bit_for_bit() -> None:
    """The search reads h_LLM's cell centres from per-row / column / floor tables: the same float64 bits
    as the per-cell formula (origin + (index + 0.5) * resolution), on an off-origin grid with several
    rooms (cells numbered out of raster order)."""
    grid = _random_grid(5, (0.05, 0.07), 1.0)
    grid = OccupancyGrid(
        traversable=grid.traversable, room_map=(np.arange(grid.shape[2]) % 3 + 1).astype(np.int16)
        * np.ones(grid.shape, dtype=np.int16), resolution_m=grid.resolution_m, origin_m=(-3.7, 12.3),
        floor_z_m=np.array([0.1, 2.9]), stairs=grid.stairs, robot_radius_m=0.0,
    )
    graph = build_cell_graph(grid)
    f, r, c = np.unravel_index(graph.positions(), grid.shape)
    expected = np.stack([-3.7 + (r + 0.5) * 0.05, 12.3 + (c + 0.5) * 0.07, np.array([0.1, 2.9])[f]], axis=1)
    assert np.array_equal(graph.cell_xyz, expected)
    x, y, z = graph.centre_tables
    _, prows, pcols = graph.padded_shape  # as h_llm_core reads them: row and column from cell_pos
    assert np.array_equal(x[(graph.cell_pos // pcols) % prows - 1], expected[:, 0])
    assert np.array_equal(y[graph.cell_pos % pcols - 1], expected[:, 1])
    assert np.array_equal(z[graph.cell_floor], expected[:, 2])

def test_a_room_confined_run_never_leaves_its_room() -> None:
    """A U-shaped room around another: the confined shortest paths go round the U (longer than across
    the other room) and equal the distances over the room's cells alone."""
    size = 20
    grid = OccupancyGrid(
        traversable=np.ones((1, size, size), dtype=bool), room_map=np.ones((1, size, size), dtype=np.int16),
        resolution_m=(0.05, 0.05), origin_m=(0.0, 0.0), floor_z_m=np.array([0.0]), stairs=(),
        robot_radius_m=0.0,
    )
    graph = build_cell_graph(grid)
    row, col = graph.cell_row, graph.cell_col
    in_u = (col < 5) | (col >= 15) | (row >= 15)
    cell_room = np.where(in_u, 1, 2).astype(np.int16)
    n = graph.num_cells
    dist, pred, order = np.zeros(n), np.zeros(n, np.uint8), np.empty(n, np.int32)
    source = np.array([graph.cell_id(0, 0, 0)], dtype=np.int64)
    settled = dijkstra(
        *_moves(graph), 0, n, False, source, cell_room, np.int32(1), int(in_u.sum()), dist, pred, order,
    )
    assert settled == int(in_u.sum()) and (pred[~in_u] == 0).all()
    room_only = OccupancyGrid(
        traversable=in_u.reshape(1, size, size), room_map=grid.room_map, resolution_m=grid.resolution_m,
        origin_m=(0.0, 0.0), floor_z_m=np.array([0.0]), stairs=(), robot_radius_m=0.0,
    )
    small = build_cell_graph(room_only)
    expected = _scipy_distances(room_only, small, np.array([small.cell_id(0, 0, 0)]))
    np.testing.assert_allclose(dist[in_u], expected, atol=1e-9)
    corner = graph.cell_id(0, size - 1, 0)
    assert dist[corner] > graph.distances(source)[corner] + 1.0


def test_stop_count_ignores_room_cells_cut_off_from_the_sources() -> None:
    """A room with a walled-in pocket: the map's stop count leaves the pocket (unreachable from the start,
    here the source) out, so its Dijkstra stops before exhausting the floor, and every room cell it can
    reach is settled and exact."""
    rows, cols = 30, 60
    traversable = np.ones((1, rows, cols), dtype=bool)
    traversable[0, 2:7, 2] = traversable[0, 2:7, 6] = traversable[0, 2, 2:7] = traversable[0, 6, 2:7] = False
    grid = OccupancyGrid(
        traversable=traversable, room_map=np.ones((1, rows, cols), dtype=np.int16), resolution_m=(0.05, 0.05),
        origin_m=(0.0, 0.0), floor_z_m=np.array([0.0]), stairs=(), robot_radius_m=0.0,
    )
    graph = build_cell_graph(grid)
    cell_room = (graph.cell_col < 10).astype(np.int16)  # room 1: the first 10 columns, pocket included
    source = np.array([graph.cell_id(15, 1, 0)], dtype=np.int64)
    (count,) = stop_counts(cell_room, graph.reachable(int(source[0])), 2, np.array([1], dtype=np.int32))
    assert count == int((cell_room == 1).sum()) - 9  # the 3 x 3 pocket
    n = graph.num_cells
    dist, pred, order = np.zeros(n), np.zeros(n, np.uint8), np.empty(n, np.int32)
    settled = dijkstra(
        *_moves(graph), 0, n, False, source, cell_room, np.int32(1), count, dist, pred, order,
    )
    full = _scipy_distances(grid, graph, source)
    room = (cell_room == 1) & np.isfinite(full)
    assert settled < int(np.isfinite(full).sum()) and (pred[room] > 0).all()
    np.testing.assert_allclose(dist[room], full[room], atol=1e-9)


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), bits=st.sampled_from([1, 5, 22, 30]))
def test_compact_labels_equal_numpy_unique(seed: int, bits: int) -> None:
    """Label ids by lookup table (small label spaces) or by sort (large ones) are np.unique's."""
    rng = np.random.default_rng(seed)
    masks = rng.choice(rng.integers(0, 2**bits, size=7), size=500).astype(np.uint32)
    label_masks, cell_label = compact_labels(masks, 2**bits)
    expected_masks, expected_ids = np.unique(masks, return_inverse=True)
    assert np.array_equal(label_masks, expected_masks) and label_masks.dtype == np.int64
    assert np.array_equal(cell_label, expected_ids) and cell_label.dtype == np.uint8  # 7 labels at most


def test_label_and_room_index_dtypes_hold_every_id() -> None:
    """Compact label ids and room indices are stored in the smallest dtype that holds them all."""
    cases = ((1, np.uint8), (256, np.uint8), (257, np.uint16), (65536, np.uint16), (65537, np.int32))
    for count, dtype in cases:
        assert label_index_dtype(count) == dtype and np.iinfo(dtype).max >= count - 1
    masks = np.arange(300, dtype=np.uint32)
    label_masks, cell_label = compact_labels(masks, 512)
    assert cell_label.dtype == np.uint16 and np.array_equal(label_masks[cell_label], masks)
    assert room_index_dtype(32767) == np.int16 and room_index_dtype(32768) == np.int32
