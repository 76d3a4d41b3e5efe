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

import html
import math
from collections.abc import Sequence
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from sgplan.errors import OutputError
from sgplan.logic.dot import edges
from sgplan.mission import Mission
from sgplan.report.automaton import Engine, automaton_svg
from sgplan.report.chart import chart_svg
from sgplan.report.floors import entities_json, floors_html, place_text
from sgplan.report.outcome import PathEvent, PlanOutcome
from sgplan.scene.draw_path import path_cells
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.labels import label_raster
from sgplan.scene.model import Building, category_words
from sgplan.scene.reach import DEFAULT_REACH_MODEL


def _table(head: Sequence[str], rows: Sequence[Sequence[Any]], table_id: str) -> str:
    cells = "".join(
        "<tr>" + "".join(f"<td>{html.escape(str(v))}</td>" for v in row) + "</tr>" for row in rows
    )
    return (
        f'<table id="{table_id}"><thead><tr>'
        + "".join(f"<th>{html.escape(h)}</th>" for h in head)
        + f"</tr></thead><tbody>{cells}</tbody></table>"
    )


def _propositions_table(building: Building, mission: Mission) -> str:
    """Each proposition, its action token when it has another name (a mission folder's ``p1``), and the
    room or object it names."""
    rows = []
    for ap in mission.automaton.aps:
        p = mission.propositions[ap]
        entity = building.room(uuid=p.uuid) if p.kind == "enter" else building.object(uuid=p.uuid)
        floor = entity.floor if p.kind == "enter" else building.floor_of_object(entity)  # type: ignore[union-attr,arg-type]
        rows.append((ap, p.name, f"{category_words(entity.name)} ({entity.key}, floor {floor})"))
    if all(ap == name for ap, name, _ in rows):
        return _table(("proposition", "in the scene"), [(ap, where) for ap, _, where in rows], "propositions")
    return _table(("name", "meaning", "in the scene"), rows, "propositions")


def _mission_section(building: Building, mission: Mission, explanation: str | None) -> str:
    rows = [("mission", mission.text or "(given as a formula)")]
    if mission.grounded_text and mission.grounded_text != mission.text:
        rows.append(("grounded", mission.grounded_text))
    if mission.formula is not None:
        rows.append(("formula", str(mission.formula)))
    return (
        '<section id="mission"><h2>Mission</h2>'
        + _definitions(rows)
        + (f'<p id="explanation">{html.escape(explanation)}</p>' if explanation else "")
        + "<h3>Propositions</h3>"
        + _propositions_table(building, mission)
        + "</section>"
    )


def _result_section(building: Building, result: PlanOutcome, cells: np.ndarray) -> str:
    rows = [
        ("status", result.status),
        ("cost", f"{result.cost_m:.3f} m" if math.isfinite(result.cost_m) else "no path"),
        ("setup", result.setup),
        ("path", f"{len(cells)} cells" if len(cells) else "none"),
        ("start", f"{place_text(building, int(cells[0][2]), int(cells[0][0]), int(cells[0][1]))}, floor "
                  f"{cells[0][2]}" if len(cells) else "-"),
    ]
    return '<section id="result"><h2>Result</h2>' + _definitions(rows) + "</section>"


def _map_section(
    building: Building,
    grid: OccupancyGrid | None,
    mission: Mission,
    cells: np.ndarray,
    events: Sequence[PathEvent],
    reach_radius_m: float | None,
    reach_model: str,
) -> str:
    reach_props = [p for p in mission.ordered_propositions if p.kind == "reach"]
    reach = label_raster(building, reach_props, reach_radius_m, reach_model) if reach_props else None
    return (
        '<section id="map"><h2>Floors</h2><p class="hint">In the map frame: x to the right, y upwards, '
        "metres. Hover the map for the place, its room and object. "
        "The path runs from blue (start, green circle) to red (end, red square); arrows show the "
        "direction; gold dots are stairs portals, white diamonds the events (hover them).</p>"
        + floors_html(building, grid, cells, reach, events)
        + "</section>"
    )


def _events_section(events: Sequence[PathEvent]) -> str:
    if not events:
        return ""
    items = "".join(f"<li>{html.escape(e.describe())}</li>" for e in events)
    return f'<section id="events"><h2>Events along the path</h2><ol>{items}</ol></section>'


def _automaton_section(mission: Mission, engine: Engine) -> str:
    names = mission.descriptions
    numbered = [(k, *edge) for k, edge in enumerate(edges(mission.automaton, True, names), start=1)]
    return (
        '<section id="automaton"><h2>Automaton</h2><p class="hint">Double circles accept; a missing edge '
        "rejects (states that cannot accept are left out). In a large automaton the edges carry the "
        "numbers of the table below.</p>"
        f'<div class="automaton-svg">{automaton_svg(mission.automaton, names=names, engine=engine)}</div>'
        + _table(("#", "from", "to", "when"), numbered, "transitions")
        + "</section>"
    )


def _iterations_section(result: PlanOutcome) -> str:
    rows = [
        (
            f"({it.w1:g}, {it.w2:g})",
            f"{it.cost_m:.3f}" if math.isfinite(it.cost_m) else "-",
            f"x{it.bound:g}",
            f"{it.time_s:.4f}",
        )
        for it in result.iterations
    ]
    return (
        '<section id="iterations"><h2>Iterations (cost against time)</h2>'
        + chart_svg(result.iterations)
        + _table(("(w1, w2)", "cost (m)", "bound", "time (s)"), rows, "iteration-table")
        + "</section>"
    )


def _definitions(rows: Sequence[tuple[str, str]]) -> str:
    return "<dl>" + "".join(f"<dt>{html.escape(k)}</dt><dd>{html.escape(v)}</dd>" for k, v in rows) + "</dl>"


def report_html(
    building: Building,
    grid: OccupancyGrid | None,
    result: PlanOutcome,
    mission: Mission,
    *,
    explanation: str | None = None,
    reach_radius_m: float | None = None,
    reach_model: str = DEFAULT_REACH_MODEL,
    title: str | None = None,
    engine: Engine = "auto",
) -> str:
    """The report page as one HTML string (see :func:`write_html_report`)."""
    cells = path_cells(result.path) if result.path is not None else np.zeros((0, 3), dtype=np.int64)
    events: Sequence[PathEvent] = getattr(result, "events", None) or []
    heading = title or f"sgplan: {building.name}"
    sections = [
        f"<header><h1>{html.escape(heading)}</h1></header>",
        _mission_section(building, mission, explanation),
        _result_section(building, result, cells),
        _map_section(building, grid, mission, cells, events, reach_radius_m, reach_model),
        _events_section(events),
        _automaton_section(mission, engine),
        _iterations_section(result),
    ]
    package = resources.files("sgplan.report")
    return (
        package.joinpath("template.html")
        .read_text(encoding="utf-8")
        .replace("<!--TITLE-->", html.escape(heading))
        .replace("/*CSS*/", package.joinpath("report.css").read_text(encoding="utf-8"))
        .replace("<!--BODY-->", "\n".join(s for s in sections if s))
        .replace("<!--DATA-->", entities_json(building))
        .replace("/*JS*/", package.joinpath("report.js").read_text(encoding="utf-8"))
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
    reach_model: str = DEFAULT_REACH_MODEL,
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
    reach_radius_m, reach_model:
        the reach radius (default: the building's) and reach model (:mod:`sgplan.scene.reach`) planned
        with, for the shaded reach regions.
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
        reach_model=reach_model,
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
