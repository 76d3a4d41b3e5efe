"""Cells of the places a scene change touches, on one floor's rasters: metric areas, the boundary between
two rooms, an object's footprint; and the fill of the cells an object leaves.

Cells are flat positions ``row * cols + col`` of a floor (int64, ascending); a cell belongs to an area
when its centre lies inside it (bounds included), as in :class:`sgplan.scene.builder.BuildingBuilder`.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.path import Path as MplPath
from scipy import ndimage

from sgplan.execution.changes import Area
from sgplan.scene.model import CatCode, Floor, SceneObject


def _span(lo_m: float, hi_m: float, origin_m: float, res_m: float, size: int) -> tuple[int, int]:
    """Indices ``[first, stop)`` of the cells along one axis whose centres lie in ``[lo, hi]``, clipped."""
    first = math.ceil((lo_m - origin_m) / res_m - 0.5)
    last = math.floor((hi_m - origin_m) / res_m - 0.5)
    return max(first, 0), min(last + 1, size)


def area_cells(floor: Floor, area: Area) -> np.ndarray:
    """The cells of ``floor`` whose centres lie in ``area`` (empty when it misses the grid)."""
    rows, cols = floor.shape
    if area.box_m is not None:
        x0, y0, x1, y1 = area.box_m
        vertices = None
    else:
        vertices = np.asarray(area.polygon_m, dtype=np.float64)
        (x0, y0), (x1, y1) = vertices.min(axis=0), vertices.max(axis=0)
    r0, r1 = _span(x0, x1, floor.origin_m[0], floor.resolution_m[0], rows)
    c0, c1 = _span(y0, y1, floor.origin_m[1], floor.resolution_m[1], cols)
    if r0 >= r1 or c0 >= c1:
        return np.zeros(0, dtype=np.int64)
    rr, cc = np.meshgrid(np.arange(r0, r1), np.arange(c0, c1), indexing="ij")
    if vertices is not None:
        centres = np.column_stack([floor.origin_m[0] + (rr.ravel() + 0.5) * floor.resolution_m[0],
                                   floor.origin_m[1] + (cc.ravel() + 0.5) * floor.resolution_m[1]])
        inside = MplPath(np.vstack([vertices, vertices[:1]]), closed=True).contains_points(centres)
        rr, cc = rr.ravel()[inside], cc.ravel()[inside]
    return np.sort((rr.ravel() * cols + cc.ravel()).astype(np.int64))


def boundary_cells(room_map: np.ndarray, room_a: int, room_b: int) -> np.ndarray:
    """The cells of rooms ``room_a`` and ``room_b`` (ids) that have an 8-neighbour in the other room: both
    sides of their shared boundary, so that no move leads from one room straight into the other once they
    are obstacles (this holds the rooms' door cells, :mod:`sgplan.scene.doors`)."""
    either = (room_map == room_a) | (room_map == room_b)
    if not either.any():
        return np.zeros(0, dtype=np.int64)
    rows, cols = np.nonzero(either.any(axis=1))[0], np.nonzero(either.any(axis=0))[0]
    r0, r1 = max(int(rows[0]) - 1, 0), int(rows[-1]) + 2
    c0, c1 = max(int(cols[0]) - 1, 0), int(cols[-1]) + 2
    window = room_map[r0:r1, c0:c1]
    in_a, in_b = window == room_a, window == room_b
    side = (in_a & _near(in_b)) | (in_b & _near(in_a))
    rr, cc = np.nonzero(side)
    return np.sort((rr + r0) * room_map.shape[1] + cc + c0).astype(np.int64)


def _near(mask: np.ndarray) -> np.ndarray:
    """The cells of ``mask``'s shape with an 8-neighbour in ``mask`` (or in it): its dilation by one cell,
    as eight shifted ORs (a generic morphology call costs several times more on a room-sized window)."""
    rows, cols = mask.shape
    padded = np.zeros((rows + 2, cols + 2), dtype=bool)
    padded[1:-1, 1:-1] = mask
    near = mask.copy()
    for dr in (0, 1, 2):
        for dc in (0, 1, 2):
            if dr != 1 or dc != 1:
                near |= padded[dr : dr + rows, dc : dc + cols]
    return near


def footprint_cells(cat_map: np.ndarray, obj: SceneObject) -> np.ndarray:
    """The cells of ``cat_map`` that hold ``obj`` (its id), searched in its bounding box."""
    rows, cols = cat_map.shape
    r0, c0 = max(obj.grid_min[0], 0), max(obj.grid_min[1], 0)
    r1, c1 = min(obj.grid_max[0] + 1, rows), min(obj.grid_max[1] + 1, cols)
    rr, cc = np.nonzero(cat_map[r0:r1, c0:c1] == obj.id)
    return ((rr + r0) * cols + cc + c0).astype(np.int64)


def fill_from_nearest(cat_map: np.ndarray, cells: np.ndarray) -> None:
    """Give each of ``cells`` (in place) the value of the nearest cell not among them (Euclidean in cells):
    what an object leaves behind looks like what surrounds it."""
    if cells.size == 0:
        return
    rows, cols = cat_map.shape
    rr, cc = np.divmod(cells, cols)
    r0, c0 = max(int(rr.min()) - 1, 0), max(int(cc.min()) - 1, 0)
    r1, c1 = min(int(rr.max()) + 2, rows), min(int(cc.max()) + 2, cols)
    window = cat_map[r0:r1, c0:c1]
    hole = np.zeros(window.shape, dtype=bool)
    hole[rr - r0, cc - c0] = True
    if hole.all():  # the cells cover the whole floor: nothing to copy from
        window[...] = CatCode.GROUND
        return
    _, (near_r, near_c) = ndimage.distance_transform_edt(hole, return_indices=True)
    window[hole] = window[near_r[hole], near_c[hole]]


def cells_box(cells: np.ndarray, cols: int) -> tuple[tuple[int, int], tuple[int, int]]:
    """The inclusive ``(row, col)`` bounding box ``(min, max)`` of non-empty ``cells``."""
    rr, cc = np.divmod(cells, cols)
    return (int(rr.min()), int(cc.min())), (int(rr.max()), int(cc.max()))
