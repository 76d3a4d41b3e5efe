"""The compact cell graph the planner searches: traversable cells only, indexed 0..N-1.

Cells are numbered floor by floor in raster order (so each floor is a contiguous index range), which
lets every per-cell array be a flat ``int32``/``float64`` array of length N instead of a full raster, and
a product state be the single integer ``cell * Q + q``. Nothing of the graph is sized by the whole
raster: a raster position is found among the cells' (ascending) positions by binary search. Edges follow
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
    cell_pos:
        ``(N,)`` ascending flat raster position ``(floor * rows + row) * cols + col`` of each cell (int32
        when the raster allows, else int64).
    cell_floor:
        ``(N,)`` int32 floor of each cell (:attr:`cell_row` / :attr:`cell_col` are computed on use).
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
    cell_pos: np.ndarray
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
    def cell_xyz(self) -> np.ndarray:
        """``(N, 3)`` float64 metric cell centres; z is the grid's floor height. Built on first use (only
        h_LLM needs it: 24 bytes a cell)."""
        xyz = np.empty((self.num_cells, 3), dtype=np.float64)
        xyz[:, 0] = self.origin_m[0] + (self.cell_row + 0.5) * self.resolution_m[0]
        xyz[:, 1] = self.origin_m[1] + (self.cell_col + 0.5) * self.resolution_m[1]
        xyz[:, 2] = np.asarray(self.floor_z_m, dtype=np.float64)[self.cell_floor]
        return xyz

    @property
    def cell_row(self) -> np.ndarray:
        """``(N,)`` int32 row of each cell, computed on each access (4 bytes a cell, not kept)."""
        _, rows, cols = self.shape
        row = self.cell_pos // cols
        row %= rows
        return row.astype(np.int32, copy=False)

    @property
    def cell_col(self) -> np.ndarray:
        """``(N,)`` int32 column of each cell, computed on each access (4 bytes a cell, not kept)."""
        return (self.cell_pos % self.shape[2]).astype(np.int32, copy=False)

    def cell_ids(self, positions: np.ndarray) -> np.ndarray:
        """The cell index (int64) at each flat raster position of ``positions``, -1 where the position is
        not a cell (not traversable). Positions must lie inside the raster."""
        return _cell_ids(self.cell_pos, positions)

    def cell_id(self, row: int, col: int, floor: int) -> int:
        """Index of cell ``(row, col, floor)``, -1 if it is outside the grid or not traversable."""
        f, r, c = self.shape
        if not (0 <= floor < f and 0 <= row < r and 0 <= col < c):
            return -1
        return int(self.cell_ids(np.array([(floor * r + row) * c + col]))[0])

    def window_ids(self, floor: int, rows: slice, cols: slice) -> np.ndarray:
        """The cell index (int64, -1 where not a cell) of every position of the window ``[rows, cols]`` of
        ``floor`` (slices with start and stop inside the raster, step 1): one binary search per window
        row, then a walk over that row's cells."""
        _, n_rows, n_cols = self.shape
        out = np.full((rows.stop - rows.start, cols.stop - cols.start), -1, dtype=np.int64)
        _window(self.cell_pos, (floor * n_rows + rows.start) * n_cols + cols.start, n_cols, out)
        return out

    def gather(self, raster: np.ndarray) -> np.ndarray:
        """The values of a ``(floors, rows, cols)`` raster at every cell, as an ``(N,)`` array."""
        return raster.reshape(-1)[self.cell_pos]

    def distances(self, sources: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """Exact metres from every cell to the nearest of ``sources`` (cell indices), stairs included.

        ``inf`` where no source can be reached. Written into ``out`` (float64, ``(N,)``, any content) when
        given, which is returned.
        """
        n = self.num_cells
        dist = np.zeros(n, dtype=np.float64) if out is None else out
        dist[:] = 0.0
        pred = np.zeros(n, dtype=np.int32)
        order = np.empty(n, dtype=np.int32)
        dijkstra(
            self.nbr, self.step_cost, self.stairs_first, self.stairs_from, self.stairs_to, self.stairs_cost,
            0, n, True, np.asarray(sources, dtype=np.int64), _NO_ROOMS, np.int32(-1), 0, dist, pred, order,
        )
        dist[pred == 0] = np.inf
        return dist

    def reachable(self, start: int) -> np.ndarray:
        """``(N,)`` bool: the cells reachable from cell ``start`` (steps and stairs); a flood fill."""
        seen = np.zeros(self.num_cells, dtype=np.bool_)
        flood(self.nbr, self.stairs_first, self.stairs_from, self.stairs_to, start, seen)
        return seen


_NO_ROOMS = np.zeros(0, dtype=np.int32)


@njit(cache=True)
def _window(cell_pos, first, stride, out):
    """``out[i, j]`` = index of the cell at raster position ``first + i * stride + j``, where there is one
    (``out`` holds -1 before)."""
    for i in range(out.shape[0]):
        start = first + i * stride
        k = np.searchsorted(cell_pos, start)
        while k < cell_pos.shape[0] and cell_pos[k] < start + out.shape[1]:
            out[i, cell_pos[k] - start] = k
            k += 1


def _cell_ids(cell_pos: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Int64 index into the ascending ``cell_pos`` of each of ``positions`` (raster positions), -1 where
    absent."""
    # In cell_pos's dtype: a mixed-dtype search would convert all of cell_pos on every call.
    positions = np.asarray(positions).astype(cell_pos.dtype, copy=False)
    if cell_pos.shape[0] == 0:
        return np.full(positions.shape, -1, dtype=np.int64)
    ids = np.searchsorted(cell_pos, positions).astype(np.int64, copy=False)
    ids[ids >= cell_pos.shape[0]] = 0
    return np.where(cell_pos[ids] == positions, ids, -1)


@njit(cache=True)
def _tabulate(traversable, cell_pos, cell_floor, nbr):
    """Number the traversable cells of ``traversable`` (floors, rows, cols) in raster order into
    ``cell_pos`` / ``cell_floor``, then fill ``nbr`` (N, 8) per :data:`STEPS`. Scratch is a few rows,
    not a raster: a row's cell indices are rebuilt from its first cell's index when needed."""
    floors, rows, cols = traversable.shape
    row_first = np.empty(floors * rows, dtype=np.int64)
    n = 0
    for f in range(floors):
        for r in range(rows):
            row_first[f * rows + r] = n
            for c in range(cols):
                if traversable[f, r, c]:
                    cell_pos[n] = (f * rows + r) * cols + c
                    cell_floor[n] = f
                    n += 1
    near = np.empty((3, cols), dtype=np.int64)  # cell index per column of rows r-1, r, r+1 (-1: none)
    for f in range(floors):
        for r in range(rows):
            for d in range(3):
                r2 = r + d - 1
                i = row_first[f * rows + r2] if 0 <= r2 < rows else 0
                for c in range(cols):
                    if 0 <= r2 < rows and traversable[f, r2, c]:
                        near[d, c] = i
                        i += 1
                    else:
                        near[d, c] = -1
            for c in range(cols):
                i = near[1, c]
                if i < 0:
                    continue
                for k in range(8):
                    c2 = c + STEPS[k, 1]
                    nbr[i, k] = near[STEPS[k, 0] + 1, c2] if 0 <= c2 < cols else -1


def build_cell_graph(grid: OccupancyGrid) -> CellGraph:
    """Index the traversable cells of ``grid`` and tabulate their moves (compiled, one pass per table).

    Raises
    ------
    SceneError
        if a stairs link costs zero or less (shortest paths need positive edge costs).
    """
    floors, rows, cols = grid.shape
    traversable = np.ascontiguousarray(grid.traversable, dtype=np.bool_)
    n = int(np.count_nonzero(traversable))
    cell_pos = np.empty(n, dtype=np.int32 if floors * rows * cols < 2**31 else np.int64)
    cell_floor = np.empty(n, dtype=np.int32)
    nbr = np.empty((n, 8), dtype=np.int32)
    _tabulate(traversable, cell_pos, cell_floor, nbr)
    res_x, res_y = grid.resolution_m
    step_cost = np.hypot(STEPS[:, 0] * res_x, STEPS[:, 1] * res_y).astype(np.float64)

    moves = []
    for link in grid.stairs:
        if not link.cost_m > 0:
            raise SceneError(
                f"stairs between floors {link.lower_floor} and {link.upper_floor} cost {link.cost_m} m; "
                "a stairs cost must be positive metres"
            )
        low, up = _cell_ids(cell_pos, np.array([
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
        cell_pos=cell_pos,
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
