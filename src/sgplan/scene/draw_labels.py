"""The labels of a floor drawing: where each belongs, what it says, and placing it clear of the rest.

Rooms are labelled with their category and ``room_<uuid>`` on their freest floor cell, objects with
their class and ``object_<uuid>`` on their own footprint (the mission's objects highlighted), stairs
portals with where they lead. :func:`place_labels` moves a label off its anchor, with a leader line,
when its spot would cover a marker (start, end, portal) or a label placed before it
(:class:`sgplan.scene.placement.LabelPlacer`); it also prefers spots off the path.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from scipy import ndimage

from sgplan.scene.model import Building, CatCode
from sgplan.scene.placement import Box, LabelPlacer

_MISSION = "#006d6d"


def label_anchors(
    raster: np.ndarray, ids: Sequence[int], open_cells: np.ndarray | None = None
) -> dict[int, tuple[int, int]]:
    """For each id, the ``(row, col)`` cell of the id farthest inside its region (a label's anchor).

    With ``open_cells``, the spot is sought among the region's open cells first (room labels go on
    free floor rather than on the furniture), falling back to the whole region. Ids absent from the
    raster are left out.
    """
    positions = {}
    for value in ids:
        mask = raster == value
        if not mask.any():
            continue
        if open_cells is not None and (mask & open_cells).any():
            mask &= open_cells
        rows, cols = np.nonzero(mask.any(axis=1))[0], np.nonzero(mask.any(axis=0))[0]
        r0, r1, c0, c1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
        depth = ndimage.distance_transform_edt(np.pad(mask[r0:r1, c0:c1], 1))[1:-1, 1:-1]
        r, c = np.unravel_index(int(np.argmax(depth)), depth.shape)
        positions[int(value)] = (int(r0 + r), int(c0 + c))
    return positions


@dataclass
class FloorLabel:
    """A label: the cell it belongs to, its text and its matplotlib text style (with a ``bbox``)."""

    anchor: tuple[int, int]
    text: str
    style: dict[str, Any]


def marker_box(ax: Axes, cell: tuple[int, int] | np.ndarray, half_px: float) -> Box:
    """The display box (pixels) of a marker of half-size ``half_px`` drawn at ``cell = (row, col)``
    (drawing coordinates ``x = row``, ``y = col``: :mod:`sgplan.scene.draw_axes`)."""
    x, y = ax.transData.transform((float(cell[0]), float(cell[1])))
    return (x - half_px, y - half_px, x + half_px, y + half_px)


def _style(
    font: float, colour: str, zorder: float, pad: float, box: dict[str, Any], bold: bool
) -> dict[str, Any]:
    return {
        "fontsize": font,
        "color": colour,
        "fontweight": "bold" if bold else "normal",
        "zorder": zorder,
        "bbox": {"boxstyle": f"round,pad={pad}", **box},
    }


def floor_labels(
    building: Building,
    floor: int,
    portals: Sequence[tuple[tuple[int, int], str]],
    mission_objects: set[int],
    font: float,
) -> list[FloorLabel]:
    """Every label of the floor, in placement priority: stairs, rooms, mission objects, other objects.

    ``portals`` are ``((row, col), "up" | "down")``; ``mission_objects`` the ids of the objects the
    mission names (highlighted); ``font`` the base font size in points.
    """
    f = building.floors[floor]
    stairs = _style(font, "#3d1466", 8, 0.2, {"fc": "white", "ec": "#3d1466", "lw": 0.6, "alpha": 0.9}, True)
    labels = [
        FloorLabel((r, c), f"stairs {word}\nto floor {floor + 1 if word == 'up' else floor - 1}", stairs)
        for (r, c), word in portals
    ]
    room_style = _style(font + 0.5, "#1a1a40", 7, 0.2, {"fc": "white", "ec": "none", "alpha": 0.75}, True)
    rooms = {r.id for r in f.rooms.values()} | {r.id for r in building.rooms() if r.floor == floor}
    for room_id, anchor in label_anchors(f.room_map, sorted(rooms), f.cat_map == CatCode.GROUND).items():
        room = building.room(id=room_id)
        labels.append(FloorLabel(anchor, f"{room.name}\n{room.key}", room_style))
    plain = _style(
        font - 1, "#4a1d00", 7, 0.15, {"fc": "#ffe8cc", "ec": "#cc6600", "lw": 0.5, "alpha": 0.88}, False
    )
    ours = _style(
        font - 1, "#003b3b", 7.5, 0.15, {"fc": "#e0fbfb", "ec": _MISSION, "lw": 1.0, "alpha": 0.88}, True
    )
    known = {o.id for o in building.objects()}
    object_ids = [i for i in np.unique(f.cat_map[f.cat_map > 0]).tolist() if i in known]
    object_ids.sort(key=lambda i: i not in mission_objects)  # the mission's objects get the best spots
    for object_id, anchor in label_anchors(f.cat_map, object_ids).items():
        obj = building.object(id=object_id)
        labels.append(
            FloorLabel(anchor, f"{obj.name}\n{obj.key}", ours if object_id in mission_objects else plain)
        )
    return labels


def place_labels(ax: Axes, renderer: Any, placer: LabelPlacer, labels: Sequence[FloorLabel]) -> None:
    """Draw each label where ``placer`` finds room (measured with ``renderer``, in display pixels); a
    label moved off its anchor gets a leader line to it."""
    to_data = ax.transData.inverted()
    dpi_scale = ax.figure.dpi / 72
    for label in labels:
        r, c = label.anchor  # drawn at (x, y) = (row, col)
        anchor = ax.transData.transform((float(r), float(c)))
        text = ax.text(r, c, label.text, ha="center", va="center", **label.style)
        extent = text.get_window_extent(renderer)
        pad = float(label.style["bbox"]["boxstyle"].split("pad=")[1]) * label.style["fontsize"] * dpi_scale
        x0, y0, x1, y1 = placer.place(
            (float(anchor[0]), float(anchor[1])), (extent.width + 2 * pad + 2, extent.height + 2 * pad + 2)
        )
        centre = to_data.transform(((x0 + x1) / 2, (y0 + y1) / 2))
        text.set_position((float(centre[0]), float(centre[1])))
        if not (x0 <= anchor[0] <= x1 and y0 <= anchor[1] <= y1):
            ax.plot(
                [r, centre[0]],
                [c, centre[1]],
                color=label.style["color"],
                lw=0.7,
                alpha=0.8,
                zorder=label.style["zorder"] - 0.05,
            )
            ax.plot([r], [c], "o", ms=2.5, color=label.style["color"], zorder=label.style["zorder"] - 0.05)
