"""Rasterising metric shapes onto one floor grid: polygons, discs, capsules, oriented boxes.

A :class:`GridFrame` is the frame every floor of an imported building shares: origin ``(x, y)`` of the
grid corner in metres, a square cell of ``resolution_m`` metres, and ``(rows, cols)``. As everywhere in
sgplan (:mod:`sgplan.scene.model`), ``row`` runs along metric x and ``col`` along metric y; a cell is
covered by a shape when its centre is. Every function returns a ``(rows, cols)`` bool mask and works
inside the shape's bounding box only, so a shape costs what it covers, not what the floor holds.
"""

from __future__ import annotations

import contextlib
import math
from dataclasses import dataclass

import numpy as np
from matplotlib.path import Path as MplPath
from scipy.spatial import ConvexHull, QhullError

from sgplan.errors import SceneError

MAX_CELLS = 16_000_000
"""Largest floor grid an importer builds (rows x cols); beyond it, ask for a coarser resolution."""


@dataclass(frozen=True)
class GridFrame:
    """The shared grid of an imported building: origin (m), square cell size (m) and shape (cells)."""

    origin_m: tuple[float, float]
    resolution_m: float
    shape: tuple[int, int]

    @classmethod
    def around(cls, lo_xy: np.ndarray, hi_xy: np.ndarray, resolution_m: float, margin_m: float) -> GridFrame:
        """The frame covering the metric box ``[lo, hi]`` plus ``margin_m`` on every side.

        Raises :class:`SceneError` for a non-positive resolution or a grid above :data:`MAX_CELLS`.
        """
        if not (math.isfinite(resolution_m) and resolution_m > 0):
            raise SceneError(f"grid resolution must be a positive number of metres, got {resolution_m}")
        lo = np.asarray(lo_xy, dtype=float) - margin_m
        hi = np.asarray(hi_xy, dtype=float) + margin_m
        rows, cols = (math.ceil((hi[k] - lo[k]) / resolution_m) for k in (0, 1))
        if rows * cols > MAX_CELLS:
            raise SceneError(
                f"a {hi[0] - lo[0]:.1f} x {hi[1] - lo[1]:.1f} m scene at {resolution_m} m per cell needs "
                f"{rows} x {cols} cells (more than {MAX_CELLS:,}); give a coarser --resolution"
            )
        return cls((float(lo[0]), float(lo[1])), float(resolution_m), (max(rows, 1), max(cols, 1)))

    def cell_of(self, xy: np.ndarray) -> np.ndarray:
        """The ``(row, col)`` cells (int64, ``(n, 2)``) containing metric points ``(n, 2)``; may lie off the
        grid."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        return np.floor((xy - np.asarray(self.origin_m)) / self.resolution_m).astype(np.int64)

    def contains(self, cells: np.ndarray) -> np.ndarray:
        """Which ``(row, col)`` cells ``(n, 2)`` lie on the grid."""
        cells = np.asarray(cells).reshape(-1, 2)
        return (cells >= 0).all(axis=1) & (cells[:, 0] < self.shape[0]) & (cells[:, 1] < self.shape[1])

    def window(
        self, lo_xy: np.ndarray, hi_xy: np.ndarray
    ) -> tuple[slice, slice, np.ndarray, np.ndarray] | None:
        """Row / column slices of the cells whose centres may lie in ``[lo, hi]``, with those centres.

        Returns ``(rows, cols, x, y)`` with ``x`` ``(n_rows, 1)`` and ``y`` ``(1, n_cols)`` metric centres,
        or ``None`` when the box misses the grid.
        """
        first = np.maximum(self.cell_of(lo_xy)[0], 0)
        last = np.minimum(self.cell_of(hi_xy)[0], np.array(self.shape) - 1)
        if (last < first).any():
            return None
        rows, cols = slice(int(first[0]), int(last[0]) + 1), slice(int(first[1]), int(last[1]) + 1)
        x = self.origin_m[0] + (np.arange(rows.start, rows.stop) + 0.5)[:, None] * self.resolution_m
        y = self.origin_m[1] + (np.arange(cols.start, cols.stop) + 0.5)[None, :] * self.resolution_m
        return rows, cols, x, y

    def empty(self) -> np.ndarray:
        return np.zeros(self.shape, dtype=bool)


def polygon_cells(frame: GridFrame, vertices_xy: np.ndarray) -> np.ndarray:
    """``(row, col)`` cells ``(n, 2)`` whose centres lie inside the simple polygon ``vertices_xy``
    (metres)."""
    vertices = np.asarray(vertices_xy, dtype=float).reshape(-1, 2)
    found = frame.window(vertices.min(axis=0), vertices.max(axis=0))
    if found is None:
        return np.zeros((0, 2), dtype=np.int64)
    rows, cols, x, y = found
    centres = np.column_stack(
        [np.broadcast_to(x, (x.size, y.size)).ravel(), np.broadcast_to(y, (x.size, y.size)).ravel()]
    )
    inside = MplPath(np.vstack([vertices, vertices[:1]]), closed=True).contains_points(centres)
    return np.argwhere(inside.reshape(x.size, y.size)) + (rows.start, cols.start)


def polygon_mask(frame: GridFrame, vertices_xy: np.ndarray) -> np.ndarray:
    """:func:`polygon_cells` as a ``(rows, cols)`` mask."""
    return cells_mask(frame, polygon_cells(frame, vertices_xy))


def cells_mask(frame: GridFrame, cells: np.ndarray) -> np.ndarray:
    """A ``(rows, cols)`` mask true on the given ``(n, 2)`` cells (all on the grid)."""
    mask = frame.empty()
    mask[cells[:, 0], cells[:, 1]] = True
    return mask


def polygon_area_m2(vertices_xy: np.ndarray) -> float:
    """Unsigned area of a simple polygon (shoelace formula), square metres."""
    v = np.asarray(vertices_xy, dtype=float).reshape(-1, 2)
    return 0.5 * abs(float(np.dot(v[:, 0], np.roll(v[:, 1], -1)) - np.dot(v[:, 1], np.roll(v[:, 0], -1))))


def capsules_mask(frame: GridFrame, a_xy: np.ndarray, b_xy: np.ndarray, radius_m: np.ndarray) -> np.ndarray:
    """Union of capsules: cells within ``radius_m[i]`` of segment ``a[i]-b[i]`` (a disc when ``a == b``)."""
    a_all = np.asarray(a_xy, dtype=float).reshape(-1, 2)
    b_all = np.asarray(b_xy, dtype=float).reshape(-1, 2)
    radii = np.broadcast_to(np.asarray(radius_m, dtype=float), (len(a_all),))
    mask = frame.empty()
    for a, b, r in zip(a_all, b_all, radii):
        found = frame.window(np.minimum(a, b) - r, np.maximum(a, b) + r)
        if found is None:
            continue
        rows, cols, x, y = found
        d = b - a
        length2 = float(d @ d)
        t = (
            np.zeros((x.size, y.size))
            if length2 == 0
            else np.clip(((x - a[0]) * d[0] + (y - a[1]) * d[1]) / length2, 0, 1)
        )
        mask[rows, cols] |= (x - a[0] - t * d[0]) ** 2 + (y - a[1] - t * d[1]) ** 2 <= r * r
    return mask


def hull_cells(frame: GridFrame, points_xy: np.ndarray) -> np.ndarray:
    """Cells ``(n, 2)`` inside the convex hull of ``points_xy``, or the cell of their centre when it has none.

    An object's footprint is the hull of its box corners projected on the floor; a box seen edge-on
    (zero area) still covers the cell it stands in, so every object on the grid keeps at least one cell.
    """
    points = np.asarray(points_xy, dtype=float).reshape(-1, 2)
    cells = np.zeros((0, 2), dtype=np.int64)
    with contextlib.suppress(QhullError, ValueError):  # a degenerate hull: the fallback below
        cells = polygon_cells(frame, points[ConvexHull(points).vertices])
    if len(cells) == 0:
        centre = frame.cell_of(points.mean(axis=0))
        cells = centre[frame.contains(centre)]
    return cells


def box_corners(center: np.ndarray, axes: np.ndarray, half_sizes: np.ndarray) -> np.ndarray:
    """The 8 corners ``(8, 3)`` of an oriented box: centre ``(3,)``, unit axes as rows ``(3, 3)``, half sizes
    ``(3,)``."""
    signs = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], dtype=float)
    return np.asarray(center, dtype=float) + (signs * np.asarray(half_sizes, dtype=float)) @ np.asarray(
        axes, dtype=float
    )


def polygon_distance_m(p: np.ndarray, q: np.ndarray) -> float:
    """Smallest distance between two closed polygons' boundaries or interiors (0 if they meet), metres.

    ``p`` and ``q`` are vertex arrays ``(n, 2)`` / ``(m, 2)``. Exact: the minimum over all pairs of
    edges of the segment distance, and 0 when a vertex of one lies inside the other.
    """
    p = np.asarray(p, dtype=float).reshape(-1, 2)
    q = np.asarray(q, dtype=float).reshape(-1, 2)
    if MplPath(p).contains_points(q).any() or MplPath(q).contains_points(p).any():
        return 0.0
    pa, pb = p, np.roll(p, -1, axis=0)
    qa, qb = q, np.roll(q, -1, axis=0)

    def point_to_segments(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        d = b - a
        length2 = np.maximum((d * d).sum(axis=1), 1e-300)
        t = np.clip(((points[:, None, :] - a[None]) * d[None]).sum(axis=2) / length2[None], 0, 1)
        closest = a[None] + t[..., None] * d[None]
        return np.sqrt(((points[:, None, :] - closest) ** 2).sum(axis=2))

    def crosses(a1: np.ndarray, b1: np.ndarray, a2: np.ndarray, b2: np.ndarray) -> bool:
        def orient(o: np.ndarray, s: np.ndarray, t: np.ndarray) -> np.ndarray:
            return (s[..., 0] - o[..., 0]) * (t[..., 1] - o[..., 1]) - (s[..., 1] - o[..., 1]) * (
                t[..., 0] - o[..., 0]
            )

        A1, B1, A2, B2 = a1[:, None], b1[:, None], a2[None], b2[None]
        d1, d2 = orient(A2, B2, A1), orient(A2, B2, B1)
        d3, d4 = orient(A1, B1, A2), orient(A1, B1, B2)
        first_straddles = (d1 * d2) < 0
        second_straddles = (d3 * d4) < 0
        return bool((first_straddles & second_straddles).any())

    if crosses(pa, pb, qa, qb):
        return 0.0
    return float(min(point_to_segments(p, qa, qb).min(), point_to_segments(q, pa, pb).min()))
