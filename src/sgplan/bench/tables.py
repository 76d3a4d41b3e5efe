"""Markdown tables in the paper's layout from result rows, with the paper's numbers beside ours.

Only rows with status ``optimal`` enter a mean (the paper's metrics need the optimum); every other row
is listed apart by :func:`excluded_table` with its reason.
"""

from __future__ import annotations

import statistics
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

from sgplan.bench.cases import PAPER_SETUPS, TABLE2_MISSION, TABLE2_SCENE, TABLE3_SETUPS, mission_order
from sgplan.bench.paper import TABLE2, TABLE3, PaperCell

Row = dict[str, Any]
COST_TOLERANCE_M = 1e-6
"""Two setups' optimal costs of one (scene, mission, start) agree when they differ by at most this."""


@dataclass(frozen=True)
class Means:
    """Means over ``n`` optimal rows: search seconds to the first path and to the optimum, first cost /
    optimal cost, precompute and load seconds, whole-case wall seconds, peak RSS in MiB."""

    n: int
    first_time_s: float
    cost_ratio: float
    optimal_time_s: float
    precompute_s: float
    load_s: float
    wall_s: float
    peak_rss_mb: float

    @property
    def triple(self) -> PaperCell:
        return (self.first_time_s, self.cost_ratio, self.optimal_time_s)


def means(rows: Iterable[Row]) -> Means | None:
    """Means of the optimal rows among ``rows`` (``None`` if there are none)."""
    solved = [r for r in rows if r["status"] == "optimal"]
    if not solved:
        return None

    def mean(name: str) -> float:
        values = [float(r[name]) for r in solved if r.get(name) is not None]
        return statistics.fmean(values) if values else float("nan")

    return Means(len(solved), mean("first_time_s"), mean("cost_ratio"), mean("optimal_time_s"),
                 mean("precompute_s"), mean("load_s"), mean("wall_s"), mean("peak_rss_mb"))


def _t(seconds: float) -> str:
    return f"{seconds:.4f}" if seconds < 1 else f"{seconds:.2f}"


def _triple(cell: PaperCell | None) -> str:
    return "-" if cell is None else f"{_t(cell[0])} / {cell[1]:.2f} / {_t(cell[2])}"


def select(rows: Iterable[Row], **fields: Any) -> list[Row]:
    """The rows whose fields equal ``fields``."""
    return [r for r in rows if all(r.get(k) == v for k, v in fields.items())]


def table2_case(rows: Sequence[Row]) -> tuple[str, str] | None:
    """The (scene, mission) of the per-setup table: the paper's Table II case when present, else the
    one run with the most setups."""
    if select(rows, scene=TABLE2_SCENE, mission=TABLE2_MISSION):
        return (TABLE2_SCENE, TABLE2_MISSION)
    setups: dict[tuple[str, str], set[str]] = {}
    for r in rows:
        setups.setdefault((r["scene"], r["mission"]), set()).add(r["setup"])
    return max(setups, key=lambda k: len(setups[k])) if setups else None


def table2(rows: Sequence[Row], scene: str, mission: str) -> str:
    """Per setup (paper order): n, first time / ratio / optimal time (ours and the paper's, the latter
    only for the paper's case), and our precompute, wall and memory means."""
    paper = TABLE2 if (scene, mission) == (TABLE2_SCENE, TABLE2_MISSION) else {}
    lines = [
        "| setup | n | 1st iter. time (s) | paper | 1st cost / opt. | paper | opt. time (s) | paper "
        "| precompute (s) | case wall (s) | peak RSS (MB) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    case_rows = select(rows, scene=scene, mission=mission)
    for setup in [s for s in PAPER_SETUPS if select(case_rows, setup=s)]:
        m = means(select(case_rows, setup=setup))
        p = paper.get(setup)
        ours = ("-",) * 3 if m is None else (_t(m.first_time_s), f"{m.cost_ratio:.4f}", _t(m.optimal_time_s))
        theirs = ("-",) * 3 if p is None else (f"{p[0]:.4f}", f"{p[1]:.4f}", f"{p[2]:.4f}")
        extra = (
            ("-",) * 3 if m is None else (f"{m.precompute_s:.2f}", f"{m.wall_s:.2f}", f"{m.peak_rss_mb:.0f}")
        )
        lines.append(
            f"| {setup} | {0 if m is None else m.n} | {ours[0]} | {theirs[0]} | {ours[1]} | {theirs[1]} "
            f"| {ours[2]} | {theirs[2]} | {' | '.join(extra)} |"
        )
    return "\n".join(lines)


def _scenes(rows: Sequence[Row]) -> list[str]:
    return list(dict.fromkeys(r["scene"] for r in rows))


def table3(rows: Sequence[Row], setups: Sequence[str] = TABLE3_SETUPS) -> str:
    """Setups x scenes; each cell ``1st time / ratio / opt. time`` (ours, then the paper's), means over
    the scene's missions x starts."""
    scenes = _scenes(rows)
    head = " | ".join(f"{s} (ours) | n | {s} (paper)" for s in scenes)
    lines = [f"| setup | {head} |", "|---" * (1 + 3 * len(scenes)) + "|"]
    for setup in [s for s in setups if select(rows, setup=s)]:
        cells = []
        for scene in scenes:
            m = means(select(rows, scene=scene, setup=setup))
            cells.append(f"{_triple(None if m is None else m.triple)} | {0 if m is None else m.n} "
                         f"| {_triple(TABLE3.get((scene, setup)))}")
        lines.append(f"| {setup} | {' | '.join(cells)} |")
    return "\n".join(lines)


def resources_table(rows: Sequence[Row], setups: Sequence[str] = TABLE3_SETUPS) -> str:
    """Per scene x setup: means of load, precompute, whole-case wall seconds and peak RSS (optimal rows)."""
    lines = [
        "| scene | setup | n | load (s) | precompute (s) | opt. search (s) | case wall (s) | peak RSS (MB) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for scene in _scenes(rows):
        for setup in [s for s in setups if select(rows, setup=s)]:
            m = means(select(rows, scene=scene, setup=setup))
            if m is not None:
                lines.append(f"| {scene} | {setup} | {m.n} | {m.load_s:.2f} | {m.precompute_s:.2f} "
                             f"| {_t(m.optimal_time_s)} | {m.wall_s:.2f} | {m.peak_rss_mb:.0f} |")
    return "\n".join(lines)


def excluded_table(rows: Sequence[Row]) -> str:
    """Every non-optimal row, grouped by (scene, mission, start, status, reason) with its setups."""
    groups: dict[tuple[Any, ...], list[str]] = {}
    order = {name: k for k, name in enumerate(PAPER_SETUPS)}
    for r in sorted(rows, key=lambda r: (mission_order(r["mission"]), r["start"], order.get(r["setup"], 99))):
        if r["status"] != "optimal":
            reason = (r.get("reason") or "").replace("|", "\\|").replace("\n", " ")
            groups.setdefault((r["scene"], r["mission"], r["start"], r["status"], reason), []).append(
                r["setup"]
            )
    if not groups:
        return "None: every case reached the optimum."
    lines = ["| scene | mission | start | status | setups | reason |", "|---|---|---|---|---|---|"]
    scenes = {name: k for k, name in enumerate(_scenes(rows))}
    for (scene, mission, start, status, reason), setups in sorted(
        groups.items(), key=lambda g: scenes[g[0][0]]
    ):
        lines.append(f"| {scene} | {mission} | {start} | {status} | {', '.join(setups)} | {reason} |")
    return "\n".join(lines)


def cost_disagreements(rows: Sequence[Row]) -> tuple[int, list[str]]:
    """Cross-check: every setup must find the same optimal cost for a (scene, mission, start, profile,
    time limit). Returns the number of such groups with two or more setups and a line per disagreement."""
    groups: dict[tuple[Any, ...], list[Row]] = {}
    for r in rows:
        if r["status"] == "optimal":
            key = (r["scene"], r["mission"], r["start"], r["profile"], r.get("time_limit_s"))
            groups.setdefault(key, []).append(r)
    compared = [g for g in groups.values() if len(g) > 1]
    bad = []
    for group in compared:
        costs = [float(r["cost_m"]) for r in group]
        if max(costs) - min(costs) > COST_TOLERANCE_M:
            r0 = group[0]
            detail = ", ".join(f"{r['setup']} {float(r['cost_m']):.6f}" for r in group)
            bad.append(f"{r0['scene']} mission {r0['mission']} start {r0['start']}: {detail}")
    return len(compared), bad
