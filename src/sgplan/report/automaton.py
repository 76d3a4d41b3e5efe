"""The mission automaton as a picture: SVG from Graphviz ``dot`` when installed, else from matplotlib.

Graphviz lays out large automata far better, so it is used when its ``dot`` program is on the PATH (the
Debian package ``graphviz``); without it a layered matplotlib drawing is made (states in columns by
their distance from the initial state, edges as arcs labelled with their guards), so a picture is
always written. Both use :func:`sgplan.logic.dot.edges`, so they show the same edges.
"""

from __future__ import annotations

import html
import io
import shutil
import subprocess
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Literal

import numpy as np
from matplotlib import rc_context
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Circle, FancyArrowPatch

from sgplan.errors import AutomatonError, OutputError
from sgplan.logic.automaton import Automaton
from sgplan.logic.dot import edges, shown_states, to_dot, wrap_guard

Engine = Literal["auto", "graphviz", "matplotlib"]
NUMBERED_ABOVE_EDGES = 12
"""Automata with more edges are drawn with numbered edges (guards in a table / tooltips)."""
MATPLOTLIB_MAX_STATES = 16
"""Above this many shown states the matplotlib layout is unreadable: a note replaces the picture."""
GRAPHVIZ_TIMEOUT_S = 30.0
"""Longest ``dot`` may run; automata that need longer to lay out are drawn by matplotlib instead."""


def graphviz_available() -> bool:
    """Whether Graphviz's ``dot`` program is on the PATH."""
    return shutil.which("dot") is not None


def automaton_svg(
    a: Automaton,
    *,
    names: Mapping[str, str] | None = None,
    hide_sinks: bool = True,
    engine: Engine = "auto",
    numbered: bool | None = None,
) -> str:
    """The automaton as SVG text (an ``<svg>`` document without an XML prolog, ready to inline in HTML).

    Parameters
    ----------
    names:
        renames propositions in the edge guards, e.g. ``mission.descriptions``.
    hide_sinks:
        leave out the states that cannot reach acceptance (a missing edge then means "rejects").
    engine:
        ``"graphviz"`` (needs ``dot``), ``"matplotlib"``, or ``"auto"``: Graphviz when available and
        working, else matplotlib.
    numbered:
        label edges ``[k]`` (their position in :func:`sgplan.logic.dot.edges`, from 1) instead of their
        guards; ``None`` does so above :data:`NUMBERED_ABOVE_EDGES` edges.

    Raises
    ------
    AutomatonError
        with ``engine="graphviz"`` when ``dot`` is missing or fails.
    """
    if engine not in ("auto", "graphviz", "matplotlib"):
        raise AutomatonError(f"unknown automaton drawing engine {engine!r}: use auto, graphviz or matplotlib")
    if numbered is None:
        numbered = len(edges(a, hide_sinks)) > NUMBERED_ABOVE_EDGES
    if engine == "graphviz" or (engine == "auto" and graphviz_available()):
        try:
            return _strip_prolog(_graphviz_svg(to_dot(a, hide_sinks, names=names, numbered=numbered)))
        except AutomatonError:
            if engine == "graphviz":
                raise
    return _strip_prolog(_matplotlib_svg(a, names, hide_sinks, numbered))


def _graphviz_svg(dot: str) -> str:
    if not graphviz_available():
        raise AutomatonError("Graphviz is not installed (no `dot` on the PATH); install the graphviz package")
    try:
        done = subprocess.run(
            ["dot", "-Tsvg"],
            input=dot,
            capture_output=True,
            text=True,
            timeout=GRAPHVIZ_TIMEOUT_S,
            check=False,
        )
    except (OSError, subprocess.TimeoutExpired) as error:
        raise AutomatonError(f"Graphviz `dot` could not draw the automaton: {error}") from None
    if done.returncode != 0:
        raise AutomatonError(f"Graphviz `dot` failed (exit {done.returncode}): {done.stderr.strip()[:300]}")
    return done.stdout


def _strip_prolog(svg: str) -> str:
    """The ``<svg ...>...</svg>`` element alone (no ``<?xml?>`` / ``<!DOCTYPE>``, which HTML rejects)."""
    start = svg.find("<svg")
    return svg[start:] if start >= 0 else svg


def _layers(a: Automaton, shown: np.ndarray) -> dict[int, tuple[int, int]]:
    """``state -> (column, row)``: column = breadth-first distance from the initial state."""
    depth = {a.initial: 0}
    frontier = [a.initial]
    while frontier:
        nxt = []
        for q in frontier:
            for r in np.unique(a.table[q]).tolist():
                if shown[r] and r not in depth:
                    depth[r] = depth[q] + 1
                    nxt.append(r)
        frontier = nxt
    for q in np.flatnonzero(shown).tolist():  # shown but unreachable: one column after the rest
        depth.setdefault(q, max(depth.values()) + 1)
    rows: dict[int, int] = {}
    place = {}
    for q in sorted(depth, key=lambda s: (depth[s], s)):
        place[q] = (depth[q], rows.get(depth[q], 0))
        rows[depth[q]] = place[q][1] + 1
    # Centre each column vertically.
    tallest = max(rows.values())
    return {q: (c, r - (rows[c] - 1) / 2 + (tallest - 1) / 2) for q, (c, r) in place.items()}  # type: ignore[misc]


def _matplotlib_svg(a: Automaton, names: Mapping[str, str] | None, hide_sinks: bool, numbered: bool) -> str:
    """The automaton drawn by matplotlib (no Graphviz): states in layers, as SVG text; a one-line note
    instead when it has more than :data:`MATPLOTLIB_MAX_STATES` states."""
    shown = shown_states(a, hide_sinks)
    if shown.sum() > MATPLOTLIB_MAX_STATES:
        return _too_large_svg(int(shown.sum()), len(edges(a, hide_sinks)))
    place = _layers(a, shown)
    columns = max(c for c, _ in place.values()) + 1
    tallest = max(r for _, r in place.values()) + 1
    guards = [
        (q, r, f"[{k}]" if numbered else wrap_guard(g))
        for k, (q, r, g) in enumerate(edges(a, hide_sinks, names), start=1)
    ]
    # Room for the widest and tallest guard between two columns / rows (7 pt text: ~0.06 in a char).
    widest = max((len(line) for *_, g in guards for line in g.split("\n")), default=4)
    tallest_guard = max((g.count("\n") + 1 for *_, g in guards), default=1)
    dx, dy = max(2.0, 0.065 * widest + 0.9), max(1.5, 0.16 * tallest_guard + 0.9)
    fig = Figure(figsize=(1.5 + dx * columns, 1.0 + dy * tallest))
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(-1.0, dx * (columns - 1) + 1.0)
    ax.set_ylim(dy * (tallest - 1) + 0.8, -0.8)
    ax.set_aspect("equal")
    ax.set_axis_off()
    xy = {q: (dx * c, dy * r) for q, (c, r) in place.items()}
    _draw_states(ax, a, xy)
    pairs = {(q, r) for q, r, _ in edges(a, hide_sinks)}
    for q, r, guard in guards:
        _draw_edge(ax, xy, q, r, guard, bend_apart=(r, q) in pairs)
    buffer = io.StringIO()
    with rc_context({"svg.fonttype": "none"}):  # text stays text: smaller, searchable, selectable
        fig.savefig(buffer, format="svg", bbox_inches="tight", pad_inches=0.1)  # guards may overhang the axes
    return buffer.getvalue()


def _too_large_svg(states: int, edge_count: int) -> str:
    """A one-line SVG saying that the automaton is too large to draw without Graphviz."""
    note = (
        f"{states} states, {edge_count} edges: too large to draw without "
        "Graphviz (install the graphviz package); the DOT file and the transition table list every edge."
    )
    return (
        '<svg xmlns="http://www.w3.org/2000/svg" width="900" height="40" viewBox="0 0 900 40">'
        f'<text x="4" y="24" font-size="13">{html.escape(note)}</text></svg>'
    )


_STATE_RADIUS = 0.28
"""A state's circle, in the drawing's units (a layer is at least 2 apart)."""


def _draw_states(ax: Any, a: Automaton, xy: Mapping[int, tuple[float, float]]) -> None:
    """Each state a circle (accepting: a double one) with its number; an arrow into the initial one."""
    radius = _STATE_RADIUS
    for q, (x, y) in xy.items():
        ax.add_patch(Circle((x, y), radius, fc="white", ec="black", lw=1.2, zorder=3))
        if a.accepting[q]:
            ax.add_patch(Circle((x, y), radius * 0.8, fc="none", ec="black", lw=1.0, zorder=3))
        ax.text(x, y, str(q), ha="center", va="center", fontsize=10, zorder=4)
    x, y = xy[a.initial]
    ax.add_patch(FancyArrowPatch((x - 0.8, y), (x - radius, y), arrowstyle="-|>", mutation_scale=12))


def _draw_edge(ax: Any, xy: Mapping[int, tuple[float, float]], q: int, r: int, guard: str, *,
               bend_apart: bool) -> None:
    """The edge ``q -> r`` with its guard: a loop above the state, or an arc (bent further when the
    edge ``r -> q`` is drawn too, so the two are apart) labelled at its midpoint."""
    style: dict[str, Any] = {
        "fontsize": 7,
        "ha": "center",
        "va": "center",
        "multialignment": "left",
        "zorder": 5,
        "bbox": {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85},
    }
    if q == r:  # a loop above the state
        x, y = xy[q][0], xy[q][1] - _STATE_RADIUS
        ax.add_patch(
            FancyArrowPatch(
                (x - 0.12, y),
                (x + 0.12, y),
                connectionstyle="arc3,rad=-2.2",
                arrowstyle="-|>",
                mutation_scale=10,
                lw=0.9,
                zorder=2,
            )
        )
        ax.text(x, y - 0.3, guard, **{**style, "va": "bottom"})
        return
    rad = 0.25 if bend_apart else 0.12  # rad > 0 bends to the right
    p0, p1 = xy[q], xy[r]
    ax.add_patch(
        FancyArrowPatch(
            p0,
            p1,
            connectionstyle=f"arc3,rad={rad}",
            arrowstyle="-|>",
            mutation_scale=11,
            lw=0.9,
            shrinkA=14,
            shrinkB=14,
            zorder=2,
        )
    )
    ddx, ddy = p1[0] - p0[0], p1[1] - p0[1]
    # The arc's midpoint: half way to arc3's control point (display y grows down here: flip the sign).
    mid_x, mid_y = (p0[0] + p1[0]) / 2 - 0.5 * rad * ddy, (p0[1] + p1[1]) / 2 + 0.5 * rad * ddx
    ax.text(mid_x, mid_y, guard, **style)


def write_automaton(
    a: Automaton,
    out_dir: str | Path,
    *,
    stem: str = "automaton",
    names: Mapping[str, str] | None = None,
    hide_sinks: bool = True,
    engine: Engine = "auto",
) -> list[Path]:
    """Write ``<stem>.dot`` and ``<stem>.svg`` into ``out_dir``; returns both paths.

    See :func:`automaton_svg` for the options. The DOT file always has the guards in full; in a large
    automaton's SVG the edges are numbered (with Graphviz, hovering an edge shows its guard).

    Raises :class:`OutputError` if the files cannot be written, :class:`AutomatonError` as
    :func:`automaton_svg` does.
    """
    out = Path(out_dir)
    dot_path, svg_path = out / f"{stem}.dot", out / f"{stem}.svg"
    svg = automaton_svg(a, names=names, hide_sinks=hide_sinks, engine=engine)
    try:
        out.mkdir(parents=True, exist_ok=True)
        dot_path.write_text(to_dot(a, hide_sinks, name=stem, names=names), encoding="utf-8")
        svg_path.write_text(svg, encoding="utf-8")
    except OSError as error:
        raise OutputError(f"cannot write the automaton drawing into {out}: {error.strerror}") from None
    return [dot_path, svg_path]
