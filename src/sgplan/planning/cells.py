"""The compact cell graph the planner searches: traversable cells only, indexed 0..N-1.

Cells are numbered floor by floor, within a floor room by room (ascending room id), and within a room in
raster order. So each floor is a contiguous index range, which lets every per-cell array be a flat
``int32``/``float64`` array of length N instead of a full raster and a product state a single integer;
and each room is one too, so what is written over one room (a composite action's map, confined to its
room; a search's pages) fills whole memory pages instead of a slice of every raster row it crosses.

Moves are not tabulated per cell. A **padded raster index** ``cell_at`` holds, for every position of the
grid with one extra cell on every side of each floor (``(floors, rows + 2, cols + 2)``, flat), the index
of the cell there or -1 (not traversable, or padding); ``cell_pos[c]`` is cell ``c``'s position in it.
Move ``k`` of :data:`STEPS` leads from ``c`` to ``cell_at[cell_pos[c] + step_offset[k]]`` (-1: not
allowed), ``step_offset[k] = d_row * (cols + 2) + d_col``: the padding keeps every lookup in bounds, so
it takes no branch, and never reaches another floor. A raster position is found by a lookup too
(:meth:`CellGraph.cell_ids`). Edges follow :mod:`sgplan.scene.grid`: 8-connected steps into traversable
cells (Euclidean step cost in metres; a diagonal step needs only its target cell traversable) and stairs
between portal cells.

Memory: 4 bytes per padded raster position (``cell_at``) plus 5 per cell (``cell_pos`` int32,
``cell_floor`` uint8), against 40 per cell for a per-cell table of the 8 neighbours (32 bytes) with a
sort key and an int32 floor. The index costs less whenever more than 4 / 35 = 11.4 % of the padded
raster is traversable, as the Gibson scenes and the synthetic scaling buildings are
(benchmarks/results/cell_graph_raster_index.md). On a very sparse raster it costs more, since it pays
for every blocked position: at 5 % traversable 85 bytes a cell instead of 40, at 1 % 405. It is still the
default: the grid itself (``traversable`` 1 byte, ``room_map`` 2 bytes) and the label raster (1-4 bytes)
already take 4-7 bytes per raster position, so the index at most about doubles what the rasters cost and
never changes the order of a building's memory, while every expansion and every Dijkstra step reads its
8 moves from 3 neighbouring raster rows shared with the cells around it (faster Dijkstra fields, the
search unchanged: cell_graph_raster_index.md) and a position is found by one read, not a binary search.
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
        ``(floors, rows, cols)`` of the grid; the padded raster is ``(floors, rows + 2, cols + 2)``
        (:attr:`padded_shape`), position ``(f, r, c)`` of the grid at ``(f, r + 1, c + 1)``.
    cell_at:
        ``(floors * (rows + 2) * (cols + 2),)`` int32: the padded raster index, the cell at each flat
        padded position, -1 where there is none (not traversable, or the padding).
    cell_pos:
        ``(N,)`` flat padded position of each cell (int32 when the padded raster allows, else int64);
        :attr:`cell_row` / :attr:`cell_col` and :meth:`positions` are computed from it on use.
    cell_floor:
        ``(N,)`` floor of each cell, in the smallest unsigned dtype that holds the floor numbers (uint8 up
        to 256 floors).
    floor_offset:
        ``(floors + 1,)`` int64: cells of floor ``f`` are ``floor_offset[f] .. floor_offset[f+1] - 1``.
    step_offset:
        ``(8,)`` int64: move ``k`` of :data:`STEPS` leads from cell ``c`` to
        ``cell_at[cell_pos[c] + step_offset[k]]`` (-1: the move is not allowed); :meth:`neighbours`.
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
    cell_at: np.ndarray
    cell_pos: np.ndarray
    cell_floor: np.ndarray
    floor_offset: np.ndarray
    step_offset: np.ndarray
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
        return int(self.cell_pos.shape[0])

    @property
    def padded_shape(self) -> tuple[int, int, int]:
        """``(floors, rows + 2, cols + 2)``: the raster :attr:`cell_at` indexes (flat)."""
        floors, rows, cols = self.shape
        return floors, rows + 2, cols + 2

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
        _, prows, pcols = self.padded_shape
        row = self.cell_pos // pcols
        row %= prows
        row -= 1
        return row.astype(np.int32, copy=False)

    @property
    def cell_col(self) -> np.ndarray:
        """``(N,)`` int32 column of each cell, computed on each access (4 bytes a cell, not kept)."""
        col = self.cell_pos % self.padded_shape[2]
        col -= 1
        return col.astype(np.int32, copy=False)

    def row_col(self, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(rows, cols)`` int64 of the given cells only (:attr:`cell_row` / :attr:`cell_col` compute every
        cell's)."""
        _, prows, pcols = self.padded_shape
        row, col = np.divmod(self.cell_pos[np.asarray(cells, dtype=np.int64)].astype(np.int64), pcols)
        return row % prows - 1, col - 1

    def positions(self) -> np.ndarray:
        """``(N,)`` flat raster position ``(floor * rows + row) * cols + col`` of every cell (int32 when the
        raster allows, else int64), computed on each call."""
        floors, rows, cols = self.shape
        dtype = np.int32 if floors * rows * cols < 2**31 else np.int64
        _, prows, pcols = self.padded_shape
        # padded = floor * prows * pcols + (row + 1) * pcols + col + 1
        #        = position + floor * (prows * pcols - rows * cols) + 2 * row + pcols + 1
        position = self.cell_pos.copy()
        position -= self.cell_row.astype(position.dtype, copy=False) * 2 + (pcols + 1)
        position -= self.cell_floor.astype(position.dtype) * (prows * pcols - rows * cols)
        return position.astype(dtype, copy=False)

    def padded(self, positions: np.ndarray) -> np.ndarray:
        """The flat padded positions (int64) of flat raster positions ``(floor * rows + row) * cols + col``
        (which must lie inside the raster)."""
        _, rows, cols = self.shape
        _, prows, pcols = self.padded_shape
        positions = np.asarray(positions, dtype=np.int64)
        floor, within = np.divmod(positions, rows * cols)
        return positions + floor * (prows * pcols - rows * cols) + within // cols * 2 + (pcols + 1)

    def cell_ids(self, positions: np.ndarray) -> np.ndarray:
        """The cell index (int64) at each flat raster position of ``positions``, -1 where the position is
        not a cell (not traversable). Positions must lie inside the raster."""
        return self.cell_at[self.padded(positions)].astype(np.int64)

    def cell_id(self, row: int, col: int, floor: int) -> int:
        """Index of cell ``(row, col, floor)``, -1 if it is outside the grid or not traversable."""
        f, r, c = self.shape
        if not (0 <= floor < f and 0 <= row < r and 0 <= col < c):
            return -1
        return int(self.cell_ids(np.array([(floor * r + row) * c + col]))[0])

    def neighbours(self, cells: np.ndarray | None = None) -> np.ndarray:
        """``(n, 8)`` int32: the cell each move of :data:`STEPS` leads to from each of ``cells`` (all cells
        when None), -1 where the move is not allowed. Computed on each call."""
        pos = self.cell_pos if cells is None else self.cell_pos[np.asarray(cells, dtype=np.int64)]
        return self.cell_at[pos[:, None] + self.step_offset]

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
            self.cell_at, self.cell_pos, self.step_offset, step_cost, self.stairs_first, self.stairs_from,
            self.stairs_to, stairs_cost, 0, n, True, np.asarray(sources, dtype=np.int64), _NO_ROOMS,
            np.int32(-1), 0, dist, pred, order,
        )
        dist[pred == 0] = np.inf
        return dist

    def reachable(self, start: int) -> np.ndarray:
        """``(N,)`` bool: the cells reachable from cell ``start`` (steps and stairs); a flood fill."""
        seen = np.zeros(self.num_cells, dtype=np.bool_)
        flood(self.cell_at, self.cell_pos, self.step_offset, self.stairs_first, self.stairs_from,
              self.stairs_to, np.array([start], dtype=np.int64), seen)
        return seen


_NO_ROOMS = np.zeros(0, dtype=np.int16)  # the dtype of a domain's cell_room: one compiled dijkstra for both


@njit(cache=True, nogil=True)
def _room_ids(traversable, room_map, present):
    """Mark in ``present`` (at ``id + 32768``) the room id of every traversable cell."""
    floors, rows, cols = traversable.shape
    for f in range(floors):
        for r in range(rows):
            for c in range(cols):
                if traversable[f, r, c]:
                    present[room_map[f, r, c] + 32768] = True


@njit(cache=True, nogil=True)
def _tabulate(traversable, room_map, room_group, num_groups, cell_at, cell_pos, cell_floor, floor_offset):
    """Number the traversable cells of ``traversable`` (floors, rows, cols) by (floor, room group, raster
    order) into ``cell_pos`` / ``cell_floor`` / ``floor_offset``, and fill the padded raster index
    ``cell_at`` (every position, the padding -1 too): one counting pass, one numbering pass, each
    group's counter advancing in raster order."""
    floors, rows, cols = traversable.shape
    prows, pcols = rows + 2, cols + 2
    slots = floors * num_groups
    start = np.zeros(slots + 1, dtype=np.int64)
    for f in range(floors):
        for r in range(rows):
            for c in range(cols):
                if traversable[f, r, c]:
                    start[f * num_groups + room_group[room_map[f, r, c] + 32768] + 1] += 1
    for g in range(slots):
        start[g + 1] += start[g]
    for f in range(floors + 1):
        floor_offset[f] = start[f * num_groups]
    for f in range(floors):
        base = f * prows * pcols
        for p in range(base, base + pcols):  # the padding row above the floor
            cell_at[p] = -1
        for r in range(rows):
            p = base + (r + 1) * pcols
            cell_at[p] = -1  # the padding column on the left
            for c in range(cols):
                p += 1
                if traversable[f, r, c]:
                    g = f * num_groups + room_group[room_map[f, r, c] + 32768]
                    i = start[g]
                    start[g] += 1
                    cell_at[p] = i
                    cell_pos[i] = p
                    cell_floor[i] = f
                else:
                    cell_at[p] = -1
            cell_at[p + 1] = -1  # and on the right
        for p in range(base + (rows + 1) * pcols, base + prows * pcols):  # the padding row below
            cell_at[p] = -1


def build_cell_graph(grid: OccupancyGrid) -> CellGraph:
    """Index the traversable cells of ``grid`` and their padded raster (compiled, two passes).

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
    padded = floors * (rows + 2) * (cols + 2)
    cell_at = np.empty(padded, dtype=np.int32)
    cell_pos = np.empty(n, dtype=np.int32 if padded < 2**31 else np.int64)
    cell_floor = np.empty(n, dtype=np.min_scalar_type(max(floors - 1, 0)))
    floor_offset = np.empty(floors + 1, dtype=np.int64)
    _tabulate(traversable, room_map, room_group, num_groups, cell_at, cell_pos, cell_floor, floor_offset)
    res_x, res_y = grid.resolution_m
    step_cost = np.hypot(STEPS[:, 0] * res_x, STEPS[:, 1] * res_y).astype(np.float64)
    graph = CellGraph(
        shape=(floors, rows, cols),
        cell_at=cell_at,
        cell_pos=cell_pos,
        cell_floor=cell_floor,
        floor_offset=floor_offset,
        step_offset=STEPS[:, 0] * (cols + 2) + STEPS[:, 1],
        step_cost=step_cost,
        stairs_from=np.zeros(0, dtype=np.int32),
        stairs_to=np.zeros(0, dtype=np.int32),
        stairs_cost=np.zeros(0, dtype=np.float64),
        stairs_first=sparse_zeros(n, np.int32),
        origin_m=(float(grid.origin_m[0]), float(grid.origin_m[1])),
        resolution_m=(float(res_x), float(res_y)),
        floor_z_m=np.asarray(grid.floor_z_m, dtype=np.float64),
    )

    moves = []
    for link in grid.stairs:
        if not link.cost_m > 0:
            raise SceneError(
                f"stairs between floors {link.lower_floor} and {link.upper_floor} cost {link.cost_m} m; "
                "a stairs cost must be positive metres"
            )
        low = graph.cell_id(link.lower_cell[0], link.lower_cell[1], link.lower_floor)
        up = graph.cell_id(link.upper_cell[0], link.upper_cell[1], link.upper_floor)
        if low >= 0 and up >= 0:
            moves += [(low, up, link.cost_m), (up, low, link.cost_m)]
    moves.sort()
    graph.stairs_from = np.array([m[0] for m in moves], dtype=np.int32)
    graph.stairs_to = np.array([m[1] for m in moves], dtype=np.int32)
    graph.stairs_cost = np.array([m[2] for m in moves], dtype=np.float64)
    for j in range(len(moves) - 1, -1, -1):
        graph.stairs_first[graph.stairs_from[j]] = j
    return graph
