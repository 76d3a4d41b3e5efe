"""The occupancy grid of a building: which cells a robot may enter, and the stairs between floors.

Cells are ``(floor, row, col)`` in arrays of shape ``(floors, rows, cols)``; see
:mod:`sgplan.scene.model` for the axis conventions. Moves are 8-connected with Euclidean step cost in
metres (``res_x``, ``res_y`` or ``hypot(res_x, res_y)``); a stairs move joins the two portal cells of a
:class:`StairsLink` at its cost.

:func:`build_occupancy_grid` builds the grid exactly as the authors' planner does
(the authors' occupancy rule); the planner's domain computes shortest distances over it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sgplan.errors import SceneError
from sgplan.scene.footprint import FootprintKernel, FootprintVariant, footprint_kernel, inflate
from sgplan.scene.model import Building, CatCode, Cell


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


def floor_heights_m(building: Building) -> np.ndarray:
    """Metric height of every floor in the authors' 3-D frame (reference-algorithm.md §2.1), metres.

    ``z_k = ground_z_0 + k * fh`` with ``fh`` the smallest gap between consecutive floors' ``ground_z``
    (2.0 m for a one-floor building). Using the smallest gap keeps straight-line distances between
    floors below every real stairs cost, so 3-D Euclidean heuristics stay admissible.
    """
    ground = np.array([floor.ground_z_m for floor in building.floors], dtype=np.float64)
    gap = float(np.min(np.diff(ground))) if len(ground) > 1 else 2.0
    return ground[0] + gap * np.arange(len(ground), dtype=np.float64)


def stairs_links(building: Building) -> tuple[StairsLink, ...]:
    """One :class:`StairsLink` per pair of consecutive floors joined by stairs, costs as given.

    Floor ``k``'s up stairs must meet floor ``k+1``'s down stairs with the same cost; a pair whose cost
    is infinite has no usable stairs and gets no link (as in the authors' planner).

    Raises
    ------
    SceneError
        if only one end of a staircase exists, or the two ends disagree on the cost.
    """
    links = []
    for lower, upper in zip(building.floors, building.floors[1:]):
        up, down = lower.up_stairs, upper.down_stairs
        if up is None and down is None:
            continue
        if up is None or down is None:
            missing, present = (f"floor {lower.index} up", f"floor {upper.index} down")
            if up is not None:
                missing, present = present, missing
            raise SceneError(
                f"building {building.name!r}: {present} stairs exist but {missing} stairs are missing; "
                "both ends of a staircase need a portal"
            )
        if not np.isclose(up.cost_m, down.cost_m, rtol=1e-9, atol=1e-9) and not (
            np.isinf(up.cost_m) and np.isinf(down.cost_m)
        ):
            raise SceneError(
                f"building {building.name!r}: stairs cost between floors {lower.index} and {upper.index} "
                f"differs by direction (up {up.cost_m} m, down {down.cost_m} m)"
            )
        if np.isfinite(up.cost_m):
            links.append(
                StairsLink(
                    lower_floor=lower.index,
                    lower_cell=(int(up.portal[0]), int(up.portal[1])),
                    upper_cell=(int(down.portal[0]), int(down.portal[1])),
                    cost_m=float(up.cost_m),
                )
            )
    return tuple(links)


def build_occupancy_grid(
    building: Building,
    robot_radius_m: float,
    footprint: FootprintVariant = "app",
) -> OccupancyGrid:
    """The occupancy grid of ``building`` for a robot of ``robot_radius_m`` metres, as the authors build it.

    Per floor (reference-algorithm.md §2.2): obstacles are all non-GROUND cells; with a radius > 0 the
    obstacles other than stairs are inflated with the authors' footprint kernel (``footprint`` selects the
    app's or the unit tests' vertex set, see :mod:`sgplan.scene.footprint`) and the stairs are put back;
    a cell is traversable iff it is free and its room id is > 0. Every stairs portal is then forced
    traversable. The kernel is quantised in floor 0's frame, as in the authors' code.

    Raises
    ------
    SceneError
        for a building without rasters, a negative or non-finite radius, a portal outside the grid, or
        inconsistent stairs.
    """
    if not all(floor.has_maps for floor in building.floors):
        raise SceneError(
            f"building {building.name!r} has no maps (read from a raw 3D Scene Graph .npz?); an occupancy "
            "grid needs a scene with category and room maps (the authors' folder or sgplan's format)"
        )
    if not np.isfinite(robot_radius_m) or robot_radius_m < 0:
        raise SceneError(f"robot radius must be a non-negative number of metres, got {robot_radius_m}")
    floor0 = building.floors[0]
    kernel = grid_kernel(building, robot_radius_m, footprint)
    shape = (building.num_floors, *building.grid_shape)
    traversable = np.empty(shape, dtype=bool)
    room_map = np.empty(shape, dtype=np.int16)
    for floor in building.floors:
        traversable[floor.index] = free_cells(floor.cat_map, floor.room_map, kernel)
        room_map[floor.index] = floor.room_map
    links = stairs_links(building)
    for link in links:
        for floor_index, cell in ((link.lower_floor, link.lower_cell), (link.upper_floor, link.upper_cell)):
            if not (0 <= cell[0] < shape[1] and 0 <= cell[1] < shape[2]):
                raise SceneError(
                    f"building {building.name!r}: stairs portal {cell} of floor {floor_index} lies outside "
                    f"the {shape[1]}x{shape[2]} grid"
                )
            traversable[floor_index, cell[0], cell[1]] = True
    return OccupancyGrid(
        traversable=traversable,
        room_map=room_map,
        resolution_m=(float(floor0.resolution_m[0]), float(floor0.resolution_m[1])),
        origin_m=(float(floor0.origin_m[0]), float(floor0.origin_m[1])),
        floor_z_m=floor_heights_m(building),
        stairs=links,
        robot_radius_m=float(robot_radius_m),
    )


def grid_kernel(
    building: Building, robot_radius_m: float, footprint: FootprintVariant = "app"
) -> FootprintKernel | None:
    """The inflation kernel of :func:`build_occupancy_grid` (quantised in floor 0's frame), ``None`` for a
    robot of radius 0."""
    if robot_radius_m <= 0:
        return None
    floor0 = building.floors[0]
    return footprint_kernel(robot_radius_m, floor0.origin_m, floor0.resolution_m, footprint)


def free_cells(cat_map: np.ndarray, room_map: np.ndarray, kernel: FootprintKernel | None) -> np.ndarray:
    """The occupancy rule on one floor (or a window of one), stairs portals aside: ``(rows, cols)`` bool,
    True where the cell is GROUND, clear of the obstacles other than stairs inflated with ``kernel`` (not
    inflated when ``None``), and in a room. On a window, cells beyond it count as free, so only the cells
    at least the kernel's reach inside the window are exact."""
    obstacles = cat_map != CatCode.GROUND
    if kernel is not None:
        stairs = (cat_map == CatCode.STAIRS_UP) | (cat_map == CatCode.STAIRS_DOWN)
        obstacles = inflate(obstacles & ~stairs, kernel) | stairs
    return ~obstacles & (room_map > 0)


def component_sizes(grid: OccupancyGrid) -> list[np.ndarray]:
    """Per floor, the sizes (cells, descending) of the 8-connected components of traversable cells.

    Stairs are not followed: this describes each floor on its own.
    """
    from scipy import ndimage  # slow to import: only for this summary, not for planning

    eight = np.ones((3, 3), dtype=bool)
    sizes = []
    for layer in grid.traversable:
        labels, count = ndimage.label(layer, structure=eight)
        counts = np.bincount(labels.ravel(), minlength=count + 1)[1:]
        sizes.append(np.sort(counts)[::-1])
    return sizes
