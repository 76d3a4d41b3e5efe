"""The path on a floor drawing: its cells, its colour by progress, and arrows in its direction.

A path is a sequence of ``(row, col, floor)`` cells -- a list of tuples or the planner's ``(n, 4)``
ndarray (extra columns, e.g. the automaton state, are ignored). On a floor its part is coloured from
blue (early) to red (late), with arrows in the direction of travel, each set slightly to the right of
its segment so the two legs of an out-and-back path show both ways. :func:`arrow_marks` is shared with
the HTML report (:mod:`sgplan.report.html`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.colors import LinearSegmentedColormap

from sgplan.errors import SceneError

PathCells = Sequence[Sequence[int]] | np.ndarray
"""A path as ``(row, col, floor[, ...])`` rows, in order: a list of tuples or an ``(n, k >= 3)`` array."""

PATH_COLOURS = LinearSegmentedColormap.from_list("sgplan_path", ["#1040c0", "#9020a0", "#e01818"])
"""Path colour by progress: blue at the start, red at the end."""
_ARROW_SPACING_PX = 70.0
_ARROW_LENGTH_PX = 16.0
_LANE_OFFSET_PX = 4.0
"""Arrows sit this far to the right of travel, so the two legs of an out-and-back path differ."""


def path_cells(path: PathCells) -> np.ndarray:
    """The ``(n, 3)`` int64 array of ``(row, col, floor)`` of a path given as rows or an array.

    Raises
    ------
    SceneError
        if the rows do not have at least three integer entries.
    """
    try:
        cells = np.asarray(path)
    except ValueError:
        raise SceneError("a path must be rows of (row, col, floor) of equal length") from None
    if cells.size == 0:
        return np.zeros((0, 3), dtype=np.int64)
    if cells.ndim != 2 or cells.shape[1] < 3 or not np.issubdtype(cells.dtype, np.integer):
        raise SceneError(
            f"a path must be rows of integer (row, col, floor[, ...]) cells, got an array of shape "
            f"{cells.shape} and dtype {cells.dtype}"
        )
    return cells[:, :3].astype(np.int64)


def draw_path(ax: Axes, cells: np.ndarray, floor: int, px_per_cell: float) -> np.ndarray:
    """Draw the floor's part of the path with direction arrows; returns its ``(k, 2)`` (x, y) points."""
    n = len(cells)
    progress = np.arange(n) / max(n - 1, 1)
    on_floor = cells[:, 2] == floor
    same = on_floor[:-1] & on_floor[1:]
    xy = cells[:, [0, 1]].astype(float)  # drawing coordinates: (x = row, y = column), sgplan.scene.draw_axes
    segments = list(np.stack([xy[:-1][same], xy[1:][same]], axis=1))
    colours = PATH_COLOURS(progress[:-1][same])
    ax.add_collection(
        LineCollection(segments, colors="white", linewidths=4.2, alpha=0.85, zorder=3.9, capstyle="round")
    )
    ax.add_collection(LineCollection(segments, colors=colours, linewidths=2.2, zorder=4, capstyle="round"))
    _draw_arrows(ax, xy, progress, on_floor, px_per_cell)
    return xy[on_floor]


def arrow_marks(
    xy: np.ndarray, on_floor: np.ndarray, spacing: float, length: float, lane: float, *, y_up: bool = False
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where direction arrows go along the runs of a path that lie on one floor.

    Parameters
    ----------
    xy:
        ``(n, 2)`` path points ``(x, y)`` in drawing units.
    on_floor:
        ``(n,)`` bool, the points on the floor drawn.
    spacing, length, lane:
        distance between arrows along the path, arrow length, and offset to the right of travel (so the
        two legs of an out-and-back path are apart), all in drawing units.
    y_up:
        whether y grows upwards on screen (matplotlib's axes) rather than downwards (SVG), which decides
        where the right of travel is.

    Returns
    -------
    ``(centres (k, 2), vectors (k, 2), index (k,))``: arrow midpoints, arrow vectors (of ``length``), and
    the fractional path index of each arrow (for colouring by progress).
    """
    breaks = np.flatnonzero(np.diff(on_floor.astype(np.int8)) != 0) + 1
    points, vectors, where = [], [], []
    for run in np.split(np.arange(len(xy)), breaks):
        if len(run) < 2 or not on_floor[run[0]]:
            continue
        p = xy[run]
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])
        if arc[-1] < 2 * length:
            continue
        marks = np.arange(spacing / 2, arc[-1] - length / 2, spacing)
        tail = np.column_stack(
            [np.interp(marks - length / 2, arc, p[:, 0]), np.interp(marks - length / 2, arc, p[:, 1])]
        )
        head = np.column_stack(
            [np.interp(marks + length / 2, arc, p[:, 0]), np.interp(marks + length / 2, arc, p[:, 1])]
        )
        d = head - tail
        norm = np.hypot(d[:, 0], d[:, 1])
        keep = norm > 0
        unit = d[keep] / norm[keep, None]
        # Right of travel on screen: (x, y) -> (-y, x) where y grows downwards, (y, -x) where it grows up.
        right = np.column_stack([unit[:, 1], -unit[:, 0]] if y_up else [-unit[:, 1], unit[:, 0]])
        points.append((tail[keep] + head[keep]) / 2 + lane * right)
        vectors.append(unit * length)
        where.append(np.interp(marks[keep], arc, run.astype(float)))
    if not points:
        return np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0)
    return np.concatenate(points), np.concatenate(vectors), np.concatenate(where)


def _draw_arrows(
    ax: Axes, xy: np.ndarray, progress: np.ndarray, on_floor: np.ndarray, px_per_cell: float
) -> None:
    """Arrows along each run of the path on this floor, every ~70 px, offset to the right of travel."""
    pts, vec, index = arrow_marks(
        xy,
        on_floor,
        _ARROW_SPACING_PX / px_per_cell,
        _ARROW_LENGTH_PX / px_per_cell,
        _LANE_OFFSET_PX / px_per_cell,
        y_up=True,
    )
    if not len(pts):
        return
    shades = np.interp(index, np.arange(len(progress)), progress)
    ax.quiver(
        pts[:, 0],
        pts[:, 1],
        vec[:, 0],
        vec[:, 1],
        color=PATH_COLOURS(shades),
        angles="xy",
        scale_units="xy",
        scale=1,
        pivot="mid",
        units="dots",
        width=2.6,
        headwidth=3.5,
        headlength=4.0,
        headaxislength=3.5,
        zorder=4.5,
        edgecolor="white",
        linewidth=0.4,
    )
