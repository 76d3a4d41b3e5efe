"""The compact cell graph the planner searches: traversable cells only, indexed 0..N-1.

Cells are numbered floor by floor, within a floor room by room (ascending room id), and within a room in
raster order. So each floor is a contiguous index range, which lets every per-cell array be a flat
``int32``/``float64`` array of length N instead of a full raster and a product state a single integer;
and each room is one too, so what is written over one room (a composite action's map, confined to its
room; a search's pages) fills whole memory pages instead of a slice of every raster row it crosses.

Nothing of the graph is sized by the whole raster: a cell is named by its key
``((floor * G + group) * rows + row) * cols + col`` (``group`` = rank of its room id among the room ids
of traversable cells, G of them), keys ascend with the cell index, and a raster position is found by
computing its key (room id from the grid's room raster) and binary search. Edges follow
:mod:`sgplan.scene.grid`: 8-connected steps into traversable cells (Euclidean step cost in metres) and
stairs between portal cells.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numba import njit

from sgplan.errors import SceneError
from sgplan.planning._dijkstra import dijkstra, flood
from sgplan.planning._memory import sparse_zeros
from sgplan.scene.grid import OccupancyGrid

# (d_row, d_col) of the 8 moves; action code k of an occupancy step is the index here.
STEPS = np.array([(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)], dtype=np.int64)


@dataclass(eq=False)
class CellGraph:
    """Traversable cells of an :class:`OccupancyGrid` and the moves between them.

    Attributes
    ----------
    shape:
        ``(floors, rows, cols)`` of the grid.
    cell_key:
        ``(N,)`` ascending key of each cell (see the module docstring; int32 when the key range allows,
        else int64).
    room_map:
        the grid's ``(floors, rows, cols)`` room raster (the grid's own array, not a copy), and
    room_group:
        ``(65536,)`` int32: the group of each int16 room id (at ``id + 32768``), -1 for ids of no cell;
        ``num_groups`` groups. Together they give the key of a raster position.
    cell_floor:
        ``(N,)`` int32 floor of each cell (:attr:`cell_row` / :attr:`cell_col` and :meth:`positions` are
        computed on use).
    floor_offset:
        ``(floors + 1,)`` int64: cells of floor ``f`` are ``floor_offset[f] .. floor_offset[f+1] - 1``.
    nbr:
        ``(N, 8)`` int32 neighbour cell per move of :data:`STEPS`, -1 where the move is not allowed.
    step_cost:
        ``(8,)`` metres of each move.
    stairs_from, stairs_to, stairs_cost:
        ``(S,)`` stairs moves (both directions of every link), sorted by ``stairs_from``.
    stairs_first:
        ``(N,)`` int32: index of the first stairs move leaving the cell; for a cell without stairs an
        index whose move does not leave it (0: lazily committed zeros, written only at the portals, so
        4 bytes a portal instead of a cell). Readers walk ``j = stairs_first[c]`` while
        ``stairs_from[j] == c``.
    origin_m, resolution_m, floor_z_m:
        the grid's frame (see :class:`OccupancyGrid`), for :attr:`cell_xyz`.
    """

    shape: tuple[int, int, int]
    cell_key: np.ndarray
    room_map: np.ndarray
    room_group: np.ndarray
    num_groups: int
    cell_floor: np.ndarray
    floor_offset: np.ndarray
    nbr: np.ndarray
    step_cost: np.ndarray
    stairs_from: np.ndarray
    stairs_to: np.ndarray
    stairs_cost: np.ndarray
    stairs_first: np.ndarray
    origin_m: tuple[float, float]
    resolution_m: tuple[float, float]
    floor_z_m: np.ndarray

    @property
    def num_cells(self) -> int:
        return int(self.cell_floor.shape[0])

    @cached_property
    def centre_tables(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(x of each row, y of each column, z of each floor)`` float64 metres: cell ``c``'s centre is
        ``(x[cell_row[c]], y[cell_col[c]], z[cell_floor[c]])``, the same values as :attr:`cell_xyz`
        without its 24 bytes a cell (the search reads them so, for h_LLM)."""
        _, rows, cols = self.shape
        return (
            self.origin_m[0] + (np.arange(rows, dtype=np.int32) + 0.5) * self.resolution_m[0],
            self.origin_m[1] + (np.arange(cols, dtype=np.int32) + 0.5) * self.resolution_m[1],
            np.asarray(self.floor_z_m, dtype=np.float64),
        )

    @property
    def cell_xyz(self) -> np.ndarray:
        """``(N, 3)`` float64 metric cell centres (z: the grid's floor height), computed on each access."""
        x, y, z = self.centre_tables
        return np.stack([x[self.cell_row], y[self.cell_col], z[self.cell_floor]], axis=1)

    @property
    def cell_row(self) -> np.ndarray:
        """``(N,)`` int32 row of each cell, computed on each access (4 bytes a cell, not kept)."""
        _, rows, cols = self.shape
        row = self.cell_key // cols
        row %= rows
        return row.astype(np.int32, copy=False)

    @property
    def cell_col(self) -> np.ndarray:
        """``(N,)`` int32 column of each cell, computed on each access (4 bytes a cell, not kept)."""
        return (self.cell_key % self.shape[2]).astype(np.int32, copy=False)

    def positions(self) -> np.ndarray:
        """``(N,)`` flat raster position ``(floor * rows + row) * cols + col`` of every cell (int32 when the
        raster allows, else int64), computed on each call."""
        floors, rows, cols = self.shape
        dtype = np.int32 if floors * rows * cols < 2**31 else np.int64
        plane = rows * cols
        within = (self.cell_key % plane).astype(dtype, copy=False)  # row * cols + col
        within += self.cell_floor.astype(dtype) * dtype(plane)
        return within

    def cell_ids(self, positions: np.ndarray) -> np.ndarray:
        """The cell index (int64) at each flat raster position of ``positions``, -1 where the position is
        not a cell (not traversable). Positions must lie inside the raster."""
        return _ids_at(self.cell_key, self.room_map, self.room_group, self.num_groups, positions)

    def cell_id(self, row: int, col: int, floor: int) -> int:
        """Index of cell ``(row, col, floor)``, -1 if it is outside the grid or not traversable."""
        f, r, c = self.shape
        if not (0 <= floor < f and 0 <= row < r and 0 <= col < c):
            return -1
        return int(self.cell_ids(np.array([(floor * r + row) * c + col]))[0])

    def gather(self, raster: np.ndarray) -> np.ndarray:
        """The values of a ``(floors, rows, cols)`` raster at every cell, as an ``(N,)`` array."""
        return raster.reshape(-1)[self.positions()]

    def distances(
        self, sources: np.ndarray, out: np.ndarray | None = None,
        costs: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> np.ndarray:
        """Exact metres from every cell to the nearest of ``sources`` (cell indices), stairs included.

        ``inf`` where no source can be reached. Written into ``out`` (float64, ``(N,)``, any content) when
        given, which is returned. ``costs``: other positive ``(step, stairs)`` costs of the same moves
        (shapes of ``step_cost`` / ``stairs_cost``) in place of the metres.
        """
        step_cost, stairs_cost = (self.step_cost, self.stairs_cost) if costs is None else costs
        n = self.num_cells
        dist = np.zeros(n, dtype=np.float64) if out is None else out
        dist[:] = 0.0
        pred = np.zeros(n, dtype=np.uint8)
        order = np.empty(n, dtype=np.int32)
        dijkstra(
            self.nbr, step_cost, self.stairs_first, self.stairs_from, self.stairs_to, stairs_cost,
            0, n, True, np.asarray(sources, dtype=np.int64), _NO_ROOMS, np.int32(-1), 0, dist, pred, order,
        )
        dist[pred == 0] = np.inf
        return dist

    def reachable(self, start: int) -> np.ndarray:
        """``(N,)`` bool: the cells reachable from cell ``start`` (steps and stairs); a flood fill."""
        seen = np.zeros(self.num_cells, dtype=np.bool_)
        flood(self.nbr, self.stairs_first, self.stairs_from, self.stairs_to, start, seen)
        return seen


_NO_ROOMS = np.zeros(0, dtype=np.int16)  # the dtype of a domain's cell_room: one compiled dijkstra for both


def _ids_at(
    cell_key: np.ndarray, room_map: np.ndarray, room_group: np.ndarray, num_groups: int, positions: np.ndarray
) -> np.ndarray:
    """:meth:`CellGraph.cell_ids` from the graph's parts."""
    positions = np.asarray(positions, dtype=np.int64)
    _, rows, cols = room_map.shape
    plane = rows * cols
    group = room_group[room_map.reshape(-1)[positions].astype(np.int64) + 32768]
    ids = _find(cell_key, (positions // plane * num_groups + group) * plane + positions % plane)
    ids[group < 0] = -1  # a room id of no cell: the key would name a cell of another group
    return ids


def _find(cell_key: np.ndarray, keys: np.ndarray) -> np.ndarray:
    """Int64 index into the ascending ``cell_key`` of each of ``keys``, -1 where absent."""
    if cell_key.shape[0] == 0:
        return np.full(keys.shape, -1, dtype=np.int64)
    # Searched in cell_key's dtype (a mixed-dtype search converts all of cell_key on every call); keys
    # beyond its range cannot be present.
    info = np.iinfo(cell_key.dtype)
    valid = (keys >= info.min) & (keys <= info.max)
    wanted = np.where(valid, keys, 0).astype(cell_key.dtype, copy=False)
    ids = np.searchsorted(cell_key, wanted).astype(np.int64, copy=False)
    ids[ids >= cell_key.shape[0]] = 0
    return np.where(valid & (cell_key[ids] == wanted), ids, -1)


@njit(cache=True)
def _room_ids(traversable, room_map, present):
    """Mark in ``present`` (at ``id + 32768``) the room id of every traversable cell."""
    floors, rows, cols = traversable.shape
    for f in range(floors):
        for r in range(rows):
            for c in range(cols):
                if traversable[f, r, c]:
                    present[room_map[f, r, c] + 32768] = True


@njit(cache=True)
def _tabulate(traversable, room_map, room_group, num_groups, cell_key, cell_floor, nbr):
    """Number the traversable cells of ``traversable`` (floors, rows, cols) by (floor, room group, raster
    order) into ``cell_key`` / ``cell_floor``, and fill ``nbr`` (N, 8) per :data:`STEPS`. Scratch is a
    counter per group and the cell indices of three raster rows, not a raster: rows are numbered in
    raster order (each group's counter advancing), one row ahead of the row whose moves are filled."""
    floors, rows, cols = traversable.shape
    slots = floors * num_groups
    start = np.zeros(slots + 1, dtype=np.int64)
    for f in range(floors):
        for r in range(rows):
            for c in range(cols):
                if traversable[f, r, c]:
                    start[f * num_groups + room_group[room_map[f, r, c] + 32768] + 1] += 1
    for g in range(slots):
        start[g + 1] += start[g]
    near = np.full((3, cols), -1, dtype=np.int64)  # cell index per column of rows r-1, r, r+1 (mod 3)
    for f in range(floors):
        for r in range(-1, rows):
            ahead = r + 1
            if ahead < rows:
                b = ahead % 3
                for c in range(cols):
                    if traversable[f, ahead, c]:
                        g = f * num_groups + room_group[room_map[f, ahead, c] + 32768]
                        i = start[g]
                        start[g] += 1
                        near[b, c] = i
                        cell_key[i] = (g * rows + ahead) * cols + c
                        cell_floor[i] = f
                    else:
                        near[b, c] = -1
            if r < 0:
                continue
            for c in range(cols):
                i = near[r % 3, c]
                if i < 0:
                    continue
                for k in range(8):
                    r2 = r + STEPS[k, 0]
                    c2 = c + STEPS[k, 1]
                    nbr[i, k] = near[r2 % 3, c2] if 0 <= r2 < rows and 0 <= c2 < cols else -1


def build_cell_graph(grid: OccupancyGrid) -> CellGraph:
    """Index the traversable cells of ``grid`` and tabulate their moves (compiled, one pass per table).

    Raises
    ------
    SceneError
        if a stairs link costs zero or less (shortest paths need positive edge costs), or a room id does
        not fit int16.
    """
    floors, rows, cols = grid.shape
    traversable = np.ascontiguousarray(grid.traversable, dtype=np.bool_)
    if grid.room_map.dtype != np.int16 and grid.room_map.size and not (
        int(grid.room_map.min()) >= -(1 << 15) and int(grid.room_map.max()) < 1 << 15
    ):
        raise SceneError(
            f"room raster holds ids {int(grid.room_map.min())}..{int(grid.room_map.max())}; room ids must "
            "fit int16 (the grid's room_map dtype)"
        )
    room_map = np.ascontiguousarray(grid.room_map, dtype=np.int16)
    present = np.zeros(1 << 16, dtype=np.bool_)
    _room_ids(traversable, room_map, present)
    num_groups = int(present.sum())
    room_group = np.full(1 << 16, -1, dtype=np.int32)
    room_group[present] = np.arange(num_groups, dtype=np.int32)
    n = int(np.count_nonzero(traversable))
    keys = floors * max(num_groups, 1) * rows * cols
    cell_key = np.empty(n, dtype=np.int32 if keys < 2**31 else np.int64)
    cell_floor = np.empty(n, dtype=np.int32)
    nbr = np.empty((n, 8), dtype=np.int32)
    _tabulate(traversable, room_map, room_group, num_groups, cell_key, cell_floor, nbr)
    res_x, res_y = grid.resolution_m
    step_cost = np.hypot(STEPS[:, 0] * res_x, STEPS[:, 1] * res_y).astype(np.float64)

    moves = []
    for link in grid.stairs:
        if not link.cost_m > 0:
            raise SceneError(
                f"stairs between floors {link.lower_floor} and {link.upper_floor} cost {link.cost_m} m; "
                "a stairs cost must be positive metres"
            )
        low, up = _ids_at(cell_key, room_map, room_group, num_groups, np.array([
            (link.lower_floor * rows + link.lower_cell[0]) * cols + link.lower_cell[1],
            (link.upper_floor * rows + link.upper_cell[0]) * cols + link.upper_cell[1],
        ]))
        if low >= 0 and up >= 0:
            moves += [(low, up, link.cost_m), (up, low, link.cost_m)]
    moves.sort()
    stairs_from = np.array([m[0] for m in moves], dtype=np.int32)
    stairs_to = np.array([m[1] for m in moves], dtype=np.int32)
    stairs_cost = np.array([m[2] for m in moves], dtype=np.float64)
    stairs_first = sparse_zeros(n, np.int32)
    for j in range(len(moves) - 1, -1, -1):
        stairs_first[stairs_from[j]] = j

    return CellGraph(
        shape=(floors, rows, cols),
        cell_key=cell_key,
        room_map=room_map,
        room_group=room_group,
        num_groups=num_groups,
        cell_floor=cell_floor,
        floor_offset=np.searchsorted(cell_floor, np.arange(floors + 1)).astype(np.int64),
        nbr=nbr,
        step_cost=step_cost,
        stairs_from=stairs_from,
        stairs_to=stairs_to,
        stairs_cost=stairs_cost,
        stairs_first=stairs_first,
        origin_m=(float(grid.origin_m[0]), float(grid.origin_m[1])),
        resolution_m=(float(res_x), float(res_y)),
        floor_z_m=np.asarray(grid.floor_z_m, dtype=np.float64),
    )
