"""The compact cell graph the planner searches: traversable cells only, indexed 0..N-1.

Cells are numbered floor by floor in raster order (so each floor is a contiguous index range), which
lets every per-cell array be a flat ``int32``/``float64`` array of length N instead of a full raster, and
a product state be the single integer ``cell * Q + q``. Edges follow :mod:`sgplan.scene.grid`: 8-connected
steps into traversable cells (Euclidean step cost in metres) and stairs between portal cells.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sgplan.planning._dijkstra import dijkstra
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
    index:
        ``(floors * rows * cols,)`` int32: the cell index of each raster position, -1 if not traversable.
    cell_floor, cell_row, cell_col:
        ``(N,)`` int32 position of each cell.
    floor_offset:
        ``(floors + 1,)`` int64: cells of floor ``f`` are ``floor_offset[f] .. floor_offset[f+1] - 1``.
    nbr:
        ``(N, 8)`` int32 neighbour cell per move of :data:`STEPS`, -1 where the move is not allowed.
    step_cost:
        ``(8,)`` metres of each move.
    stairs_from, stairs_to, stairs_cost:
        ``(S,)`` stairs moves (both directions of every link), sorted by ``stairs_from``.
    stairs_first:
        ``(N,)`` int32: index of the first stairs move leaving the cell, -1 if none.
    cell_xyz:
        ``(N, 3)`` metric cell centres; z is the grid's floor height (``OccupancyGrid.floor_z_m``).
    """

    shape: tuple[int, int, int]
    index: np.ndarray
    cell_floor: np.ndarray
    cell_row: np.ndarray
    cell_col: np.ndarray
    floor_offset: np.ndarray
    nbr: np.ndarray
    step_cost: np.ndarray
    stairs_from: np.ndarray
    stairs_to: np.ndarray
    stairs_cost: np.ndarray
    stairs_first: np.ndarray
    cell_xyz: np.ndarray

    @property
    def num_cells(self) -> int:
        return int(self.cell_floor.shape[0])

    def cell_id(self, row: int, col: int, floor: int) -> int:
        """Index of cell ``(row, col, floor)``, -1 if it is outside the grid or not traversable."""
        f, r, c = self.shape
        if not (0 <= floor < f and 0 <= row < r and 0 <= col < c):
            return -1
        return int(self.index[(floor * r + row) * c + col])

    def gather(self, raster: np.ndarray) -> np.ndarray:
        """The values of a ``(floors, rows, cols)`` raster at every cell, as an ``(N,)`` array."""
        _, r, c = self.shape
        flat = (self.cell_floor.astype(np.int64) * r + self.cell_row) * c + self.cell_col
        return raster.reshape(-1)[flat]

    def distances(self, sources: np.ndarray) -> np.ndarray:
        """Exact metres from every cell to the nearest of ``sources`` (cell indices), stairs included.

        ``inf`` where no source can be reached.
        """
        n = self.num_cells
        dist = np.zeros(n, dtype=np.float64)
        pred = np.zeros(n, dtype=np.int32)
        order = np.empty(n, dtype=np.int32)
        dijkstra(
            self.nbr, self.step_cost, self.stairs_first, self.stairs_from, self.stairs_to, self.stairs_cost,
            0, n, True, np.asarray(sources, dtype=np.int64), _NO_ROOMS, np.int32(-1), 0, dist, pred, order,
        )
        dist[pred == 0] = np.inf
        return dist


_NO_ROOMS = np.zeros(0, dtype=np.int32)


def build_cell_graph(grid: OccupancyGrid) -> CellGraph:
    """Index the traversable cells of ``grid`` and tabulate their moves (vectorised)."""
    floors, rows, cols = grid.shape
    flat = np.flatnonzero(grid.traversable.reshape(-1))
    n = flat.shape[0]
    index = np.full(floors * rows * cols, -1, dtype=np.int32)
    index[flat] = np.arange(n, dtype=np.int32)
    floor, rest = np.divmod(flat, rows * cols)
    row, col = np.divmod(rest, cols)

    res_x, res_y = grid.resolution_m
    nbr = np.full((n, 8), -1, dtype=np.int32)
    for k, (d_row, d_col) in enumerate(STEPS):
        r2, c2 = row + d_row, col + d_col
        inside = (r2 >= 0) & (r2 < rows) & (c2 >= 0) & (c2 < cols)
        nbr[inside, k] = index[(floor[inside] * rows + r2[inside]) * cols + c2[inside]]
    step_cost = np.hypot(STEPS[:, 0] * res_x, STEPS[:, 1] * res_y).astype(np.float64)

    moves = []
    for link in grid.stairs:
        low = index[(link.lower_floor * rows + link.lower_cell[0]) * cols + link.lower_cell[1]]
        up = index[(link.upper_floor * rows + link.upper_cell[0]) * cols + link.upper_cell[1]]
        if low >= 0 and up >= 0:
            moves += [(low, up, link.cost_m), (up, low, link.cost_m)]
    moves.sort()
    stairs_from = np.array([m[0] for m in moves], dtype=np.int32)
    stairs_to = np.array([m[1] for m in moves], dtype=np.int32)
    stairs_cost = np.array([m[2] for m in moves], dtype=np.float64)
    stairs_first = np.full(n, -1, dtype=np.int32)
    for j in range(len(moves) - 1, -1, -1):
        stairs_first[stairs_from[j]] = j

    cell_xyz = np.stack(
        [
            grid.origin_m[0] + (row + 0.5) * res_x,
            grid.origin_m[1] + (col + 0.5) * res_y,
            np.asarray(grid.floor_z_m, dtype=np.float64)[floor],
        ],
        axis=1,
    )
    return CellGraph(
        shape=(floors, rows, cols),
        index=index,
        cell_floor=floor.astype(np.int32),
        cell_row=row.astype(np.int32),
        cell_col=col.astype(np.int32),
        floor_offset=np.searchsorted(floor, np.arange(floors + 1)).astype(np.int64),
        nbr=nbr,
        step_cost=step_cost,
        stairs_from=stairs_from,
        stairs_to=stairs_to,
        stairs_cost=stairs_cost,
        stairs_first=stairs_first,
        cell_xyz=cell_xyz,
    )
