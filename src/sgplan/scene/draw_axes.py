"""The frame of floor drawings: the map frame as ROS and RViz show it, with axes in metres or in cells.

A floor is drawn with metric x (the grid's rows, :mod:`sgplan.scene.model`) to the right and metric y
(its columns) upwards, as RViz shows a map frame and as a map_server image is drawn. The drawing
coordinates are cell indices, ``x = row`` and ``y = col`` (a cell's centre at its index); the ticks say
metres (``axes="metres"``, the default) or rows and columns (``axes="cells"``, to read off a
``--start ROW,COL,FLOOR``). Shared by the PNG / SVG pictures (:mod:`sgplan.scene.draw`) and the HTML
report (:mod:`sgplan.report.floors`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sgplan.errors import SceneError

AXES = ("metres", "cells")
"""What a drawing's ticks say: metres in the map frame, or grid rows and columns."""


def check_axes(axes: str) -> str:
    """``axes`` if it is one of :data:`AXES`, else a :class:`SceneError` naming the choices."""
    if axes not in AXES:
        raise SceneError(f"unknown drawing axes {axes!r}: use {' or '.join(AXES)}")
    return axes


def nice_step(extent: float, target: int) -> float:
    """A 1-2-5 step giving at most about ``target`` ticks over ``extent``."""
    for magnitude in 10.0 ** np.arange(-2, 6):
        for base in (1, 2, 2.5, 5):
            if extent / (base * magnitude) <= target:
                return float(base * magnitude)
    return float(extent)


@dataclass(frozen=True)
class Ticks:
    """One axis's ticks: ``positions`` and ``minor`` in drawing coordinates (cells), and the labels."""

    positions: np.ndarray
    labels: tuple[str, ...]
    minor: np.ndarray


def axis_ticks(num_cells: int, origin_m: float, resolution_m: float, axes: str, target: int = 10) -> Ticks:
    """The ticks of an axis of ``num_cells`` cells starting at ``origin_m`` (metres, the grid's edge),
    ``resolution_m`` metres a cell: at round metre values, or at round cell indices; four unlabelled
    minor ticks between two labelled ones."""
    if check_axes(axes) == "cells":
        step = nice_step(num_cells, target)
        values = np.arange(0, num_cells, step)
        minor = np.arange(0, num_cells, step / 5)
        return Ticks(values, tuple(f"{v:g}" for v in values), minor)
    extent = num_cells * resolution_m
    step = nice_step(extent, target)
    first = np.ceil(origin_m / step) * step

    def position(metres: np.ndarray) -> np.ndarray:
        return (metres - origin_m) / resolution_m - 0.5

    values = np.arange(first, origin_m + extent + 1e-9, step)
    minor = np.arange(first - step, origin_m + extent + 1e-9, step / 5)
    minor = minor[minor >= origin_m - 1e-9]
    decimals = max(0, -int(np.floor(np.log10(step)))) if step < 1 else 0
    labels = tuple(f"{v + 0.0:.{decimals}f}" for v in np.round(values, decimals))
    return Ticks(position(values), labels, position(minor))


def axis_titles(axes: str) -> tuple[str, str]:
    """The horizontal and vertical axis titles."""
    return ("x (m)", "y (m)") if check_axes(axes) == "metres" else ("row", "column")
