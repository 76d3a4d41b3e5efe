"""Drawings of a building, one picture (PNG and/or SVG) per floor, with an optional plan on top.

Colours: outside light grey, walls dark grey, each room its own pastel colour (labelled with its
category and ``room_<uuid>``), objects dark orange (labelled with class and ``object_<uuid>``), stairs
purple, stairs portals as gold stars. With an occupancy grid, ground cells the robot may not enter (too
close to an obstacle, or outside every room) are shaded.

A path is a sequence of ``(row, col, floor)`` cells -- a list of tuples or the planner's ``(n, 4)``
ndarray. Each floor shows its part, coloured from blue (early) to red (late) with arrows in the
direction of travel (:mod:`sgplan.scene.draw_path`); the start is a green circle and the end a red
square. Labels are placed so that they cover neither those markers, nor the stairs portals, nor each
other (:mod:`sgplan.scene.draw_labels`). Each floor's legend lists what that floor shows.

A :class:`MissionView` adds the mission (text or formula) and the cost to the title, its explanation
to a caption under the legend (both wrapped, never cut), shades the reach regions of the mission's
``reach`` objects and outlines its ``enter`` rooms.

Pictures are in the map frame as ROS and RViz show it: metric x to the right, metric y upwards
(:mod:`sgplan.scene.draw_axes`), ticked in metres, or in grid rows and columns with ``axes="cells"``
(so a ``--start ROW,COL,FLOOR`` can be read off); a scale bar gives metres and cells.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib import colormaps, rc_context
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.transforms import blended_transform_factory

from sgplan.errors import SceneError
from sgplan.files import write_file_atomically
from sgplan.scene.draw_axes import axis_ticks, axis_titles, check_axes
from sgplan.scene.draw_labels import floor_labels, marker_box, place_labels
from sgplan.scene.draw_path import PATH_COLOURS, PathCells, draw_path, path_cells
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.labels import Proposition, label_raster
from sgplan.scene.model import Building, CatCode
from sgplan.scene.placement import LabelPlacer
from sgplan.scene.reach import DEFAULT_REACH_MODEL

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
_REACH = (0.0, 0.55, 0.55)
_REACH_ALPHA = 0.33
_MISSION_ROOM = "#006d6d"
_START, _END, _PORTAL = "#2ca02c", "#e01818", "#ffd700"
_DPI = 110


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
        an optional explanation, put in a caption under the legend.
    cost_m:
        the plan's cost in metres, put in the title.
    propositions:
        the mission's propositions: the reach regions of its ``reach`` objects are shaded and its
        ``enter`` rooms outlined.
    reach_radius_m:
        the global reach radius for ``reach`` propositions without their own (default: the building's).
    reach_model:
        where an object counts as reached (:mod:`sgplan.scene.reach`): ``"visible"`` or ``"box"``.
    """

    text: str | None = None
    explanation: str | None = None
    cost_m: float | None = None
    propositions: Sequence[Proposition] = ()
    reach_radius_m: float | None = None
    reach_model: str = DEFAULT_REACH_MODEL


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


def _nice_floor(value: float) -> float:
    """The largest 1-2-5 number not above ``value`` (> 0)."""
    magnitude = 10.0 ** np.floor(np.log10(value))
    return float(max(b for b in (1, 2, 5) if b * magnitude <= value * (1 + 1e-9)) * magnitude)


@dataclass(frozen=True)
class _Frame:
    """The map's size on paper: inches per cell, map width and height (inches), base font (points).

    ``width_cells`` run along the horizontal axis (the grid's rows, metric x), ``height_cells`` along
    the vertical one (its columns, metric y)."""

    scale: float
    map_w: float
    map_h: float
    font: float

    @classmethod
    def of(cls, width_cells: int, height_cells: int) -> _Frame:
        scale = max(min(15.0 / width_cells, 13.0 / height_cells), 6.5 / max(width_cells, height_cells))
        map_w, map_h = width_cells * scale, height_cells * scale
        return cls(scale, map_w, map_h, float(np.clip(min(map_w, map_h) * 0.85, 6.5, 8.5)))

    @property
    def width(self) -> float:
        """Figure width in inches (the map and its side margins)."""
        return _LEFT_IN + self.map_w + _RIGHT_IN

    def chars_per_line(self, font: float) -> int:
        """How many characters of ``font`` points fit across the figure (a wide average glyph: lines
        wrapped to it never reach the edges)."""
        return max(20, int((self.width - 0.3) * 72 / (font * 0.62)))


_LEFT_IN, _RIGHT_IN = 0.75, 0.3


def _line_in(font: float) -> float:
    """The height of a text line of ``font`` points, inches."""
    return font * 1.45 / 72


@dataclass(frozen=True)
class _Texts:
    """The title lines (bold head, then the mission) and the caption lines (the explanation), wrapped to
    the figure's width, each with its matplotlib style."""

    title: list[tuple[str, dict[str, Any]]]
    caption: list[tuple[str, dict[str, Any]]]

    @property
    def title_in(self) -> float:
        return sum(_line_in(style["fontsize"]) for _, style in self.title)

    @property
    def caption_in(self) -> float:
        return sum(_line_in(style["fontsize"]) for _, style in self.caption)


def _layout(frame: _Frame, texts: _Texts, legend_rows: int) -> tuple[Figure, Axes]:
    """A figure whose map axes has square cells and fixed margins for the title, the legend and the
    caption.

    The axes position is final (no tight_layout later), so label boxes measured now stay right.
    """
    top = 0.25 + texts.title_in + 0.35  # title, then the scale bar above the map
    bottom = 0.6 + legend_rows * (frame.font * 2.0 / 72) + 0.15 + texts.caption_in + 0.15
    width, height = frame.width, top + frame.map_h + bottom
    fig = Figure(figsize=(width, height), dpi=_DPI)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((_LEFT_IN / width, bottom / height, frame.map_w / width, frame.map_h / height))
    return fig, ax


def _texts(
    building: Building,
    floor: int,
    mission: MissionView | None,
    frame: _Frame,
    title: str | None,
    note: str | None = None,
) -> _Texts:
    """The title (head and mission text) and the caption (explanation), wrapped in full: never cut."""
    f = building.floors[floor]
    head = title or f"{building.name} - floor {floor} ({f.name})"
    if mission is not None and mission.cost_m is not None and np.isfinite(mission.cost_m):
        head += f" - cost {mission.cost_m:.2f} m"
    if note:
        head += f" ({note})"
    big, normal = frame.font + 4, frame.font + 2
    lines = [(line, {"fontweight": "bold", "fontsize": big})
             for line in textwrap.wrap(head, frame.chars_per_line(big))]
    if mission is not None and mission.text:
        lines += [(line, {"fontsize": normal})
                  for line in textwrap.wrap(f"mission: {mission.text}", frame.chars_per_line(normal))]
    caption = []
    if mission is not None and mission.explanation:
        style = {"fontstyle": "italic", "color": "#333333", "fontsize": frame.font + 1}
        width = frame.chars_per_line(frame.font + 1)
        for paragraph in mission.explanation.splitlines():
            caption += [(line, style) for line in textwrap.wrap(paragraph, width)]
    return _Texts(lines, caption)


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
    # Drawing coordinates are (x, y) = (row, col) (sgplan.scene.draw_axes): the transposed mask.
    ax.contour(np.arange(r0 - 1, r1 + 1), np.arange(c0 - 1, c1 + 1), sub.T, levels=[0.5], **style)


def reach_region(building: Building, floor: int, mission: MissionView) -> np.ndarray:
    """``(rows, cols)`` bool: the cells of ``floor`` within reach of one of the mission's objects."""
    reach = [p for p in mission.propositions if p.kind == "reach"]
    if not reach:
        return np.zeros(building.floors[floor].shape, dtype=bool)
    return label_raster(building, reach, mission.reach_radius_m, mission.reach_model)[floor] > 0


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


def _draw_ticks(ax: Axes, building: Building, floor: int, axes: str, font: float) -> None:
    f = building.floors[floor]
    rows, cols = f.shape
    horizontal = axis_ticks(rows, f.origin_m[0], f.resolution_m[0], axes)
    vertical = axis_ticks(cols, f.origin_m[1], f.resolution_m[1], axes)
    ax.set_xticks(horizontal.positions, horizontal.labels)
    ax.set_yticks(vertical.positions, vertical.labels)
    # Unlabelled minor ticks on all four sides, a fifth of a step apart, to read a place off the picture.
    ax.set_xticks(horizontal.minor, minor=True)
    ax.set_yticks(vertical.minor, minor=True)
    ax.tick_params(which="both", top=True, right=True)
    ax.tick_params(labelsize=font, length=3, pad=1.5)
    ax.tick_params(which="minor", length=1.5)
    x_title, y_title = axis_titles(axes)
    ax.set_xlabel(x_title, fontsize=font, labelpad=1)
    ax.set_ylabel(y_title, fontsize=font, labelpad=1)
    ax.grid(True, color="black", alpha=0.12, lw=0.5)
    ax.set_axisbelow(False)


def _draw_scale_bar(ax: Axes, building: Building, rows: int, map_h_in: float, font: float) -> None:
    """A metre bar above the map's top right corner, along metric x (the grid's rows)."""
    res_row = building.resolution_m[0]
    metres = _nice_floor(rows * res_row * 0.25)
    cells = metres / res_row
    transform = blended_transform_factory(ax.transData, ax.transAxes)
    y = 1.0 + 0.1 / map_h_in
    x1 = rows - 0.5
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
    axes: str = "metres",
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
        adds the mission text and cost to the title, its explanation in a caption, and marks its rooms
        and objects.
    axes:
        ``"metres"`` (map-frame x and y) or ``"cells"`` (grid rows and columns); the picture is in the
        map frame either way (:mod:`sgplan.scene.draw_axes`).

    Raises
    ------
    SceneError
        for a floor the building lacks, a malformed path, or unknown ``axes``.
    """
    check_axes(axes)
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
    region = reach_region(building, floor, mission) if mission is not None else None
    shown = _shown(building, floor, grid, cells, region, mission)
    handles = _legend_handles(shown)
    note = "the path does not come to this floor" if len(cells) and not shown.path else None
    frame = _Frame.of(rows, cols)
    legend_cols = max(3, min(len(handles), int(frame.width / 1.55)))
    texts = _texts(building, floor, mission, frame, title, note)
    fig, ax = _layout(frame, texts, -(-len(handles) // legend_cols))

    image = floor_image(building, floor, grid)
    if region is not None:  # blended here: one raster to resample instead of two (drawing time)
        image[region] = (1 - _REACH_ALPHA) * image[region] + _REACH_ALPHA * np.asarray(_REACH)
    # x = row to the right, y = column upwards: the raster transposed, drawn from the bottom.
    picture = np.swapaxes((image * 255).round().astype(np.uint8), 0, 1)
    ax.imshow(picture, interpolation="nearest", aspect="auto", origin="lower", zorder=1)
    ax.set_xlim(-0.5, rows - 0.5)
    ax.set_ylim(-0.5, cols - 0.5)
    _draw_ticks(ax, building, floor, axes, frame.font)
    mission_objects = set()
    if mission is not None and region is not None:
        mission_objects = _draw_mission_regions(ax, building, floor, mission, region)
    path_xy = draw_path(ax, cells, floor, ax.bbox.width / rows) if len(cells) else np.zeros((0, 2))
    placer = _draw_markers(ax, portals, cells, floor, path_xy)
    labels = floor_labels(building, floor, portals, mission_objects, frame.font)
    place_labels(ax, fig.canvas.get_renderer(), placer, labels)  # type: ignore[attr-defined]

    _add_legend_and_texts(fig, ax, handles, legend_cols, texts, frame.font)
    _draw_scale_bar(ax, building, rows, frame.map_h, frame.font)
    return fig


def _shown(
    building: Building,
    floor: int,
    grid: OccupancyGrid | None,
    cells: np.ndarray,
    region: np.ndarray | None,
    mission: MissionView | None,
) -> _OnFloor:
    here = cells[:, 2] == floor
    rooms = [
        building.room(uuid=p.uuid).id for p in (mission.propositions if mission else ()) if p.kind == "enter"
    ]
    f = building.floors[floor]
    return _OnFloor(
        grid=grid is not None,
        portal=f.up_stairs is not None or f.down_stairs is not None,
        path=bool(here.any()),
        start=bool(len(cells)) and bool(here[0]),
        end=bool(len(cells)) and bool(here[-1]),
        reach=region is not None and bool(region.any()),
        mission_room=bool(rooms) and bool(np.isin(f.room_map, rooms).any()),
    )


def _draw_markers(
    ax: Axes, portals: list[tuple[tuple[int, int], str]], cells: np.ndarray, floor: int, path_xy: np.ndarray
) -> LabelPlacer:
    """Draw the portals, the end and the start; returns a label placer that keeps labels off them (and,
    if it can, off the path)."""
    x0, y0, x1, y1 = (float(v) for v in ax.bbox.extents)
    soft = ax.transData.transform(path_xy) if len(path_xy) else np.zeros((0, 2))
    placer = LabelPlacer((x0, y0, x1, y1), gap=3.0, soft_points=soft)
    for (r, c), _ in portals:
        ax.plot([r], [c], marker="*", ms=15, color=_PORTAL, mec="black", mew=0.8, zorder=6)
        placer.block(marker_box(ax, (r, c), 9.0))
    if len(cells):
        start, end = cells[0], cells[-1]
        if end[2] == floor:
            ax.plot([end[0]], [end[1]], "s", ms=12, color=_END, mec="black", zorder=6.5)
            placer.block(marker_box(ax, (end[0], end[1]), 8.0))
        if start[2] == floor:  # drawn last: on top of the end when a path comes back to its start
            ax.plot([start[0]], [start[1]], "o", ms=10, color=_START, mec="black", zorder=6.6)
            placer.block(marker_box(ax, (start[0], start[1]), 7.0))
    return placer


def _add_legend_and_texts(
    fig: Figure,
    ax: Axes,
    handles: list[Any],
    legend_cols: int,
    texts: _Texts,
    font: float,
) -> None:
    """The legend under the map (below the tick labels), the title lines at the top and the caption
    lines at the bottom."""
    height = fig.get_figheight()
    ax.legend(
        handles=handles,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.5 / (ax.get_position().height * height)),
        ncol=legend_cols,
        fontsize=font,
        frameon=True,
        framealpha=0.9,
        borderaxespad=0.0,
        handlelength=1.6,
        columnspacing=1.0,
    )
    top = 1.0 - 0.12 / height
    for text, style in texts.title:
        fig.text(0.5, top, text, ha="center", va="top", **style)
        top -= _line_in(style["fontsize"]) / height
    top = (0.15 + texts.caption_in) / height
    for text, style in texts.caption:
        fig.text(0.5, top, text, ha="center", va="top", **style)
        top -= _line_in(style["fontsize"]) / height


def draw_building(
    building: Building,
    out_dir: str | Path,
    *,
    grid: OccupancyGrid | None = None,
    path: PathCells | None = None,
    mission: MissionView | None = None,
    stem: str = "floor",
    formats: Sequence[str] = FORMATS,
    axes: str = "metres",
) -> list[Path]:
    """Write one picture per floor and format, ``<out_dir>/<stem>_<k>.<format>``; returns the paths.

    ``grid`` shades the ground cells the robot may not enter; ``path`` overlays a path of
    ``(row, col, floor[, ...])`` rows (the planner's ``result.path`` ndarray works as it is);
    ``mission`` adds the mission, its explanation and the cost to the titles and marks its regions;
    ``formats`` is any of :data:`FORMATS` (default: both); ``axes`` is ``"metres"`` or ``"cells"``
    (:func:`draw_floor`).

    Raises
    ------
    SceneError
        for an unknown format or axes, a malformed path, or if ``out_dir`` cannot be created or written to.
    """
    unknown = [fmt for fmt in formats if fmt not in FORMATS]
    if unknown or not formats:
        raise SceneError(
            f"cannot draw format(s) {', '.join(unknown) or '(none)'}: use {' or '.join(FORMATS)}"
        )
    check_axes(axes)
    cells = path_cells(path) if path is not None else None
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise SceneError(f"cannot create the drawing folder {out}: {error.strerror}") from None
    written = []
    for floor in range(building.num_floors):
        fig = draw_floor(building, floor, grid=grid, path=cells, mission=mission, axes=axes)
        for fmt in formats:
            target = out / f"{stem}_{floor}.{fmt}"
            try:
                with rc_context({"svg.fonttype": "none"}):  # SVG text stays text: smaller and searchable
                    # an earlier drawing stays whole if this one fails
                    write_file_atomically(target, partial(fig.savefig, format=fmt))
            except OSError as error:
                raise SceneError(f"cannot write {target}: {error.strerror}") from None
            written.append(target)
    return written
