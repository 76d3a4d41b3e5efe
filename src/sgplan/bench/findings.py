"""The sentences of the benchmark report that state findings, each computed from the rows of that run:
what is timed and what the workers reused, how our numbers compare with the paper's, and where paths
planned under the ``authors`` profile break the mission as written. Nothing here is prose fixed in
advance about numbers, so the report cannot go stale.
"""

from __future__ import annotations

import statistics
from collections.abc import Callable, Sequence
from typing import Any

from sgplan.bench.cases import TABLE2_MISSION, TABLE2_SCENE, TABLE3_SETUPS, mission_order
from sgplan.bench.paper import TABLE2, TABLE3
from sgplan.bench.tables import Means, means, select
from sgplan.english import count

Row = dict[str, Any]


def timing_section(rows: Sequence[Row]) -> list[str]:
    """What the times measure, what they leave out, and what the long-lived workers reused."""
    text = [
        "## What is timed",
        "",
        "- *1st iter. time* and *opt. time* are AMRA* search seconds, as in the paper: from the start of the "
        "search to the first path and to the optimum. The search runs compiled (numba kernels, compiled "
        "once per machine, kept in numba's disk cache and loaded before the search clock starts).",
        "- Not in them, as in the paper: *load* (the scene and mission, the occupancy grid and labels) and "
        "*precompute* (the planning domain, all of it built before the search clock starts: the cell graph, "
        "the h_LTL distance fields, the LLM heuristic's tables, the composite-action maps of the object, "
        "room and floor levels, and loading the search kernels).",
        "- *case wall* is the parent's clock for the whole case: request to answer for a long-lived worker, "
        "the whole process (interpreter start and imports included) with `--fresh-workers`.",
    ]
    known = [r for r in rows if r.get("scene_reused") is not None and r["status"] == "optimal"]
    warm = [r for r in known if r["scene_reused"]]
    cold = [r for r in known if not r["scene_reused"]]
    if warm:
        def mean_precompute(group: Sequence[Row]) -> str:
            values = [float(r["precompute_s"]) for r in group if r.get("precompute_s") is not None]
            return f"{statistics.fmean(values):.2f} s" if values else "-"

        text.append(
            f"- Reuse: {count(len(warm), 'case')} of the {len(known)} optimal ones ran in a worker that had "
            "loaded their scene for an earlier case and kept it (building, grids, label masks, "
            "composite-action maps, h_LTL distance fields); their *precompute* is only what they added "
            f"(mean {mean_precompute(warm)}, against {mean_precompute(cold)} for the "
            f"{count(len(cold), 'case')} that loaded their scene). `--fresh-workers` runs every case cold."
        )
    elif known:
        cases = count(len(known), "optimal case")
        text.append(f"- Reuse: none; each of the {cases} loaded its scene itself.")
    return [*text, ""]


def _times(ratio: float) -> str:
    """``x3.1``, ``x47.5``, ``x229``, ``x2,740``."""
    return f"x{ratio:,.0f}" if ratio >= 100 else f"x{ratio:.3g}"


def _ratio_range(pairs: Sequence[tuple[float, float]]) -> str:
    """``x3.1 to x820 (median x240)`` of paper / ours over (ours, paper) pairs."""
    ratios = sorted(paper / ours for ours, paper in pairs if ours > 0)
    if not ratios:
        return "not comparable (no time above 0)"
    return f"{_times(ratios[0])} to {_times(ratios[-1])} (median {_times(statistics.median(ratios))})"


def _winners(table: dict[str, dict[str, tuple[float, float, float]]], index: int, best: Callable[..., Any]
             ) -> str:
    """Per scene, the setup with the lowest (``best=min``) or highest value of the triple's ``index``."""
    return "; ".join(f"{scene}: {best(cells, key=lambda s: cells[s][index])}"
                     for scene, cells in table.items() if cells)


def comparison_section(rows: Sequence[Row], case: tuple[str, str] | None) -> list[str]:
    """Our means against the paper's, in numbers of this run: how much shorter the search is, and which
    setup is fastest or has the worst first path, per scene, in both."""
    ours: dict[str, dict[str, tuple[float, float, float]]] = {}
    paper: dict[str, dict[str, tuple[float, float, float]]] = {}
    pairs: list[tuple[Means, tuple[float, float, float]]] = []
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for setup in TABLE3_SETUPS:
            m, p = means(select(rows, scene=scene, setup=setup)), TABLE3.get((scene, setup))
            if m is not None and p is not None:
                ours.setdefault(scene, {})[setup], paper.setdefault(scene, {})[setup] = m.triple, p
                pairs.append((m, p))
    if not pairs:
        return ["## Reading the comparison with the paper", "",
                "No case of this run has a counterpart in the paper's Table III.", ""]
    text = [
        "## Reading the comparison with the paper", "",
        "Computed from this run's Table III (means over missions x starts, optimal cases only; the paper's "
        "numbers come from the authors' C++ on their machine, ours from sgplan's compiled search on this "
        "one, precomputation left out of both):", "",
        "- Search to the optimum, the paper's time over ours: "
        f"{_ratio_range([(m.optimal_time_s, p[2]) for m, p in pairs])} over "
        f"{count(len(pairs), '(scene, setup) cell')}; to the first path: "
        f"{_ratio_range([(m.first_time_s, p[0]) for m, p in pairs])}.",
        f"- Fastest first path per scene, ours: {_winners(ours, 0, min)}. The paper's: "
        f"{_winners(paper, 0, min)}.",
        f"- Fastest to the optimum per scene, ours: {_winners(ours, 2, min)}. The paper's: "
        f"{_winners(paper, 2, min)}.",
        f"- Worst first path (highest 1st cost ÷ opt.) per scene, ours: {_winners(ours, 1, max)}. The "
        f"paper's: {_winners(paper, 1, max)}.",
    ]
    if case == (TABLE2_SCENE, TABLE2_MISSION):
        case_rows = select(rows, scene=case[0], mission=case[1])
        table2 = [(m, TABLE2[s]) for s in TABLE2 if (m := means(select(case_rows, setup=s))) is not None]
        if table2:
            text.append(f"- Table II ({case[0]} mission {case[1]}, {count(len(table2), 'setup')}): the "
                        "paper's time to the optimum over ours "
                        f"{_ratio_range([(m.optimal_time_s, p[2]) for m, p in table2])}.")
    return [*text, ""]


SHOWN_VIOLATIONS = 3
"""Places named per path in the report (the first ones along it; the rest are counted)."""


def _violation_text(violations: Sequence[dict[str, Any]]) -> str:
    parts = []
    for v in violations[:SHOWN_VIOLATIONS]:
        row, col, floor = v["cell"]
        where = f"at ({row}, {col}) on floor {floor}, {v['cost_m']:.2f} m along the path"
        places = " and ".join(v["places"]) or "a cell in none of the mission's places"
        if v["reason"] == "start-label":
            parts.append(f"starts in {places} ({where}), which the mission does not allow as its first step; "
                         "`authors` does not read the start cell's label")
        else:
            again = v.get("times", 1) - 1
            more = (" (and once more)" if again == 1 else f" (and {again} times more)") if again else ""
            parts.append(f"enters {places} {where}{more}: the automaton has no edge for that from state "
                         f"{v['state']}, which `authors` reads as staying in it")
    hidden = len(violations) - SHOWN_VIOLATIONS
    if hidden > 0:
        parts.append(f"and {hidden} more (`ltlf_violations` in results.json)")
    return "; ".join(parts)


def semantics_section(rows: Sequence[Row]) -> list[str]:
    """Under ``authors``: which paths break the mission as written (read again under ``ltlf``), where and
    why; under ``ltlf``: that there is nothing to re-read."""
    title = ["## Paths and the mission as written", ""]
    if all(r["profile"] != "authors" for r in rows):
        return [*title, "Profile `ltlf`: every path reads the start cell's label and takes only the "
                "automaton's edges (a missing edge rejects), so each satisfies the mission as written.", ""]
    paths = [r for r in rows if r["profile"] == "authors" and r.get("path_cells") is not None]
    checked = [r for r in paths if r.get("ltlf_accepts") is not None]
    broken = [r for r in checked if not r["ltlf_accepts"]]
    text = [
        *title,
        "Profile `authors` reproduces the authors' C++: a label with no automaton edge keeps the state and "
        "the start cell's label is not read (docs/semantics.md), so a path may cross a place that the "
        "mission's \"always avoid\" forbids. Each path was read again under `ltlf` (a missing edge rejects, "
        f"the start is read): {len(checked) - len(broken)} of the {count(len(checked), 'path')} satisfy "
        f"the mission as written, {len(broken)} do not.",
    ]
    if len(checked) < len(paths):
        text.append(f"{count(len(paths) - len(checked), 'path')} could not be checked (rows recorded by an "
                    "older sgplan: run them again to check them).")
    groups: dict[tuple[Any, ...], list[str]] = {}
    for r in sorted(broken, key=lambda r: (r["scene"], mission_order(r["mission"]), r["start"])):
        key = (r["scene"], r["mission"], r["start"], _violation_text(r.get("ltlf_violations") or []))
        groups.setdefault(key, []).append(r["setup"])
    if groups:
        text += ["", "| scene | mission | start | setups | where and why |", "|---|---|---|---|---|"]
        ending = "it ends in a state that does not accept"
        text += [f"| {scene} | {mission} | {start} | {', '.join(setups)} | {why or ending} |"
                 for (scene, mission, start, why), setups in groups.items()]
    return [*text, ""]
