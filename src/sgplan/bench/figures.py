"""The paper's two figures from result rows (matplotlib, written as PNG and SVG).

- :func:`cost_vs_time`: path cost against search time, one point per AMRA* iteration, a line per setup,
  a panel per start of one (scene, mission).
- :func:`expansions_per_iteration`: node expansions in each AMRA* iteration, queues grouped by their
  hierarchy level, a panel per setup, for one case.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from sgplan.bench.cases import PAPER_SETUPS
from sgplan.planning.setups import LEVEL_NAMES, queue_level_name

Row = dict[str, Any]
SETUP_COLOURS = {
    "ALL": "#d62728", "OCC": "#ff7f0e", "OBJ": "#bcbd22", "ROOM": "#2ca02c", "FLR": "#17becf",
    "NO-LLM": "#1f77b4", "A*": "#7f7f7f",
}
SETUP_MARKERS = {"ALL": "o", "OCC": "v", "OBJ": "^", "ROOM": "s", "FLR": "D", "NO-LLM": "P", "A*": "X"}
LEVEL_COLOURS = {"anchor": "#444444", "occupancy": "#1f77b4", "object": "#ff7f0e", "room": "#2ca02c",
                 "floor": "#9467bd"}
_MIN_TIME_S = 1e-5  # the log time axis needs a positive floor (a first path can take ~0 s)


def _save(fig: Figure, out_dir: Path, stem: str) -> list[Path]:
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for ext in ("png", "svg"):
        path = out_dir / f"{stem}.{ext}"
        fig.savefig(path, dpi=150 if ext == "png" else None)
        written.append(path)
    return written


def _solved(rows: Sequence[Row], **fields: Any) -> list[Row]:
    return [r for r in rows if r["status"] == "optimal" and r.get("iterations")
            and all(r.get(k) == v for k, v in fields.items())]


def cost_vs_time(rows: Sequence[Row], scene: str, mission: str, out_dir: str | Path,
                 stem: str = "cost_vs_time") -> list[Path]:
    """Path cost (m) vs cumulative search time (s, log scale) per iteration, for every setup and start of
    ``scene`` / ``mission`` that reached the optimum. Returns the PNG and SVG paths ([] without data)."""
    solved = _solved(rows, scene=scene, mission=mission)
    starts = sorted({r["start"] for r in solved})
    if not starts:
        return []
    ncols = 2 if len(starts) == 4 else min(3, len(starts))
    nrows = -(-len(starts) // ncols)
    fig = Figure(figsize=(4.6 * ncols, 3.6 * nrows + 0.9), layout="constrained")
    FigureCanvasAgg(fig)
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).ravel()
    handles: dict[str, Any] = {}
    for ax, start in zip(axes, starts):
        here = {r["setup"]: r for r in solved if r["start"] == start}
        optimum = min(float(r["cost_m"]) for r in here.values())
        ax.axhline(optimum, color="black", lw=0.8, ls="--", zorder=1)
        for setup in [s for s in PAPER_SETUPS if s in here]:
            its = here[setup]["iterations"]
            times = np.maximum([it["time_s"] for it in its], _MIN_TIME_S)
            costs = [it["cost_m"] for it in its]
            (line,) = ax.step(times, costs, where="post", color=SETUP_COLOURS.get(setup), lw=1.6,
                              marker=SETUP_MARKERS.get(setup, "o"), ms=5, alpha=0.9, label=setup, zorder=3)
            handles.setdefault(setup, line)
        ax.set_xscale("log")
        ax.set_title(f"start {start}  (optimum {optimum:.2f} m, dashed)", fontsize=10)
        ax.set_xlabel("search time (s, log scale)")
        ax.set_ylabel("path cost (m)")
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes[len(starts):]:
        ax.set_visible(False)
    profile = solved[0]["profile"]
    fig.suptitle(f"Path cost vs planning time per AMRA* iteration - {scene} mission {mission} "
                 f"(profile {profile})", fontsize=12)
    fig.legend(handles.values(), handles.keys(), loc="outside lower center", ncol=len(handles), fontsize=9)
    return _save(fig, Path(out_dir), stem)


def _per_iteration_levels(row: Row) -> tuple[np.ndarray, list[str]]:
    """``(iterations, levels)`` expansions made during each iteration, summed over the queues of a level;
    and the levels present (in hierarchy order)."""
    cumulative = np.array([it["expansions"] for it in row["iterations"]], dtype=np.int64)
    per_iteration = np.diff(cumulative, axis=0, prepend=0)
    levels = [lv for lv in LEVEL_NAMES if any(queue_level_name(q) == lv for q in row["queues"])]
    grouped = np.stack(
        [per_iteration[:, [i for i, q in enumerate(row["queues"]) if queue_level_name(q) == lv]].sum(axis=1)
         for lv in levels], axis=1)
    return grouped, levels


def default_expansion_case(rows: Sequence[Row], scene: str, mission: str,
                           setups: Sequence[str] = ("ALL", "NO-LLM")) -> int | None:
    """The start of ``scene`` / ``mission`` with the most expansions (summed over ``setups``) among those
    where every one of ``setups`` that was run reached the optimum: the most telling case to draw."""
    best: tuple[int, int] | None = None
    for start in sorted({r["start"] for r in _solved(rows, scene=scene, mission=mission)}):
        ran = [r for r in rows if (r["scene"], r["mission"], r["start"]) == (scene, mission, start)
               and r["setup"] in setups]
        if ran and all(r["status"] == "optimal" for r in ran):
            total = sum(int(r["expansions"]) for r in ran)
            if best is None or total > best[0]:
                best = (total, start)
    return None if best is None else best[1]


def expansions_per_iteration(rows: Sequence[Row], scene: str, mission: str, start: int, out_dir: str | Path,
                             setups: Sequence[str] = ("ALL", "NO-LLM"),
                             stem: str = "expansions_per_iteration") -> list[Path]:
    """Grouped bars: node expansions during each AMRA* iteration (log scale) per hierarchy level (LTL and
    LLM queues of a level added), a panel per setup of ``setups`` run on the case. Returns the PNG and
    SVG paths ([] without data)."""
    chosen = [r for s in setups for r in _solved(rows, scene=scene, mission=mission, start=start, setup=s)]
    if not chosen:
        return []
    fig = Figure(figsize=(6.0 * len(chosen), 4.4), layout="constrained")
    FigureCanvasAgg(fig)
    axes = np.atleast_1d(fig.subplots(1, len(chosen), squeeze=False)).ravel()
    handles: dict[str, Any] = {}
    for ax, row in zip(axes, chosen):
        grouped, levels = _per_iteration_levels(row)
        n_it = grouped.shape[0]
        width = 0.8 / len(levels)
        x = np.arange(n_it)
        for k, level in enumerate(levels):
            bars = ax.bar(x + (k - (len(levels) - 1) / 2) * width, np.maximum(grouped[:, k], 0.8), width,
                          color=LEVEL_COLOURS[level], label=level, zorder=3)
            handles.setdefault(level, bars)
        for i in np.flatnonzero(grouped.sum(axis=1) == 0):
            # AMRA* can end an iteration at once: the previous path already meets the new bound.
            ax.text(i, 1.0, "0", ha="center", va="bottom", fontsize=8, color="0.4")
        ax.set_yscale("log")
        ax.set_ylim(bottom=0.8)
        ax.set_xticks(x, [f"{i + 1}\n({it['w1']:g}, {it['w2']:g})" for i, it in enumerate(row["iterations"])],
                      fontsize=8)
        ax.set_xlabel("AMRA* iteration (w1, w2)")
        ax.set_ylabel("node expansions in the iteration")
        ax.set_title(f"{row['setup']}: {int(grouped.sum()):,} expansions, optimum {row['cost_m']:.2f} m",
                     fontsize=10)
        ax.grid(True, axis="y", which="major", alpha=0.3, zorder=0)
    fig.suptitle(f"Node expansions per planning iteration and hierarchy level - {scene} mission {mission}, "
                 f"start {start}", fontsize=12)
    fig.legend(handles.values(), handles.keys(), loc="outside lower center", ncol=len(handles), fontsize=9)
    return _save(fig, Path(out_dir), stem)
