"""The floors of the HTML report: one layer per floor, all inline.

Floors are shown in the map frame, like the PNG pictures (:mod:`sgplan.scene.draw_axes`): metric x
(the grid's rows) to the right, metric y (its columns) upwards, with ticks in metres. A layer is the
floor raster as a PNG data URI, the reach regions as a second (toggled) PNG, an SVG overlay in cell units
with ``x = row`` and ``y = cols - 1 - col`` (SVG's y grows downwards: room names, the path coloured by
progress with arrows, start, end, portals, events with tooltips), the metre axes, and two id rasters
(room and object id per cell, in the bytes of opaque PNGs, in the same orientation) that the page's
script reads back to name what the pointer is over, with its metres, row and column.
"""

from __future__ import annotations

import base64
import html
import io
import json
import math
from collections.abc import Sequence

import numpy as np
from PIL import Image

from sgplan.errors import OutputError
from sgplan.report.outcome import PathEvent
from sgplan.scene.draw import floor_image
from sgplan.scene.draw_axes import axis_ticks
from sgplan.scene.draw_labels import label_anchors
from sgplan.scene.draw_path import PATH_COLOURS, arrow_marks
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building, CatCode
from sgplan.scene.placement import LabelPlacer

_ARROW_SPACING = 0.06
"""Arrow spacing along the path, as a fraction of the floor's larger side."""


def _map_frame(raster: np.ndarray) -> np.ndarray:
    """A ``(rows, cols, ...)`` raster as shown: ``(cols, rows, ...)``, the last column at the top, rows
    from left to right."""
    return np.flipud(np.swapaxes(raster, 0, 1))


def _png_data_uri(rgba: np.ndarray) -> str:
    """``data:image/png;base64,...`` of a ``(height, width, 3|4)`` uint8 array."""
    buffer = io.BytesIO()
    Image.fromarray(rgba).save(buffer, format="PNG", optimize=False)
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


def _id_image(ids: np.ndarray) -> str:
    """A raster of ids (< 2**24; negative ones read as 0) as an opaque PNG: red = low byte, green, blue =
    high byte. Opaque, so browsers keep the exact bytes when the script reads them back through a canvas.
    """
    if ids.size and int(ids.max()) >= 1 << 24:
        raise OutputError(f"an id raster holds id {int(ids.max())}; the HTML report encodes ids below 2**24")
    ids = np.where(ids > 0, ids, 0).astype(np.uint32)
    rgba = np.empty((*ids.shape, 4), dtype=np.uint8)
    rgba[..., 0], rgba[..., 1], rgba[..., 2] = ids & 255, (ids >> 8) & 255, (ids >> 16) & 255
    rgba[..., 3] = 255
    return _png_data_uri(_map_frame(rgba))


def _colour(value: float) -> str:
    r, g, b, _ = PATH_COLOURS(value)
    return f"#{int(r * 255):02x}{int(g * 255):02x}{int(b * 255):02x}"


def _svg_xy(rows: np.ndarray | int, cols: np.ndarray | int, num_cols: int) -> np.ndarray:
    """SVG coordinates of cells: ``x = row``, ``y = num_cols - 1 - col`` (metric y upwards)."""
    return np.column_stack([np.atleast_1d(rows), num_cols - 1 - np.atleast_1d(cols)]).astype(float)


def floor_svg(building: Building, floor: int, cells: np.ndarray, events: Sequence[PathEvent] = ()) -> str:
    """The SVG overlay of one floor in the map frame (:func:`_svg_xy`): room names, the path with its
    arrows, then the portals, events, end and start on top. ``cells``: the path's ``(n, 3)``
    ``(row, col, floor)`` rows (empty: no path). The report draws each floor with it, and the live page of
    ``sgplan serve`` swaps it in when a path changes."""
    f = building.floors[floor]
    rows, cols = f.shape
    unit = rows / 1000  # cells per CSS pixel: the map is shown about 1000 px wide
    head = (
        f'<svg class="overlay" viewBox="-0.5 -0.5 {rows} {cols}" preserveAspectRatio="none" '
        'xmlns="http://www.w3.org/2000/svg">'
    )
    path = _path_svg(cells, floor, unit, max(rows, cols), cols) if len(cells) else []
    names = _room_names_svg(building, floor, cells, unit)
    return head + "".join(path + names + _markers_svg(building, floor, cells, events, unit)) + "</svg>"


def _axes_svg(building: Building, floor: int) -> str:
    """Ticks in metres along the bottom (x) and the left (y) of the map, outside it."""
    f = building.floors[floor]
    rows, cols = f.shape
    unit = rows / 1000
    font = 11 * unit
    parts = [f'<svg class="axes" viewBox="-0.5 -0.5 {rows} {cols}" preserveAspectRatio="none" '
             'xmlns="http://www.w3.org/2000/svg">']
    x_ticks = axis_ticks(rows, f.origin_m[0], f.resolution_m[0], "metres")
    y_ticks = axis_ticks(cols, f.origin_m[1], f.resolution_m[1], "metres")
    bottom, left = cols - 0.5, -0.5
    for position, label in zip(x_ticks.positions, x_ticks.labels):
        parts.append(f'<line x1="{position:.2f}" y1="{bottom:.2f}" x2="{position:.2f}" '
                     f'y2="{bottom + 5 * unit:.2f}"/><text class="tick" x="{position:.2f}" '
                     f'y="{bottom + 16 * unit:.2f}" font-size="{font:.2f}">{label}</text>')
    for position, label in zip(y_ticks.positions, y_ticks.labels):
        y = cols - 1 - position
        parts.append(f'<line x1="{left - 5 * unit:.2f}" y1="{y:.2f}" x2="{left:.2f}" y2="{y:.2f}"/>'
                     f'<text class="tick y" x="{left - 8 * unit:.2f}" y="{y:.2f}" font-size="{font:.2f}">'
                     f"{label}</text>")
    parts.append(f'<text class="title" x="{rows / 2:.2f}" y="{bottom + 32 * unit:.2f}" '
                 f'font-size="{font:.2f}">x (m)</text>')
    parts.append(f'<text class="title y" x="{left - 44 * unit:.2f}" y="{cols / 2:.2f}" '
                 f'font-size="{font:.2f}">y (m)</text>')
    return "".join(parts) + "</svg>"


def _room_names_svg(building: Building, floor: int, cells: np.ndarray, unit: float) -> list[str]:
    """Room names at their rooms' freest cells, moved off the start, end and portals (and each other)."""
    f = building.floors[floor]
    rows, cols = f.shape
    placer = LabelPlacer((-0.5, -0.5, rows - 0.5, cols - 0.5), gap=2 * unit)
    markers = [end.portal for end in (f.up_stairs, f.down_stairs) if end is not None]
    markers += [(int(cell[0]), int(cell[1])) for cell in (*cells[:1], *cells[-1:]) if cell[2] == floor]
    for r, c in markers:
        x, y = _svg_xy(r, c, cols)[0]
        placer.block((x - 8 * unit, y - 8 * unit, x + 8 * unit, y + 8 * unit))
    font = 11 * unit
    parts = []
    rooms = sorted(r.id for r in building.rooms() if r.floor == floor)
    for room_id, (r, c) in label_anchors(f.room_map, rooms, f.cat_map == CatCode.GROUND).items():
        name = building.room(id=room_id).name
        x, y = _svg_xy(r, c, cols)[0]
        # Box size from the text length: about 0.6 em a character in the report's sans-serif font.
        x0, y0, x1, y1 = placer.place((x, y), (0.62 * font * len(name) + 4 * unit, 1.3 * font))
        parts.append(
            f'<text class="room-label" x="{(x0 + x1) / 2:.2f}" y="{(y0 + y1) / 2:.2f}" '
            f'font-size="{font:.2f}" stroke-width="{3 * unit:.2f}">{html.escape(name)}</text>'
        )
    return parts


def _path_svg(cells: np.ndarray, floor: int, unit: float, size: int, num_cols: int) -> list[str]:
    """The floor's part of the path: polylines coloured by progress, and direction arrows."""
    n = len(cells)
    on = cells[:, 2] == floor
    xy = _svg_xy(cells[:, 0], cells[:, 1], num_cols)
    same = on[:-1] & on[1:]
    # One polyline per colour step and run keeps the progress colouring without one element per cell.
    steps = 24
    bins = np.minimum((np.arange(n - 1) * steps) // max(n - 1, 1), steps - 1)
    parts = []
    for b in range(steps):
        idx = np.flatnonzero(same & (bins == b))
        for run in np.split(idx, np.flatnonzero(np.diff(idx) != 1) + 1) if len(idx) else []:
            pts = np.concatenate([xy[run], xy[run[-1] + 1][None]])
            text = " ".join(f"{x:g},{y:g}" for x, y in pts)
            parts.append(f'<polyline class="path" points="{text}" stroke="{_colour((b + 0.5) / steps)}"/>')
    s = 6.5 * unit
    shape = f"{s:g},0 {-s:g},{-0.7 * s:g} {-0.5 * s:g},0 {-s:g},{0.7 * s:g}"
    centres, vectors, index = arrow_marks(xy, on, _ARROW_SPACING * size, 8 * unit, 3 * unit)
    for (cx, cy), (vx, vy), i in zip(centres, vectors, index):
        parts.append(
            f'<polygon class="arrow" points="{shape}" fill="{_colour(i / max(n - 1, 1))}" '
            f'transform="translate({cx:.2f},{cy:.2f}) rotate({math.degrees(math.atan2(vy, vx)):.1f})"/>'
        )
    return parts


def place_text(building: Building, floor: int, row: int, col: int) -> str:
    """``x 1.23 m, y 4.56 m (row r, column c)`` of a cell's centre."""
    x_m, y_m = building.floors[floor].cell_to_xy((row, col))
    return f"x {x_m:.2f} m, y {y_m:.2f} m (row {row}, column {col})"


def _markers_svg(
    building: Building, floor: int, cells: np.ndarray, events: Sequence[PathEvent], unit: float
) -> list[str]:
    """Portals, events, end and start of one floor, each with a tooltip; later ones lie on top."""
    f = building.floors[floor]
    cols = f.shape[1]
    parts = []
    for end_, word in ((f.up_stairs, "up"), (f.down_stairs, "down")):
        if end_ is not None:
            r, c = end_.portal
            x, y = _svg_xy(r, c, cols)[0]
            target = floor + 1 if word == "up" else floor - 1
            parts.append(
                f'<circle class="portal" cx="{x:g}" cy="{y:g}" r="{5 * unit:.2f}"><title>stairs {word} to '
                f"floor {target} ({place_text(building, floor, r, c)})</title></circle>"
            )
    s = 4.5 * unit
    for event in (e for e in events if e.floor == floor):
        x, y = _svg_xy(event.row, event.col, cols)[0]
        parts.append(
            f'<rect class="event" x="{-s:.2f}" y="{-s:.2f}" width="{2 * s:.2f}" height="{2 * s:.2f}" '
            f'transform="translate({x:g},{y:g}) rotate(45)">'
            f"<title>{html.escape(event.describe())}</title></rect>"
        )
    if len(cells) and cells[-1][2] == floor:
        r, c, s = int(cells[-1][0]), int(cells[-1][1]), 7 * unit
        x, y = _svg_xy(r, c, cols)[0]
        parts.append(
            f'<rect class="end" x="{x - s:.2f}" y="{y - s:.2f}" width="{2 * s:.2f}" height="{2 * s:.2f}">'
            f"<title>end: {place_text(building, floor, r, c)}, floor {floor}</title></rect>"
        )
    if len(cells) and cells[0][2] == floor:
        r, c = int(cells[0][0]), int(cells[0][1])
        x, y = _svg_xy(r, c, cols)[0]
        parts.append(
            f'<circle class="start" cx="{x:g}" cy="{y:g}" r="{6 * unit:.2f}">'
            f"<title>start: {place_text(building, floor, r, c)}, floor {floor}</title></circle>"
        )
    return parts


def _reach_image(labels: np.ndarray) -> str | None:
    region = labels > 0
    if not region.any():
        return None
    rgba = np.zeros((*region.shape, 4), dtype=np.uint8)
    rgba[region] = (0, 140, 140, 110)
    return _png_data_uri(_map_frame(rgba))


def floors_html(
    building: Building,
    grid: OccupancyGrid | None,
    cells: np.ndarray,
    reach: np.ndarray | None,
    events: Sequence[PathEvent],
) -> str:
    tabs, layers = [], []
    for f in building.floors:
        k = f.index
        rows, cols = f.shape
        on_floor = int((cells[:, 2] == k).sum()) if len(cells) else 0
        tabs.append(
            f'<button type="button" class="floor-tab" data-floor="{k}">floor {k} ({html.escape(f.name)})'
            f"{f' - {on_floor} path cells' if on_floor else ''}</button>"
        )
        image = _png_data_uri(_map_frame((floor_image(building, k, grid) * 255).round().astype(np.uint8)))
        objects = np.where(f.cat_map > 0, f.cat_map, 0)
        reach_uri = _reach_image(reach[k]) if reach is not None else None
        layers.append(
            f'<div class="floor" data-floor="{k}" data-rows="{rows}" data-cols="{cols}" '
            f'data-origin="{f.origin_m[0]!r} {f.origin_m[1]!r}" '
            f'data-resolution="{f.resolution_m[0]!r} {f.resolution_m[1]!r}" hidden>'
            f'<div class="stage" style="aspect-ratio: {rows} / {cols}">'
            f'<img class="map" alt="floor {k} map" src="{image}">'
            + (f'<img class="reach" alt="reach regions on floor {k}" src="{reach_uri}">' if reach_uri else "")
            + floor_svg(building, k, cells, events)
            + _axes_svg(building, k)
            + f'<img class="ids rooms" hidden alt="" src="{_id_image(f.room_map)}">'
            f'<img class="ids objects" hidden alt="" src="{_id_image(objects)}">'
            "</div></div>"
        )
    return (
        '<div id="floor-tabs" role="tablist">' + "".join(tabs) + "</div>"
        '<label class="toggle"><input type="checkbox" id="show-reach" checked> '
        "reach regions of the mission</label>"
        '<div id="floors">' + "".join(layers) + '</div><div id="tooltip" hidden></div>'
    )


def entities_json(building: Building) -> str:
    rooms = {
        str(r.id): {"name": r.name, "key": r.key, "uuid": r.uuid, "floor": r.floor} for r in building.rooms()
    }
    objects = {}
    for o in building.objects():
        objects[str(o.id)] = {
            "name": o.name,
            "key": o.key,
            "uuid": o.uuid,
            "floor": building.floor_of_object(o),
            "room": building.room(id=o.room_id).key if o.room_id else None,
        }
    # "</" would end the script element early.
    return json.dumps({"rooms": rooms, "objects": objects}).replace("</", "<\\/")
