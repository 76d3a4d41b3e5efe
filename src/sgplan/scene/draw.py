"""Drawings of a building, one picture (PNG and/or SVG) per floor, with an optional plan on top.

Colours: outside light grey, walls dark grey, each room its own pastel colour (labelled with its
category and ``room_<uuid>``), objects dark orange (labelled with class and ``object_<uuid>``), stairs
purple, stairs portals as gold stars. With an occupancy grid, ground cells the robot may not enter (too
close to an obstacle, or outside every room) are shaded.

A path is a sequence of ``(row, col, floor)`` cells -- a list of tuples or the planner's ``(n, 4)``
ndarray (extra columns, e.g. the automaton state, are ignored). Each floor shows its part, coloured
from blue (early) to red (late) with arrows in the direction of travel, each arrow set slightly to the
right of its segment so an out-and-back path shows both ways; the start is a green circle and the end
a red square. Labels are placed greedily so that they cover neither those markers, nor the stairs
portals, nor each other (:mod:`sgplan.scene.placement`).

A :class:`MissionView` adds the mission (text or formula, a one-line explanation) and the cost to the
title, shades the reach regions of the mission's ``reach`` objects and outlines its ``enter`` rooms.

Images use matrix orientation: rows (metric x) downwards, columns (metric y) to the right; the axes
are ticked in rows and columns (so a ``--start ROW,COL,FLOOR`` can be read off) and a scale bar gives
metres.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib import colormaps, rc_context
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection
from matplotlib.colors import LinearSegmentedColormap
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.transforms import blended_transform_factory
from scipy import ndimage

from sgplan.errors import SceneError
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.labels import Proposition, label_raster
from sgplan.scene.model import Building, CatCode
from sgplan.scene.placement import LabelPlacer

PathCells = Sequence[Sequence[int]] | np.ndarray
"""A path as ``(row, col, floor[, ...])`` rows, in order: a list of tuples or an ``(n, k >= 3)`` array."""

FORMATS = ("png", "svg")
"""The picture formats :func:`draw_building` writes."""

_OUTSIDE = np.array([0.94, 0.94, 0.94])
_WALL = np.array([0.22, 0.22, 0.25])
_UNROOMED_GROUND = np.array([0.99, 0.99, 0.97])
_OBJECT = np.array([0.80, 0.40, 0.10])
_STAIRS = np.array([0.55, 0.35, 0.75])
_PALETTE = np.array(
    [colormaps["Pastel1"](i)[:3] for i in range(8)]
    + [colormaps["Pastel2"](i)[:3] for i in range(7)]
    + [colormaps["Set3"](i)[:3] for i in range(12)]
)
_COLOURS = np.vstack([_OUTSIDE, _WALL, _UNROOMED_GROUND, _STAIRS, _OBJECT, _PALETTE])
"""Colour lookup of :func:`floor_image`: outside, wall, ground outside rooms, stairs, object, rooms."""
PATH_COLOURS = LinearSegmentedColormap.from_list("sgplan_path", ["#1040c0", "#9020a0", "#e01818"])
"""Path colour by progress: blue at the start, red at the end."""
_START, _END, _PORTAL = "#2ca02c", "#e01818", "#ffd700"
_REACH = (0.0, 0.55, 0.55)
_REACH_ALPHA = 0.33
_MISSION_ROOM = "#006d6d"
_DPI = 110
_ARROW_SPACING_PX = 70.0
_ARROW_LENGTH_PX = 16.0
_LANE_OFFSET_PX = 4.0
"""Arrows sit this far to the right of travel, so the two legs of an out-and-back path differ."""


def room_colour(room_id: int) -> np.ndarray:
    """The fill colour (RGB in [0, 1]) of a room, fixed by its id."""
    return _PALETTE[room_id % len(_PALETTE)]


@dataclass(frozen=True)
class MissionView:
    """What a drawing shows of a mission.

    Attributes
    ----------
    text:
        the mission as the user gave it (natural language or a formula), put in the title.
    explanation:
        an optional one-line explanation, put under the text.
    cost_m:
        the plan's cost in metres, put in the title.
    propositions:
        the mission's propositions: the reach regions of its ``reach`` objects are shaded and its
        ``enter`` rooms outlined.
    reach_radius_m:
        the global reach radius for ``reach`` propositions without their own (default: the building's).
    """

    text: str | None = None
    explanation: str | None = None
    cost_m: float | None = None
    propositions: Sequence[Proposition] = ()
    reach_radius_m: float | None = None


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


def floor_image(building: Building, floor: int, grid: OccupancyGrid | None = None) -> np.ndarray:
    """The floor's colour raster: ``(rows, cols, 3)`` float RGB in [0, 1] (see the module's colours)."""
    f = building.floors[floor]
    cat, rooms = f.cat_map, f.room_map
    ground = cat == CatCode.GROUND
    # A colour index per cell, then one lookup: much faster than masked writes into the RGB image.
    index = np.where((cat == CatCode.WALL) | (cat == CatCode.CEILING), 1, 0)
    index = np.where(ground, np.where(rooms > 0, 5 + rooms % len(_PALETTE), 2), index)
    index = np.where((cat == CatCode.STAIRS_UP) | (cat == CatCode.STAIRS_DOWN), 3, index)
    index = np.where(cat > 0, 4, index)
    image = _COLOURS[index]
    if grid is not None:  # only ground cells can be blocked, so objects and stairs keep their colours
        blocked = ground & ~grid.traversable[floor]
        image[blocked] = 0.75 * image[blocked] + 0.25 * _WALL
    return image


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
class _Label:
    anchor: tuple[int, int]
    text: str
    style: dict[str, Any]


def _nice_step(extent: float, target: int) -> float:
    """A 1-2-5 step giving at most about ``target`` ticks over ``extent``."""
    for magnitude in 10.0 ** np.arange(-2, 6):
        for base in (1, 2, 2.5, 5):
            if extent / (base * magnitude) <= target:
                return float(base * magnitude)
    return float(extent)


def _nice_floor(value: float) -> float:
    """The largest 1-2-5 number not above ``value`` (> 0)."""
    magnitude = 10.0 ** np.floor(np.log10(value))
    return float(max(b for b in (1, 2, 5) if b * magnitude <= value * (1 + 1e-9)) * magnitude)


def _layout(rows: int, cols: int, title_lines: int, legend_rows: int) -> tuple[Figure, Axes, float]:
    """A figure whose map axes has square cells and fixed margins; returns it, the axes and the font size.

    The axes position is final (no tight_layout later), so label boxes measured now stay right.
    """
    scale = max(min(15.0 / cols, 13.0 / rows), 6.5 / max(rows, cols))  # inches per cell
    map_w, map_h = cols * scale, rows * scale
    font = float(np.clip(min(map_w, map_h) * 0.85, 6.5, 8.5))
    line_in = (font + 4) * 1.45 / 72
    left, right = 0.65, 0.25
    top = 0.25 + title_lines * line_in + 0.35  # title, then the scale bar above the map
    bottom = 0.55 + legend_rows * (font * 2.0 / 72) + 0.1
    width, height = left + map_w + right, top + map_h + bottom
    fig = Figure(figsize=(width, height), dpi=_DPI)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((left / width, bottom / height, map_w / width, map_h / height))
    return fig, ax, font


def _title_lines(
    building: Building,
    floor: int,
    mission: MissionView | None,
    width_chars: int,
    title: str | None,
    note: str | None = None,
) -> list[tuple[str, dict[str, Any]]]:
    f = building.floors[floor]
    head = title or f"{building.name} - floor {floor} ({f.name})"
    if mission is not None and mission.cost_m is not None and np.isfinite(mission.cost_m):
        head += f" - cost {mission.cost_m:.2f} m"
    if note:
        head += f" ({note})"
    lines: list[tuple[str, dict[str, Any]]] = [(head, {"fontweight": "bold"})]
    if mission is not None and mission.text:
        for line in textwrap.wrap(f"mission: {mission.text}", width_chars)[:4]:
            lines.append((line, {}))
    if mission is not None and mission.explanation:
        for line in textwrap.wrap(mission.explanation, width_chars)[:2]:
            lines.append((line, {"fontstyle": "italic", "color": "#333333"}))
    return lines


@dataclass(frozen=True)
class _OnFloor:
    """What a floor shows, so its legend lists only that."""

    grid: bool
    portal: bool
    path: bool
    start: bool
    end: bool
    reach: bool
    mission_room: bool


def _legend_handles(shown: _OnFloor) -> list[Any]:
    handles: list[Any] = [
        Patch(fc=_WALL, label="wall"),
        Patch(fc=_OUTSIDE, ec="0.6", label="outside"),
        Patch(fc=_OBJECT, label="object"),
        Patch(fc=_STAIRS, label="stairs"),
    ]
    if shown.grid:
        handles.append(Patch(fc=0.75 * _UNROOMED_GROUND + 0.25 * _WALL, label="not traversable"))
    if shown.portal:
        handles.append(
            Line2D([], [], ls="none", marker="*", ms=11, color=_PORTAL, mec="black", label="stairs portal")
        )
    if shown.start:
        handles.append(Line2D([], [], ls="none", marker="o", ms=9, color=_START, mec="black", label="start"))
    if shown.end:
        handles.append(Line2D([], [], ls="none", marker="s", ms=9, color=_END, mec="black", label="end"))
    if shown.path:
        handles.append(
            Line2D(
                [], [], color=PATH_COLOURS(0.5), lw=2.2, marker=">", ms=5, label="path (blue early, red late)"
            )
        )
    if shown.reach:
        handles.append(Patch(fc=(*_REACH, _REACH_ALPHA), ec=_REACH, label="reach region (mission)"))
    if shown.mission_room:
        handles.append(Line2D([], [], color=_MISSION_ROOM, lw=2, ls="--", label="mission room"))
    return handles


def _outline(ax: Axes, mask: np.ndarray, **style: Any) -> None:
    """Contour of a boolean mask, computed on its bounding box only (fast on large floors)."""
    rows, cols = np.nonzero(mask.any(axis=1))[0], np.nonzero(mask.any(axis=0))[0]
    if len(rows) == 0:
        return
    r0, r1 = max(rows[0] - 1, 0), min(rows[-1] + 2, mask.shape[0])
    c0, c1 = max(cols[0] - 1, 0), min(cols[-1] + 2, mask.shape[1])
    sub = np.pad(mask[r0:r1, c0:c1].astype(float), 1)
    ax.contour(np.arange(c0 - 1, c1 + 1), np.arange(r0 - 1, r1 + 1), sub, levels=[0.5], **style)


def reach_region(building: Building, floor: int, mission: MissionView) -> np.ndarray:
    """``(rows, cols)`` bool: the cells of ``floor`` within reach of one of the mission's objects."""
    reach = [p for p in mission.propositions if p.kind == "reach"]
    if not reach:
        return np.zeros(building.floors[floor].shape, dtype=bool)
    return label_raster(building, reach, mission.reach_radius_m)[floor] > 0


def _draw_mission_regions(
    ax: Axes, building: Building, floor: int, mission: MissionView, region: np.ndarray
) -> set[int]:
    """Outline the reach ``region`` (shaded in the raster) and the rooms of the mission; returns the ids
    of its objects."""
    f = building.floors[floor]
    if region.any():
        _outline(ax, region, colors=[_REACH], linewidths=0.9, zorder=2.1)
    for p in mission.propositions:
        if p.kind == "enter":
            room = building.room(uuid=p.uuid)
            mask = f.room_map == room.id
            if mask.any():
                _outline(ax, mask, colors=[_MISSION_ROOM], linewidths=2.0, linestyles="--", zorder=2.2)
    return {building.object(uuid=p.uuid).id for p in mission.propositions if p.kind == "reach"}


def _draw_path(ax: Axes, cells: np.ndarray, floor: int, px_per_cell: float) -> np.ndarray:
    """Draw the floor's part of the path with direction arrows; returns its ``(k, 2)`` (x, y) points."""
    n = len(cells)
    progress = np.arange(n) / max(n - 1, 1)
    on_floor = cells[:, 2] == floor
    same = on_floor[:-1] & on_floor[1:]
    xy = cells[:, [1, 0]].astype(float)  # (x = column, y = row)
    segments = list(np.stack([xy[:-1][same], xy[1:][same]], axis=1))
    colours = PATH_COLOURS(progress[:-1][same])
    ax.add_collection(
        LineCollection(segments, colors="white", linewidths=4.2, alpha=0.85, zorder=3.9, capstyle="round")
    )
    ax.add_collection(LineCollection(segments, colors=colours, linewidths=2.2, zorder=4, capstyle="round"))
    _draw_arrows(ax, xy, progress, on_floor, px_per_cell)
    return xy[on_floor]


def arrow_marks(
    xy: np.ndarray, on_floor: np.ndarray, spacing: float, length: float, lane: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where direction arrows go along the runs of a path that lie on one floor.

    Parameters
    ----------
    xy:
        ``(n, 2)`` path points ``(x, y)`` in drawing units (here cells: x = column, y = row).
    on_floor:
        ``(n,)`` bool, the points on the floor drawn.
    spacing, length, lane:
        distance between arrows along the path, arrow length, and offset to the right of travel (so the
        two legs of an out-and-back path are apart), all in drawing units with y growing downwards.

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
        # Right of travel on screen (y grows downwards): (x, y) -> (-y, x).
        points.append((tail[keep] + head[keep]) / 2 + lane * np.column_stack([-unit[:, 1], unit[:, 0]]))
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


def _draw_ticks(ax: Axes, rows: int, cols: int, font: float) -> None:
    step = _nice_step(max(rows, cols), 12)
    ax.set_xticks(np.arange(0, cols, step))
    ax.set_yticks(np.arange(0, rows, step))
    ax.tick_params(labelsize=font, length=3, pad=1.5)
    ax.set_xlabel("column", fontsize=font, labelpad=1)
    ax.set_ylabel("row", fontsize=font, labelpad=1)
    ax.grid(True, color="black", alpha=0.12, lw=0.5)
    ax.set_axisbelow(False)


def _draw_scale_bar(ax: Axes, building: Building, cols: int, map_h_in: float, font: float) -> None:
    """A metre bar above the map's top right corner (in column units: cells are metres / resolution)."""
    res_col = building.resolution_m[1]
    metres = _nice_floor(cols * res_col * 0.25)
    cells = metres / res_col
    transform = blended_transform_factory(ax.transData, ax.transAxes)
    y = 1.0 + 0.1 / map_h_in
    x1 = cols - 0.5
    ax.plot(
        [x1 - cells, x1],
        [y, y],
        color="black",
        lw=2.5,
        transform=transform,
        clip_on=False,
        solid_capstyle="butt",
    )
    ax.text(
        x1 - cells / 2,
        y + 0.04 / map_h_in,
        f"{metres:g} m ({cells:.0f} cells)",
        ha="center",
        va="bottom",
        fontsize=font,
        transform=transform,
    )


def draw_floor(
    building: Building,
    floor: int,
    *,
    grid: OccupancyGrid | None = None,
    path: PathCells | None = None,
    title: str | None = None,
    mission: MissionView | None = None,
) -> Figure:
    """A matplotlib figure of one floor (not attached to pyplot; save it with ``fig.savefig``).

    Parameters
    ----------
    grid:
        shades the ground cells the robot may not enter.
    path:
        ``(row, col, floor[, ...])`` rows (a list of tuples or the planner's ndarray); the floor's part
        is drawn with its direction, the start and the end.
    title:
        replaces the first title line (default: building, floor index and name).
    mission:
        adds the mission text, explanation and cost to the title and marks its rooms and objects.

    Raises
    ------
    SceneError
        for a floor the building lacks, or a malformed path.
    """
    if not 0 <= floor < building.num_floors:
        raise SceneError(
            f"building {building.name!r} has no floor {floor} (floors 0..{building.num_floors - 1})"
        )
    cells = path_cells(path) if path is not None else np.zeros((0, 3), dtype=np.int64)
    f = building.floors[floor]
    rows, cols = f.shape
    portals = [
        (end.portal, word) for end, word in ((f.up_stairs, "up"), (f.down_stairs, "down")) if end is not None
    ]
    here = cells[:, 2] == floor
    region = reach_region(building, floor, mission) if mission is not None else None
    mission_rooms = [
        building.room(uuid=p.uuid).id for p in (mission.propositions if mission else ()) if p.kind == "enter"
    ]
    shown = _OnFloor(
        grid=grid is not None,
        portal=bool(portals),
        path=bool(here.any()),
        start=bool(len(cells)) and bool(here[0]),
        end=bool(len(cells)) and bool(here[-1]),
        reach=region is not None and bool(region.any()),
        mission_room=bool(mission_rooms) and bool(np.isin(f.room_map, mission_rooms).any()),
    )
    handles = _legend_handles(shown)
    note = "the path does not come to this floor" if len(cells) and not shown.path else None

    scale = max(min(15.0 / cols, 13.0 / rows), 6.5 / max(rows, cols))
    fig_w = 0.9 + cols * scale
    legend_cols = max(3, min(len(handles), int(fig_w / 1.55)))
    font_guess = float(np.clip(min(cols, rows) * scale * 0.85, 6.5, 8.5))
    lines = _title_lines(building, floor, mission, int(fig_w * 72 / ((font_guess + 2) * 0.55)), title, note)
    fig, ax, font = _layout(rows, cols, len(lines), -(-len(handles) // legend_cols))

    image = floor_image(building, floor, grid)
    if region is not None:  # blended here: one raster to resample instead of two (drawing time)
        image[region] = (1 - _REACH_ALPHA) * image[region] + _REACH_ALPHA * np.asarray(_REACH)
    ax.imshow((image * 255).round().astype(np.uint8), interpolation="nearest", aspect="auto", zorder=1)
    ax.set_xlim(-0.5, cols - 0.5)
    ax.set_ylim(rows - 0.5, -0.5)
    _draw_ticks(ax, rows, cols, font)
    mission_objects = (
        _draw_mission_regions(ax, building, floor, mission, region)
        if mission is not None and region is not None
        else set()
    )
    px_per_cell = ax.bbox.width / cols
    path_xy = _draw_path(ax, cells, floor, px_per_cell) if len(cells) else np.zeros((0, 2))

    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    x0, y0, x1, y1 = (float(v) for v in ax.bbox.extents)
    placer = LabelPlacer(
        (x0, y0, x1, y1),
        gap=3.0,
        soft_points=ax.transData.transform(path_xy) if len(path_xy) else np.zeros((0, 2)),
    )
    for (r, c), _ in portals:
        ax.plot([c], [r], marker="*", ms=15, color=_PORTAL, mec="black", mew=0.8, zorder=6)
        placer.block(_marker_box(ax, (r, c), 9.0))
    if len(cells):
        start, end = cells[0], cells[-1]
        if end[2] == floor:
            ax.plot([end[1]], [end[0]], "s", ms=12, color=_END, mec="black", zorder=6.5)
            placer.block(_marker_box(ax, (end[0], end[1]), 8.0))
        if start[2] == floor:
            ax.plot([start[1]], [start[0]], "o", ms=10, color=_START, mec="black", zorder=6.6)
            placer.block(_marker_box(ax, (start[0], start[1]), 7.0))
    _place_labels(ax, renderer, placer, _floor_labels(building, floor, portals, mission_objects, font))

    ax.legend(
        handles=handles,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.45 / ax.get_position().height / fig.get_figheight()),
        ncol=legend_cols,
        fontsize=font,
        frameon=True,
        framealpha=0.9,
        borderaxespad=0.0,
        handlelength=1.6,
        columnspacing=1.0,
    )
    top = 1.0 - 0.12 / fig.get_figheight()
    line_h = (font + 4) * 1.45 / 72 / fig.get_figheight()
    for k, (text, style) in enumerate(lines):
        size = font + 4 if k == 0 else font + 2
        fig.text(0.5, top - k * line_h, text, ha="center", va="top", fontsize=size, **style)
    _draw_scale_bar(ax, building, cols, ax.get_position().height * fig.get_figheight(), font)
    return fig


def _marker_box(
    ax: Axes, cell: tuple[int, int] | np.ndarray, half_px: float
) -> tuple[float, float, float, float]:
    x, y = ax.transData.transform((float(cell[1]), float(cell[0])))
    return (x - half_px, y - half_px, x + half_px, y + half_px)


def _floor_labels(
    building: Building,
    floor: int,
    portals: list[tuple[tuple[int, int], str]],
    mission_objects: set[int],
    font: float,
) -> list[_Label]:
    """Every label of the floor, in placement priority: stairs, rooms, mission objects, other objects."""
    f = building.floors[floor]
    labels = []
    for (r, c), word in portals:
        target = floor + 1 if word == "up" else floor - 1
        labels.append(
            _Label(
                (r, c),
                f"stairs {word}\nto floor {target}",
                {
                    "fontsize": font,
                    "color": "#3d1466",
                    "fontweight": "bold",
                    "zorder": 8,
                    "bbox": {
                        "boxstyle": "round,pad=0.2",
                        "fc": "white",
                        "ec": "#3d1466",
                        "lw": 0.6,
                        "alpha": 0.9,
                    },
                },
            )
        )
    known_rooms = {r.id for r in f.rooms.values()} | {r.id for r in building.rooms() if r.floor == floor}
    for room_id, anchor in label_anchors(
        f.room_map, sorted(known_rooms), f.cat_map == CatCode.GROUND
    ).items():
        room = building.room(id=room_id)
        labels.append(
            _Label(
                anchor,
                f"{room.name}\n{room.key}",
                {
                    "fontsize": font + 0.5,
                    "fontweight": "bold",
                    "color": "#1a1a40",
                    "zorder": 7,
                    "bbox": {"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.75},
                },
            )
        )
    known_objects = {o.id for o in building.objects()}
    object_ids = [i for i in np.unique(f.cat_map[f.cat_map > 0]).tolist() if i in known_objects]
    object_ids.sort(key=lambda i: i not in mission_objects)
    for object_id, anchor in label_anchors(f.cat_map, object_ids).items():
        obj = building.object(id=object_id)
        ours = object_id in mission_objects
        labels.append(
            _Label(
                anchor,
                f"{obj.name}\n{obj.key}",
                {
                    "fontsize": font - 1,
                    "color": "#003b3b" if ours else "#4a1d00",
                    "fontweight": "bold" if ours else "normal",
                    "zorder": 7.5 if ours else 7,
                    "bbox": {
                        "boxstyle": "round,pad=0.15",
                        "fc": "#e0fbfb" if ours else "#ffe8cc",
                        "ec": _MISSION_ROOM if ours else "#cc6600",
                        "lw": 1.0 if ours else 0.5,
                        "alpha": 0.88,
                    },
                },
            )
        )
    return labels


def _place_labels(ax: Axes, renderer: Any, placer: LabelPlacer, labels: list[_Label]) -> None:
    """Put each label where :class:`LabelPlacer` finds room; a label moved off its anchor gets a leader."""
    to_data = ax.transData.inverted()
    dpi_scale = ax.figure.dpi / 72
    for label in labels:
        r, c = label.anchor
        anchor = ax.transData.transform((float(c), float(r)))
        text = ax.text(c, r, label.text, ha="center", va="center", **label.style)
        extent = text.get_window_extent(renderer)
        pad = float(label.style["bbox"]["boxstyle"].split("pad=")[1]) * label.style["fontsize"] * dpi_scale
        x0, y0, x1, y1 = placer.place(
            (float(anchor[0]), float(anchor[1])), (extent.width + 2 * pad + 2, extent.height + 2 * pad + 2)
        )
        centre = to_data.transform(((x0 + x1) / 2, (y0 + y1) / 2))
        text.set_position((float(centre[0]), float(centre[1])))
        if not (x0 <= anchor[0] <= x1 and y0 <= anchor[1] <= y1):
            ax.plot(
                [c, centre[0]],
                [r, centre[1]],
                color=label.style["color"],
                lw=0.7,
                alpha=0.8,
                zorder=label.style["zorder"] - 0.05,
            )
            ax.plot([c], [r], "o", ms=2.5, color=label.style["color"], zorder=label.style["zorder"] - 0.05)


def draw_building(
    building: Building,
    out_dir: str | Path,
    *,
    grid: OccupancyGrid | None = None,
    path: PathCells | None = None,
    mission: MissionView | None = None,
    stem: str = "floor",
    formats: Sequence[str] = ("png",),
) -> list[Path]:
    """Write one picture per floor and format, ``<out_dir>/<stem>_<k>.<format>``; returns the paths.

    ``grid`` shades the ground cells the robot may not enter; ``path`` overlays a path of
    ``(row, col, floor[, ...])`` rows (the planner's ``result.path`` ndarray works as it is);
    ``mission`` adds the mission, its explanation and the cost to the titles and marks its regions;
    ``formats`` is any of :data:`FORMATS`.

    Raises
    ------
    SceneError
        for an unknown format, a malformed path, or if ``out_dir`` cannot be created or written to.
    """
    unknown = [fmt for fmt in formats if fmt not in FORMATS]
    if unknown or not formats:
        raise SceneError(
            f"cannot draw format(s) {', '.join(unknown) or '(none)'}: use {' or '.join(FORMATS)}"
        )
    cells = path_cells(path) if path is not None else None
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise SceneError(f"cannot create the drawing folder {out}: {error.strerror}") from None
    written = []
    for floor in range(building.num_floors):
        fig = draw_floor(building, floor, grid=grid, path=cells, mission=mission)
        for fmt in formats:
            target = out / f"{stem}_{floor}.{fmt}"
            try:
                with rc_context({"svg.fonttype": "none"}):  # SVG text stays text: smaller and searchable
                    fig.savefig(target, format=fmt)
            except OSError as error:
                raise SceneError(f"cannot write {target}: {error.strerror}") from None
            written.append(target)
    return written
