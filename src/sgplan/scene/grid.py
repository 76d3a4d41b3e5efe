"""The occupancy grid of a building: which cells a robot may enter, and the stairs between floors.

Cells are ``(floor, row, col)`` in arrays of shape ``(floors, rows, cols)``; see
:mod:`sgplan.scene.model` for the axis conventions. Moves are 8-connected with Euclidean step cost in
metres (``res_x``, ``res_y`` or ``hypot(res_x, res_y)``); a stairs move joins the two portal cells of a
:class:`StairsLink` at its cost.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sgplan.scene.model import Cell


@dataclass(frozen=True)
class StairsLink:
    """Stairs between ``lower_cell`` on ``lower_floor`` and ``upper_cell`` on ``lower_floor + 1``.

    Taken in either direction at ``cost_m`` metres.
    """

    lower_floor: int
    lower_cell: Cell
    upper_cell: Cell
    cost_m: float

    @property
    def upper_floor(self) -> int:
        return self.lower_floor + 1


@dataclass(eq=False)
class OccupancyGrid:
    """Traversability of every cell of every floor for one robot radius.

    Attributes
    ----------
    traversable:
        ``(floors, rows, cols)`` bool: an occupancy move may enter the cell. True iff the cell is GROUND,
        clear of the inflated obstacles (robot footprint, stairs exempt from inflation) and inside a room
        (room id > 0) -- or it is a stairs portal, which is always traversable.
    room_map:
        ``(floors, rows, cols)`` int16: the room id of every cell (``NO_ROOM`` outside rooms).
    resolution_m:
        ``(res_x, res_y)``: metres per cell along rows and along columns.
    origin_m:
        metric ``(x, y)`` of the grid corner (floor 0's; all floors share the frame).
    floor_z_m:
        ``(floors,)`` metric height used for 3-D distances between floors (the authors' frame:
        ``ground_z_0 + k * min floor gap``).
    stairs:
        one link per pair of consecutive floors that has stairs.
    robot_radius_m:
        the radius the obstacles were inflated with.
    """

    traversable: np.ndarray
    room_map: np.ndarray
    resolution_m: tuple[float, float]
    origin_m: tuple[float, float]
    floor_z_m: np.ndarray
    stairs: tuple[StairsLink, ...]
    robot_radius_m: float

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(floors, rows, cols)``."""
        f, r, c = self.traversable.shape
        return (int(f), int(r), int(c))

    def is_traversable(self, floor: int, cell: Cell) -> bool:
        """Whether ``cell`` on ``floor`` lies in the grid and may be entered."""
        f, rows, cols = self.shape
        row, col = cell
        return 0 <= floor < f and 0 <= row < rows and 0 <= col < cols and bool(
            self.traversable[floor, row, col]
        )

    def cell_xyz(self, floor: int, cell: Cell) -> tuple[float, float, float]:
        """Metric centre ``(x, y, z)`` of a cell, in the frame used for 3-D distances."""
        return (
            self.origin_m[0] + (cell[0] + 0.5) * self.resolution_m[0],
            self.origin_m[1] + (cell[1] + 0.5) * self.resolution_m[1],
            float(self.floor_z_m[floor]),
        )
