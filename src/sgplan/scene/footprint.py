"""The authors' robot-footprint kernel and obstacle inflation (reference-algorithm.md §2.2).

The footprint is a polygon of 360 points on a circle of radius ``r`` metres around the metric origin.
Each point is converted to a cell with ``floor((v - origin) / res)`` in floor 0's frame, the closed
polygon through those cells is rasterised (outline with 8-connected lines, then filled), and the cell of
metric ``(0, 0)`` is the anchor. Inflation then marks cell ``p`` as an obstacle iff some kernel cell ``k``
has an obstacle at ``p + k - anchor`` (OpenCV's ``dilate`` convention, which does not mirror the kernel).

Two vertex variants exist in the authors' code:

- ``"app"``: angles ``k * 2*pi / 360`` for ``k = 0..359`` (the experiment app);
- ``"gtest"``: 360 angles evenly spaced from 0 to ``2*pi`` inclusive (their unit tests, whose expected
  costs are reproduced with it).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Literal

import numpy as np

from sgplan.errors import SceneError

FootprintVariant = Literal["app", "gtest"]
_NUM_POINTS = 360


@dataclass(frozen=True)
class FootprintKernel:
    """A dilation kernel: ``mask`` (bool, rows x cols) with ``anchor`` ``(row, col)`` inside its frame.

    The anchor need not be a kernel cell. ``offsets`` are the kernel cells relative to the anchor, as an
    ``(n, 2)`` int array of ``(d_row, d_col)``: inflation ORs the obstacle mask shifted by each offset.
    """

    mask: np.ndarray
    anchor: tuple[int, int]

    @property
    def offsets(self) -> np.ndarray:
        return np.argwhere(self.mask) - np.asarray(self.anchor)

    @property
    def size(self) -> int:
        """Number of kernel cells."""
        return int(self.mask.sum())


def footprint_vertices(radius_m: float, variant: FootprintVariant = "app") -> np.ndarray:
    """The 360 metric footprint points ``(x, y)`` around the origin, shape ``(360, 2)``, metres."""
    if variant == "app":
        angles = np.arange(_NUM_POINTS) * (2.0 * np.pi / _NUM_POINTS)
    elif variant == "gtest":
        angles = np.linspace(0.0, 2.0 * np.pi, _NUM_POINTS)
    else:
        raise ValueError(f"unknown footprint variant {variant!r} (use 'app' or 'gtest')")
    return np.stack([radius_m * np.cos(angles), radius_m * np.sin(angles)], axis=1)


def _line_cells(r0: int, c0: int, r1: int, c1: int) -> np.ndarray:
    """Cells of OpenCV's 8-connected line from ``(r0, c0)`` to ``(r1, c1)`` (ends included).

    OpenCV walks left to right (increasing column), steps the major axis every time and the minor axis
    when its error term goes negative, starting from ``err = major - 2 * minor``; the same tie-breaking is
    kept here so that the filled kernel matches cell for cell.
    """
    if c1 < c0:
        r0, c0, r1, c1 = r1, c1, r0, c0
    d_col, d_row = c1 - c0, r1 - r0
    row_step = -1 if d_row < 0 else 1
    d_row = abs(d_row)
    col_major = d_col >= d_row
    major, minor = (d_col, d_row) if col_major else (d_row, d_col)
    cells = np.empty((major + 1, 2), dtype=np.int64)
    err = major - 2 * minor
    row, col = r0, c0
    for i in range(major + 1):
        cells[i] = (row, col)
        step_minor = err < 0
        err += -2 * minor + (2 * major if step_minor else 0)
        if col_major:
            col += 1
            row += row_step if step_minor else 0
        else:
            row += row_step
            col += 1 if step_minor else 0
    return cells


def _fill_polygon(vertices: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Filled closed polygon through integer ``(row, col)`` vertices: outline plus interior, per row.

    The footprint polygon is convex up to quantisation, so each row of the fill is the span between
    the leftmost and rightmost outline cells of that row.
    """
    outline = np.concatenate(
        [
            _line_cells(*vertices[i - 1], *vertices[i])
            for i in range(len(vertices))
        ]
    )
    mask = np.zeros(shape, dtype=bool)
    rows = outline[:, 0]
    lo = np.full(shape[0], np.iinfo(np.int64).max)
    hi = np.full(shape[0], -1)
    np.minimum.at(lo, rows, outline[:, 1])
    np.maximum.at(hi, rows, outline[:, 1])
    cols = np.arange(shape[1])
    mask[:] = (cols[None, :] >= lo[:, None]) & (cols[None, :] <= hi[:, None])
    return mask


@lru_cache(maxsize=32)
def _kernel_cached(
    radius_m: float,
    origin_m: tuple[float, float],
    resolution_m: tuple[float, float],
    variant: FootprintVariant,
) -> FootprintKernel:
    origin = np.asarray(origin_m, dtype=np.float64)
    res = np.asarray(resolution_m, dtype=np.float64)
    cells = np.floor((footprint_vertices(radius_m, variant) - origin) / res).astype(np.int64)
    anchor_cell = np.floor((np.zeros(2) - origin) / res).astype(np.int64)
    low = np.minimum(cells.min(axis=0), anchor_cell)
    high = np.maximum(cells.max(axis=0), anchor_cell)
    shape = (int(high[0] - low[0] + 1), int(high[1] - low[1] + 1))
    mask = _fill_polygon(cells - low, shape)
    mask.flags.writeable = False
    anchor = anchor_cell - low
    return FootprintKernel(mask=mask, anchor=(int(anchor[0]), int(anchor[1])))


def footprint_kernel(
    radius_m: float,
    origin_m: tuple[float, float],
    resolution_m: tuple[float, float],
    variant: FootprintVariant = "app",
) -> FootprintKernel:
    """The authors' footprint kernel for a robot of ``radius_m`` metres on a grid (floor 0's frame).

    ``origin_m`` / ``resolution_m`` are floor 0's ``(x, y)`` grid origin and ``(res_x, res_y)`` cell size
    in metres. The quantisation depends on the origin, exactly as in the authors' code.

    Raises
    ------
    SceneError
        if the radius is not a positive finite number.
    """
    if not np.isfinite(radius_m) or radius_m <= 0:
        raise SceneError(f"robot radius must be a positive number of metres, got {radius_m}")
    return _kernel_cached(
        float(radius_m),
        (float(origin_m[0]), float(origin_m[1])),
        (float(resolution_m[0]), float(resolution_m[1])),
        variant,
    )


def inflate(obstacles: np.ndarray, kernel: FootprintKernel) -> np.ndarray:
    """Inflate a 2-D bool obstacle mask with ``kernel`` (cells beyond the grid count as free).

    ``out[p] = any(obstacles[p + d] for d in kernel.offsets)``.

    Every kernel row is one contiguous run of cells (see :func:`_fill_polygon`), so with a summed-area
    table of the obstacles each run is tested in O(1); a cell whose whole kernel bounding box holds no
    obstacle (most of a floor) is settled by a single box test (compiled, one pass).
    """
    offsets = kernel.offsets
    if len(offsets) == 0:
        return np.zeros_like(obstacles, dtype=bool)
    d_rows = np.unique(offsets[:, 0])
    firsts = np.array([offsets[offsets[:, 0] == d, 1].min() for d in d_rows], dtype=np.int64)
    lasts = np.array([offsets[offsets[:, 0] == d, 1].max() for d in d_rows], dtype=np.int64)
    # Test the runs nearest the anchor row first: an obstacle close by is found after a few.
    near = np.argsort(np.abs(d_rows), kind="stable")
    from sgplan.scene._inflate import inflate_runs  # numba only once a grid is built

    out = np.empty(obstacles.shape, dtype=bool)
    inflate_runs(np.ascontiguousarray(obstacles, dtype=np.bool_), d_rows[near].astype(np.int64),
                 firsts[near], lasts[near], out)
    return out
