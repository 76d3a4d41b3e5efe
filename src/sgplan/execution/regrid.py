"""The occupancy grid after a scene change, recomputed only around the cells that changed.

A cell's traversability depends on the categories within the robot's footprint around it
(:func:`sgplan.scene.grid.free_cells`), so a change of some cells' categories can only change the cells
within the kernel's reach of them. :func:`regrid` recomputes that window (with a margin of the kernel's
reach for the inflation to see every obstacle that matters) and leaves the rest of the grid as it was;
the result equals :func:`sgplan.scene.grid.build_occupancy_grid` of the changed building.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from sgplan.scene.grid import OccupancyGrid, free_cells, grid_kernel
from sgplan.scene.model import Building


@dataclass(frozen=True)
class GridChange:
    """Cells whose traversability changed, as flat positions ``(floor * rows + row) * cols + col`` of the
    grid (int64, ascending): ``blocked`` were traversable and are no longer, ``freed`` the reverse."""

    blocked: np.ndarray
    freed: np.ndarray

    @property
    def empty(self) -> bool:
        return self.blocked.size == 0 and self.freed.size == 0


def kernel_reach(building: Building, robot_radius_m: float) -> tuple[int, int]:
    """How many cells (rows, columns) away a category change can change traversability."""
    kernel = grid_kernel(building, robot_radius_m)
    if kernel is None:
        return (0, 0)
    offsets = np.abs(kernel.offsets)
    return int(offsets[:, 0].max()), int(offsets[:, 1].max())


def regrid(
    grid: OccupancyGrid, building: Building, cells: dict[int, np.ndarray]
) -> tuple[OccupancyGrid, GridChange]:
    """The grid of ``building`` (the changed building) from ``grid`` (the grid before the change, same
    robot radius), given the cells whose category changed (floor -> flat positions ``row * cols + col``),
    and which cells changed traversability. Costs a copy of the traversable raster and the inflation of
    a window around the changed cells.

    Stairs portals stay traversable, as :func:`~sgplan.scene.grid.build_occupancy_grid` keeps them.
    """
    _, rows, cols = grid.shape
    kernel = grid_kernel(building, grid.robot_radius_m)
    reach_r, reach_c = kernel_reach(building, grid.robot_radius_m)
    traversable = grid.traversable
    blocked: list[np.ndarray] = []
    freed: list[np.ndarray] = []
    portals = {(link.lower_floor, *link.lower_cell) for link in grid.stairs}
    portals |= {(link.upper_floor, *link.upper_cell) for link in grid.stairs}
    for f, changed in sorted(cells.items()):
        if changed.size == 0:
            continue
        if traversable is grid.traversable:
            traversable = grid.traversable.copy()
        rr, cc = np.divmod(changed, cols)
        # The window whose cells may change, and around it the cells whose categories decide them.
        r0, r1 = max(int(rr.min()) - reach_r, 0), min(int(rr.max()) + reach_r + 1, rows)
        c0, c1 = max(int(cc.min()) - reach_c, 0), min(int(cc.max()) + reach_c + 1, cols)
        s0, s1 = max(r0 - reach_r, 0), min(r1 + reach_r, rows)
        t0, t1 = max(c0 - reach_c, 0), min(c1 + reach_c, cols)
        plan = building.floors[f]
        free = free_cells(plan.cat_map[s0:s1, t0:t1], plan.room_map[s0:s1, t0:t1], kernel)
        new = free[r0 - s0 : r1 - s0, c0 - t0 : c1 - t0]
        for pf, pr, pc in portals:
            if pf == f and r0 <= pr < r1 and c0 <= pc < c1:
                new[pr - r0, pc - c0] = True
        old = traversable[f, r0:r1, c0:c1]
        for mask, out in ((old & ~new, blocked), (~old & new, freed)):
            wr, wc = np.nonzero(mask)
            out.append(((f * rows + wr + r0) * cols + wc + c0).astype(np.int64))
        traversable[f, r0:r1, c0:c1] = new
    if traversable is grid.traversable:
        none = np.zeros(0, dtype=np.int64)
        return grid, GridChange(none, none)
    change = GridChange(np.sort(np.concatenate(blocked)), np.sort(np.concatenate(freed)))
    return replace(grid, traversable=traversable), change
