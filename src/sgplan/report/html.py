"""A self-contained HTML report of one plan: one file that opens offline in any browser.

Everything is inline: floor rasters and hover-lookup rasters as PNG data URIs, the path and markers as
SVG, the automaton as SVG (:mod:`sgplan.report.automaton`), the cost-vs-time chart as SVG, the style
sheet and the script (``report.css``, ``report.js`` beside this module). No network, no CDN.

The page shows: the mission (text, grounded text, formula, the explanation passed in), the result
(status, cost, setup), the floors as switchable layers (path coloured by progress with direction
arrows, start, end, stairs portals, reach regions that can be toggled; hovering a cell names its room
and object with category, id, uuid and floor), the events along the path when the result has them,
the automaton (picture and transition table) and the iterations (chart and table).
"""

from __future__ import annotations

import base64
import html
import io
import json
import math
from collections.abc import Sequence
from importlib import resources
from pathlib import Path
from typing import Any, Protocol

import numpy as np
from PIL import Image

from sgplan.errors import OutputError
from sgplan.logic.dot import edges
from sgplan.mission import Mission
from sgplan.report.automaton import Engine, automaton_svg
from sgplan.scene.draw import floor_image
from sgplan.scene.draw_labels import label_anchors
from sgplan.scene.draw_path import PATH_COLOURS, arrow_marks, path_cells
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.labels import label_raster
from sgplan.scene.model import Building, CatCode

_ARROW_SPACING = 0.06
"""Arrow spacing along the path, as a fraction of the floor's larger side."""


class Iteration(Protocol):
    """One AMRA* iteration as the report reads it (:class:`sgplan.planning.amra.IterationRecord`)."""

    w1: float
    w2: float
    cost_m: float
    bound: float
    time_s: float


class PathEvent(Protocol):
    """An event along the path as the report reads it (:class:`sgplan.outputs.events.Event`)."""

    floor: int
    row: int
    col: int

    def describe(self) -> str: ...


class PlanOutcome(Protocol):
    """What the report reads of a plan result (both ``sgplan.planning.amra.PlanResult`` and
    ``sgplan.result.PlanResult`` fit): the path rows ``(row, col, floor, ...)`` or ``None``, the cost in
    metres, the status, the setup and the iterations."""

    path: np.ndarray | None
    cost_m: float
    status: str
    setup: str
    iterations: Sequence[Any]


def _png_data_uri(rgba: np.ndarray) -> str:
    """``data:image/png;base64,...`` of a ``(rows, cols, 3|4)`` uint8 array."""
    buffer = io.BytesIO()
    Image.fromarray(rgba).save(buffer, format="PNG", optimize=False)
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


def _id_image(ids: np.ndarray) -> str:
    """A raster of non-negative ids (< 2**24) as an opaque PNG: red = low byte, green, blue = high byte.

    Opaque, so browsers keep the exact bytes when the script reads them back through a canvas.
    """
    ids = np.where(ids > 0, ids, 0).astype(np.uint32)
    rgba = np.empty((*ids.shape, 4), dtype=np.uint8)
    rgba[..., 0], rgba[..., 1], rgba[..., 2] = ids & 255, (ids >> 8) & 255, (ids >> 16) & 255
    rgba[..., 3] = 255
    return _png_data_uri(rgba)


def _colour(value: float) -> str:
    r, g, b, _ = PATH_COLOURS(value)
    return f"#{int(r * 255):02x}{int(g * 255):02x}{int(b * 255):02x}"


def _floor_svg(building: Building, floor: int, cells: np.ndarray, events: Sequence[PathEvent] = ()) -> str:
    """The SVG overlay of one floor in cell coordinates (x = column, y = row): path, arrows, markers."""
    f = building.floors[floor]
    rows, cols = f.shape
    unit = cols / 1000  # cells per CSS pixel: the map is shown about 1000 px wide
    parts = [
        (
            f'<svg class="overlay" viewBox="-0.5 -0.5 {cols} {rows}" preserveAspectRatio="none" '
            'xmlns="http://www.w3.org/2000/svg">'
        )
    ]
    rooms = sorted(r.id for r in building.rooms() if r.floor == floor)
    for room_id, (r, c) in label_anchors(f.room_map, rooms, f.cat_map == CatCode.GROUND).items():
        parts.append(
            f'<text class="room-label" x="{c}" y="{r}" font-size="{11 * unit:.2f}">'
            f"{html.escape(building.room(id=room_id).name)}</text>"
        )
    if len(cells):
        n = len(cells)
        on = cells[:, 2] == floor
        xy = cells[:, [1, 0]].astype(float)
        same = on[:-1] & on[1:]
        # One short polyline per colour step keeps the progress colouring without one element per cell.
        steps = 24
        bins = np.minimum((np.arange(n - 1) * steps) // max(n - 1, 1), steps - 1)
        for b in range(steps):
            idx = np.flatnonzero(same & (bins == b))
            if not len(idx):
                continue
            runs = np.split(idx, np.flatnonzero(np.diff(idx) != 1) + 1)
            for run in runs:
                pts = np.concatenate([xy[run], xy[run[-1] + 1][None]])
                text = " ".join(f"{x:g},{y:g}" for x, y in pts)
                parts.append(
                    f'<polyline class="path" points="{text}" stroke="{_colour((b + 0.5) / steps)}"/>'
                )
        centres, vectors, index = arrow_marks(xy, on, _ARROW_SPACING * max(rows, cols), 8 * unit, 3 * unit)
        for (cx, cy), (vx, vy), i in zip(centres, vectors, index):
            angle = math.degrees(math.atan2(vy, vx))
            s = 6.5 * unit
            shape = f"{s:g},0 {-s:g},{-0.7 * s:g} {-0.5 * s:g},0 {-s:g},{0.7 * s:g}"
            parts.append(
                f'<polygon class="arrow" points="{shape}" fill="{_colour(i / max(n - 1, 1))}" '
                f'transform="translate({cx:.2f},{cy:.2f}) rotate({angle:.1f})"/>'
            )
        start, end = cells[0], cells[-1]
        if end[2] == floor:
            s = 7 * unit
            parts.append(
                f'<rect class="end" x="{end[1] - s:.2f}" y="{end[0] - s:.2f}" width="{2 * s:.2f}" '
                f'height="{2 * s:.2f}"><title>end: row {end[0]}, column {end[1]}, floor {floor}</title>'
                "</rect>"
            )
        if start[2] == floor:
            parts.append(
                f'<circle class="start" cx="{start[1]}" cy="{start[0]}" r="{6 * unit:.2f}">'
                f"<title>start: row {start[0]}, column {start[1]}, floor {floor}</title></circle>"
            )
    for event in events:
        if event.floor == floor:
            s = 4.5 * unit
            parts.append(
                f'<rect class="event" x="{-s:.2f}" y="{-s:.2f}" width="{2 * s:.2f}" height="{2 * s:.2f}" '
                f'transform="translate({event.col},{event.row}) rotate(45)">'
                f"<title>{html.escape(event.describe())}</title></rect>"
            )
    for end_, word in ((f.up_stairs, "up"), (f.down_stairs, "down")):
        if end_ is not None:
            r, c = end_.portal
            target = floor + 1 if word == "up" else floor - 1
            parts.append(
                f'<circle class="portal" cx="{c}" cy="{r}" r="{5 * unit:.2f}"><title>stairs {word} to floor '
                f"{target} (row {r}, column {c})</title></circle>"
            )
    parts.append("</svg>")
    return "".join(parts)


def _reach_image(labels: np.ndarray) -> str | None:
    region = labels > 0
    if not region.any():
        return None
    rgba = np.zeros((*region.shape, 4), dtype=np.uint8)
    rgba[region] = (0, 140, 140, 110)
    return _png_data_uri(rgba)


def _floors_html(
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
        image = _png_data_uri((floor_image(building, k, grid) * 255).round().astype(np.uint8))
        objects = np.where(f.cat_map > 0, f.cat_map, 0)
        reach_uri = _reach_image(reach[k]) if reach is not None else None
        layers.append(
            f'<div class="floor" data-floor="{k}" data-rows="{rows}" data-cols="{cols}" hidden>'
            f'<div class="stage" style="aspect-ratio: {cols} / {rows}">'
            f'<img class="map" alt="floor {k} map" src="{image}">'
            + (f'<img class="reach" alt="reach regions on floor {k}" src="{reach_uri}">' if reach_uri else "")
            + _floor_svg(building, k, cells, events)
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


def _entities_json(building: Building) -> str:
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


def _chart_svg(iterations: Sequence[Any]) -> str:
    """Cost (m) against search time (s) of the iterations, as an inline SVG step chart."""
    its = [it for it in iterations if math.isfinite(it.cost_m)]
    if not its:
        return '<p class="empty">No iteration finished with a path.</p>'
    w, h, left, bottom, top, right = 560, 260, 64, 40, 14, 16
    t = np.array([it.time_s for it in its])
    c = np.array([it.cost_m for it in its])
    t_max = float(t.max()) * 1.08 or 1e-3
    c_lo, c_hi = float(c.min()), float(c.max())
    pad = (c_hi - c_lo) * 0.15 or max(c_hi * 0.05, 0.5)
    c_lo, c_hi = max(0.0, c_lo - pad), c_hi + pad

    def x(v: float) -> float:
        return left + (w - left - right) * v / t_max

    def y(v: float) -> float:
        return h - bottom - (h - bottom - top) * (v - c_lo) / (c_hi - c_lo)

    steps = [f"{x(t[0]):.1f},{y(c[0]):.1f}"]
    for k in range(1, len(its)):
        steps += [f"{x(t[k]):.1f},{y(c[k - 1]):.1f}", f"{x(t[k]):.1f},{y(c[k]):.1f}"]
    steps.append(f"{x(t_max):.1f},{y(c[-1]):.1f}")
    parts = [
        (
            f'<svg id="cost-chart" viewBox="0 0 {w} {h}" width="{w}" height="{h}" '
            'xmlns="http://www.w3.org/2000/svg" role="img" aria-label="cost against time">'
        ),
        f'<line class="axis" x1="{left}" y1="{h - bottom}" x2="{w - right}" y2="{h - bottom}"/>',
        f'<line class="axis" x1="{left}" y1="{top}" x2="{left}" y2="{h - bottom}"/>',
    ]
    for v in np.linspace(c_lo, c_hi, 5):
        parts.append(f'<text class="tick" x="{left - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{v:.2f}</text>')
    for v in np.linspace(0, t_max, 5):
        parts.append(
            f'<text class="tick" x="{x(v):.1f}" y="{h - bottom + 16}" text-anchor="middle">{v:.3g}</text>'
        )
    parts.append(
        f'<text class="label" x="{(left + w) / 2}" y="{h - 6}" text-anchor="middle">search time (s)</text>'
    )
    parts.append(
        f'<text class="label" transform="translate(14,{(h - bottom + top) / 2}) rotate(-90)" '
        'text-anchor="middle">path cost (m)</text>'
    )
    parts.append(f'<polyline class="series" points="{" ".join(steps)}"/>')
    for it in its:
        parts.append(
            f'<circle class="point" cx="{x(it.time_s):.1f}" cy="{y(it.cost_m):.1f}" r="4">'
            f"<title>(w1, w2) = ({it.w1:g}, {it.w2:g}): cost {it.cost_m:.3f} m after {it.time_s:.4f} s, "
            f"bound x{it.bound:g}</title></circle>"
        )
    parts.append("</svg>")
    return "".join(parts)


def _table(head: Sequence[str], rows: Sequence[Sequence[Any]], table_id: str) -> str:
    cells = "".join(
        "<tr>" + "".join(f"<td>{html.escape(str(v))}</td>" for v in row) + "</tr>" for row in rows
    )
    return (
        f'<table id="{table_id}"><thead><tr>'
        + "".join(f"<th>{html.escape(h)}</th>" for h in head)
        + f"</tr></thead><tbody>{cells}</tbody></table>"
    )


def _proposition_rows(building: Building, mission: Mission) -> list[tuple[str, str, str]]:
    rows = []
    for ap in mission.automaton.aps:
        p = mission.propositions[ap]
        entity = building.room(uuid=p.uuid) if p.kind == "enter" else building.object(uuid=p.uuid)
        floor = entity.floor if p.kind == "enter" else building.floor_of_object(entity)  # type: ignore[union-attr,arg-type]
        rows.append((ap, p.name, f"{entity.name} ({entity.key}, floor {floor})"))
    return rows


def report_html(
    building: Building,
    grid: OccupancyGrid | None,
    result: PlanOutcome,
    mission: Mission,
    *,
    explanation: str | None = None,
    reach_radius_m: float | None = None,
    title: str | None = None,
    engine: Engine = "auto",
) -> str:
    """The report page as one HTML string (see :func:`write_html_report`)."""
    cells = path_cells(result.path) if result.path is not None else np.zeros((0, 3), dtype=np.int64)
    reach_props = [p for p in mission.ordered_propositions if p.kind == "reach"]
    reach = label_raster(building, reach_props, reach_radius_m) if reach_props else None
    names = mission.descriptions
    cost = f"{result.cost_m:.3f} m" if math.isfinite(result.cost_m) else "no path"
    heading = title or f"sgplan: {building.name}"
    mission_rows = [("mission", mission.text or "(given as a formula)")]
    if mission.grounded_text and mission.grounded_text != mission.text:
        mission_rows.append(("grounded", mission.grounded_text))
    if mission.formula is not None:
        mission_rows.append(("formula", str(mission.formula)))
    summary = [
        ("status", result.status),
        ("cost", cost),
        ("setup", result.setup),
        ("path", f"{len(cells)} cells" if len(cells) else "none"),
        ("start", f"row {cells[0][0]}, column {cells[0][1]}, floor {cells[0][2]}" if len(cells) else "-"),
    ]
    events = getattr(result, "events", None) or []
    sections = [
        f"<header><h1>{html.escape(heading)}</h1></header>",
        '<section id="mission"><h2>Mission</h2><dl>'
        + "".join(f"<dt>{html.escape(k)}</dt><dd>{html.escape(v)}</dd>" for k, v in mission_rows)
        + "</dl>"
        + (f'<p id="explanation">{html.escape(explanation)}</p>' if explanation else "")
        + "<h3>Propositions</h3>"
        + _table(("name", "meaning", "in the scene"), _proposition_rows(building, mission), "propositions")
        + "</section>",
        '<section id="result"><h2>Result</h2><dl>'
        + "".join(f"<dt>{k}</dt><dd>{html.escape(v)}</dd>" for k, v in summary)
        + "</dl></section>",
        '<section id="map"><h2>Floors</h2><p class="hint">Hover the map for rooms and objects. '
        "The path runs from blue (start, green circle) to red (end, red square); arrows show the "
        "direction; gold dots are stairs portals, white diamonds the events (hover them).</p>"
        + _floors_html(building, grid, cells, reach, events)
        + "</section>",
    ]
    if events:
        sections.append(
            '<section id="events"><h2>Events along the path</h2><ol>'
            + "".join(f"<li>{html.escape(e.describe())}</li>" for e in events)
            + "</ol></section>"
        )
    sections.append(
        '<section id="automaton"><h2>Automaton</h2><p class="hint">Double circles accept; a missing edge '
        "rejects (states that cannot accept are left out). In a large automaton the edges carry the "
        "numbers of the table below.</p>"
        f'<div class="automaton-svg">{automaton_svg(mission.automaton, names=names, engine=engine)}</div>'
        + _table(
            ("#", "from", "to", "when"),
            [(k, *edge) for k, edge in enumerate(edges(mission.automaton, True, names), start=1)],
            "transitions",
        )
        + "</section>"
    )
    iteration_rows = [
        (
            f"({it.w1:g}, {it.w2:g})",
            f"{it.cost_m:.3f}" if math.isfinite(it.cost_m) else "-",
            f"x{it.bound:g}",
            f"{it.time_s:.4f}",
        )
        for it in result.iterations
    ]
    sections.append(
        '<section id="iterations"><h2>Iterations (cost against time)</h2>'
        + _chart_svg(result.iterations)
        + _table(("(w1, w2)", "cost (m)", "bound", "time (s)"), iteration_rows, "iteration-table")
        + "</section>"
    )
    page = resources.files("sgplan.report").joinpath("template.html").read_text(encoding="utf-8")
    css = resources.files("sgplan.report").joinpath("report.css").read_text(encoding="utf-8")
    script = resources.files("sgplan.report").joinpath("report.js").read_text(encoding="utf-8")
    return (
        page.replace("<!--TITLE-->", html.escape(heading))
        .replace("/*CSS*/", css)
        .replace("<!--BODY-->", "\n".join(sections))
        .replace("<!--DATA-->", _entities_json(building))
        .replace("/*JS*/", script)
    )


def write_html_report(
    path: str | Path,
    building: Building,
    grid: OccupancyGrid | None,
    result: PlanOutcome,
    mission: Mission,
    *,
    explanation: str | None = None,
    reach_radius_m: float | None = None,
    title: str | None = None,
    engine: Engine = "auto",
) -> Path:
    """Write the self-contained HTML report of one plan to ``path``; returns the path.

    Parameters
    ----------
    building, grid:
        the scene and the occupancy grid planned on (``grid`` shades cells the robot may not enter).
    result:
        the plan (:class:`PlanOutcome`); a result without a path still gets a report. If it has
        ``events`` (``sgplan.result.PlanResult``), they are listed.
    mission:
        the mission planned (text, formula, propositions, automaton).
    explanation:
        the mission explained in plain language, shown under the mission.
    reach_radius_m:
        the reach radius planned with (default: the building's), for the shaded reach regions.
    title:
        the page heading (default ``sgplan: <building>``).
    engine:
        how the automaton is drawn (see :func:`sgplan.report.automaton.automaton_svg`).

    Raises
    ------
    OutputError
        if the file cannot be written.
    """
    text = report_html(
        building,
        grid,
        result,
        mission,
        explanation=explanation,
        reach_radius_m=reach_radius_m,
        title=title,
        engine=engine,
    )
    target = Path(path)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text, encoding="utf-8")
    except OSError as error:
        raise OutputError(f"cannot write the HTML report {target}: {error.strerror}") from None
    return target
