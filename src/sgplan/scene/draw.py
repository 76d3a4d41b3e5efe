"""Drawings of a building, one PNG per floor, with an optional path on top (matplotlib, Agg backend).

Colours: outside light grey, walls dark grey, each room its own pastel colour (labelled with its
category and ``room_<uuid>``), objects dark orange (labelled with class and ``object_<uuid>``), stairs
purple, stairs portals as stars. With an occupancy grid, ground cells the robot may not enter (too close
to an obstacle, or outside every room) are shaded. A path is a sequence of ``(row, col, floor)`` cells;
each floor shows its part, the start as a green circle and the end as a red square.

Images use matrix orientation: rows (metric x) downwards, columns (metric y) to the right.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib import colormaps
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from scipy import ndimage

from sgplan.errors import SceneError
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building, CatCode

PathCells = Sequence[tuple[int, int, int]]
"""A path as ``(row, col, floor)`` cells, in order."""

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


def room_colour(room_id: int) -> np.ndarray:
    """The fill colour (RGB in [0, 1]) of a room, fixed by its id."""
    return _PALETTE[room_id % len(_PALETTE)]


def floor_image(building: Building, floor: int, grid: OccupancyGrid | None = None) -> np.ndarray:
    """The floor's colour raster: ``(rows, cols, 3)`` float RGB in [0, 1] (see the module's colours)."""
    f = building.floors[floor]
    cat, rooms = f.cat_map, f.room_map
    image = np.empty((*cat.shape, 3))
    image[:] = _OUTSIDE
    image[(cat == CatCode.WALL) | (cat == CatCode.CEILING)] = _WALL
    ground = cat == CatCode.GROUND
    image[ground] = _UNROOMED_GROUND
    in_room = ground & (rooms > 0)
    image[in_room] = _PALETTE[rooms[in_room] % len(_PALETTE)]
    if grid is not None:
        blocked = ground & ~grid.traversable[floor]
        image[blocked] = 0.75 * image[blocked] + 0.25 * _WALL
    image[(cat == CatCode.STAIRS_UP) | (cat == CatCode.STAIRS_DOWN)] = _STAIRS
    image[cat > 0] = _OBJECT
    return image


def _label_positions(
    raster: np.ndarray, ids: np.ndarray, open_cells: np.ndarray | None = None
) -> dict[int, tuple[float, float]]:
    """For each id, the (row, col) of a label spot: the cell of the id farthest inside its region.

    With ``open_cells``, the spot is sought among the region's open cells first (room labels go on
    free floor rather than on the furniture), falling back to the whole region.
    """
    positions = {}
    for value in ids.tolist():
        mask = raster == value
        if open_cells is not None and (mask & open_cells).any():
            mask &= open_cells
        rows, cols = np.nonzero(mask.any(axis=1))[0], np.nonzero(mask.any(axis=0))[0]
        r0, r1, c0, c1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
        depth = ndimage.distance_transform_edt(np.pad(mask[r0:r1, c0:c1], 1))[1:-1, 1:-1]
        r, c = np.unravel_index(int(np.argmax(depth)), depth.shape)
        positions[int(value)] = (float(r0 + r), float(c0 + c))
    return positions


def draw_floor(
    building: Building,
    floor: int,
    *,
    grid: OccupancyGrid | None = None,
    path: PathCells | None = None,
    title: str | None = None,
) -> Figure:
    """A matplotlib figure of one floor (not attached to pyplot; save it with ``fig.savefig``)."""
    if not 0 <= floor < building.num_floors:
        raise SceneError(
            f"building {building.name!r} has no floor {floor} (floors 0..{building.num_floors - 1})"
        )
    f = building.floors[floor]
    rows, cols = f.shape
    width_in = float(np.clip(cols / 70.0, 7.0, 16.0))
    fig = Figure(figsize=(width_in, width_in * rows / cols + 0.6), dpi=110)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.imshow(floor_image(building, floor, grid), interpolation="nearest")
    ax.set_axis_off()
    font = float(np.clip(min(rows, cols) / 45.0, 6.0, 8.5))

    room_ids = np.unique(f.room_map[f.room_map > 0])
    room_ids_known = {r.id for r in building.rooms()}
    known_rooms = np.array([i for i in room_ids.tolist() if i in room_ids_known], dtype=f.room_map.dtype)
    for room_id, (r, c) in _label_positions(f.room_map, known_rooms, f.cat_map == CatCode.GROUND).items():
        room = building.room(id=room_id)
        ax.text(
            c, r, f"{room.name}\n{room.key}", ha="center", va="center", fontsize=font + 0.5,
            fontweight="bold", color="#1a1a40", zorder=7,
            bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.7},
        )
    object_ids = np.unique(f.cat_map[f.cat_map > 0])
    object_ids_known = {o.id for o in building.objects()}
    known = [i for i in object_ids.tolist() if i in object_ids_known]
    for object_id, (r, c) in _label_positions(f.cat_map, np.array(known, dtype=f.cat_map.dtype)).items():
        obj = building.object(id=object_id)
        ax.text(
            c, r, f"{obj.name}\n{obj.key}", ha="center", va="center", fontsize=font - 1,
            color="#4a1d00",
            bbox={"boxstyle": "round,pad=0.15", "fc": "#ffe8cc", "ec": "#cc6600", "lw": 0.5, "alpha": 0.85},
        )
    for end, word in ((f.up_stairs, "up"), (f.down_stairs, "down")):
        if end is None:
            continue
        r, c = end.portal
        ax.plot([c], [r], marker="*", ms=14, color="#ffd700", mec="black", mew=0.8, zorder=5)
        target = floor + 1 if word == "up" else floor - 1
        ax.annotate(
            f"stairs {word} to floor {target}", (c, r), xytext=(8, 8), textcoords="offset points",
            fontsize=font, color="#3d1466", fontweight="bold",
            bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "#3d1466", "lw": 0.5, "alpha": 0.8},
            zorder=6,
        )
    if path:
        _draw_path(ax, path, floor)
    legend = [
        Patch(fc=_WALL, label="wall"),
        Patch(fc=_OUTSIDE, ec="0.6", label="outside"),
        Patch(fc=_OBJECT, label="object"),
        Patch(fc=_STAIRS, label="stairs"),
    ]
    if grid is not None:
        legend.append(Patch(fc=0.75 * _UNROOMED_GROUND + 0.25 * _WALL, label="not traversable"))
    ax.legend(handles=legend, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=len(legend),
              fontsize=font, frameon=True, framealpha=0.8, borderaxespad=0.2)
    ax.set_title(title or f"{building.name} - floor {floor} ({f.name})", fontsize=font + 4, pad=18)
    fig.tight_layout(pad=0.4)
    return fig


def _draw_path(ax, path: PathCells, floor: int) -> None:
    cells = np.asarray(path, dtype=np.int64).reshape(-1, 3)
    on_floor = cells[:, 2] == floor
    # Split into runs of consecutive cells on this floor (a path may leave and come back by stairs).
    breaks = np.flatnonzero(np.diff(on_floor.astype(np.int8)) != 0) + 1
    for run in np.split(np.arange(len(cells)), breaks):
        if len(run) and on_floor[run[0]]:
            ax.plot(cells[run, 1], cells[run, 0], color="#d62728", lw=2.0, zorder=4)
    start, end = cells[0], cells[-1]
    if start[2] == floor:
        ax.plot([start[1]], [start[0]], "o", ms=10, color="#2ca02c", mec="black", zorder=6, label="start")
    if end[2] == floor:
        ax.plot([end[1]], [end[0]], "s", ms=10, color="#d62728", mec="black", zorder=6, label="end")


def draw_building(
    building: Building,
    out_dir: str | Path,
    *,
    grid: OccupancyGrid | None = None,
    path: PathCells | None = None,
    stem: str = "floor",
) -> list[Path]:
    """Write one PNG per floor, ``<out_dir>/<stem>_<k>.png``; returns the paths written.

    ``grid`` shades the ground cells the robot may not enter; ``path`` overlays a path of
    ``(row, col, floor)`` cells.

    Raises
    ------
    SceneError
        if ``out_dir`` cannot be created or written to.
    """
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise SceneError(f"cannot create the drawing folder {out}: {error.strerror}") from None
    written = []
    for floor in range(building.num_floors):
        fig = draw_floor(building, floor, grid=grid, path=path)
        target = out / f"{stem}_{floor}.png"
        partial = out / f".{target.name}.{os.getpid()}.tmp"
        try:
            fig.savefig(partial, format="png")
            os.replace(partial, target)  # an earlier drawing stays whole if this one fails
        except OSError as error:
            raise SceneError(f"cannot write {target}: {error.strerror}") from None
        finally:
            partial.unlink(missing_ok=True)
        written.append(target)
    return written
