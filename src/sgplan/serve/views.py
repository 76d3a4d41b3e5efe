"""What the live page draws, made by the HTML report's renderer (:mod:`sgplan.report.floors`), not a
second one: the floors once per scene (pictures, hover rasters, tabs), then one SVG overlay per floor
each time the path changes."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from sgplan.report.floors import entities_json, floor_svg, floors_html
from sgplan.scene.draw_path import path_cells
from sgplan.serve.scenes import SceneHost


def scene_layers(host: SceneHost) -> dict[str, Any]:
    """The page's floors of a scene, no path yet: ``{"html": the report's floor tabs and layers,
    "entities": rooms and objects by id (JSON text) for the hover}``."""
    grid = host.session.grid()
    empty = np.zeros((0, 3), dtype=np.int64)
    return {
        "html": floors_html(host.building, grid, empty, None, []),
        "entities": entities_json(host.building),
    }


def overlays(
    host: SceneHost, path: np.ndarray | list[list[int]] | None, events: Sequence[Any] = ()
) -> list[str]:
    """One SVG overlay per floor (the report's :func:`sgplan.report.floors.floor_svg`) for ``path``
    (rows ``[row, col, floor, ...]``; ``None``: no path) and its ``events``
    (:class:`sgplan.outputs.events.Event`, drawn as the report draws them)."""
    rows = np.asarray(path, dtype=np.int64) if path is not None and len(path) else None
    cells = path_cells(rows) if rows is not None else np.zeros((0, 3), dtype=np.int64)
    return [floor_svg(host.building, k, cells, events) for k in range(host.building.num_floors)]
