"""Simplified waypoints on every Gibson case: how many, how long their segments, and each one re-checked.

Plans every shipped mission folder of the three scenes from each of its scene's start positions (one
:class:`sgplan.Session` per scene, setup and profile as given), then per path: its cells and length,
the simplified waypoints of each variant, waypoints per metre, the shortest segment, the segments one
cell long (< 2 cm), the compiled simplification's seconds (warm: compiled and cached before), and the
problems :func:`tests.polyline_oracle.check_polyline` finds (an independent brute-force check of every
segment's cells, the automaton along it and the whole polyline; 0 everywhere is the guarantee).

Variants: ``after`` (this tree, exact line of sight, tolerance 0), ``after+tol`` (``--tolerance M``, default
0.01 m, one cell) and, with ``--before SRC``, the simplification of an older source tree, run in a child
process on the same paths (its ``simplify_path(path, grid, labels, automaton)`` reads ``grid.traversable``
and ``automaton.table``):

    git archive 864cc9c src | tar -x -C /tmp/sgplan-before
    .venv/bin/python benchmarks/waypoints.py --before /tmp/sgplan-before/src \\
        --out benchmarks/results/waypoints.md

Needs the Gibson data.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

SCENES = ("Allensville", "Benevolence", "Collierville")
ONE_CELL_M = 0.02


def plan_cases(setup: str, profile: str) -> list[dict]:
    """Every (scene, mission folder, start) planned; the path and what simplifying it needs."""
    import sgplan
    from sgplan.datasets import scene_dir
    from sgplan.errors import SgplanError

    cases = []
    for scene in SCENES:
        folder = scene_dir(scene)
        session = sgplan.Session(folder)
        missions = sorted((p for p in (folder / "missions").iterdir() if p.is_dir()), key=lambda p: p.name)
        for mission_dir in missions:
            mission = sgplan.load_mission(mission_dir, profile=profile)
            for start in range(len(session.building.initial_cells)):
                case = {"scene": scene, "mission": mission_dir.name, "start": start}
                try:
                    result = session.plan(mission, start, setup=setup, profile=profile)
                except SgplanError as error:
                    cases.append(case | {"status": getattr(error, "status", "error")})
                    continue
                cases.append(case | {"status": result.status, "result": result})
                print(f"planned {scene} {mission_dir.name} start {start}: {len(result.path)} cells",
                      file=sys.stderr)
    return cases


def segment_stats(path: np.ndarray, keep: np.ndarray, grid) -> dict:
    from sgplan.outputs.waypoints import leg_costs

    legs = leg_costs(path[keep], grid)
    same_floor = np.diff(path[keep, 2]) == 0
    flat = legs[same_floor]
    # A segment that ends where the automaton moves on, or starts there, is forced by the mission (a room
    # entered by one cell and left again); the others follow the obstacles' shape.
    changes = set((np.flatnonzero(np.diff(path[:, 3])) + 1).tolist())
    short = np.flatnonzero(same_floor & (legs < ONE_CELL_M))
    at_event = sum(1 for k in short if int(keep[k]) in changes or int(keep[k + 1]) in changes)
    return {"waypoints": len(keep), "shortest_m": float(flat.min()) if len(flat) else None,
            "one_cell": len(short), "one_cell_at_event": at_event}


def run_before(src: Path, cases: list[dict]) -> list[list[int]]:
    """The kept rows of each solved case by the older tree at ``src`` (a child process)."""
    with tempfile.TemporaryDirectory() as tmp:
        for k, case in enumerate(cases):
            r = case["result"]
            np.savez(Path(tmp) / f"{k}.npz", path=r.path, traversable=r.grid.traversable, labels=r.labels,
                     table=np.asarray(r.mission.automaton.table))
        env = dict(os.environ, PYTHONPATH=str(src))
        out = subprocess.run([sys.executable, __file__, "--child", tmp, str(len(cases))], env=env, cwd=tmp,
                             capture_output=True, text=True, check=True)
        return json.loads(out.stdout)


def child(folder: str, count: int) -> None:
    from sgplan.outputs.waypoints import simplify_path

    kept = []
    for k in range(count):
        data = np.load(Path(folder) / f"{k}.npz")
        grid = SimpleNamespace(traversable=data["traversable"])
        automaton = SimpleNamespace(table=data["table"])
        kept.append(simplify_path(data["path"], grid, data["labels"], automaton).tolist())
    print(json.dumps(kept))


def measure(cases: list[dict], tolerance_m: float, before: list[list[int]] | None) -> list[dict]:
    from sgplan.outputs.waypoints import leg_costs, simplify_path
    from tests.polyline_oracle import check_polyline

    rows = []
    for k, case in enumerate(cases):
        r = case["result"]
        automaton = r.mission.automaton
        row = {key: case[key] for key in ("scene", "mission", "start")}
        row |= {"cells": len(r.path), "length_m": float(leg_costs(r.path, r.grid).sum())}
        variants = {"after": 0.0, "after+tol": tolerance_m}
        for name, tol in variants.items():
            t0 = time.perf_counter()
            keep = simplify_path(r.path, r.grid, r.labels, automaton, tolerance_m=tol, building=r.building)
            seconds = time.perf_counter() - t0
            problems = check_polyline(r.path, keep, r.grid, r.labels, automaton, r.profile, tolerance_m=tol,
                                      building=r.building)
            row[name] = segment_stats(r.path, keep, r.grid) | {"seconds": seconds, "problems": len(problems)}
        if before is not None:
            keep = np.array(before[k])
            problems = check_polyline(r.path, keep, r.grid, r.labels, automaton, r.profile)
            row["before"] = segment_stats(r.path, keep, r.grid) | {"problems": len(problems)}
        rows.append(row)
    return rows


def markdown(rows: list[dict], skipped: list[dict], args: argparse.Namespace, command: str) -> str:
    names = (["before"] if args.before else []) + ["after", "after+tol"]
    lines = [
        "# Simplified waypoints on every Gibson case", "",
        f"`{command}`", "",
        f"Setup {args.setup}, profile {args.profile}; every shipped mission folder x every start of its "
        f"scene ({len(rows)} paths; {len(skipped)} cases without a path: "
        + ", ".join(f"{c['scene']} {c['mission']} s{c['start']} ({c['status']})" for c in skipped) + ").",
        f"`before`: the older tree's simplification; `after`: exact line of sight; `after+tol`: with a "
        f"{args.tolerance:g} m waypoint tolerance. One-cell segments: same-floor segments under "
        f"{ONE_CELL_M * 100:g} cm; \"at an event\": those that start or end where the automaton moves on "
        "(a room entered by one cell and left again: forced by the mission). Problems: what the independent "
        "checker (tests/polyline_oracle.py) finds over every segment.", "",
        "## Totals", "",
        "| variant | waypoints | per metre | one-cell segments | of them at an event | shortest segment (m) "
        "| problems |",
        "|---|---|---|---|---|---|---|",
    ]
    length = sum(r["length_m"] for r in rows)
    for name in names:
        total = sum(r[name]["waypoints"] for r in rows)
        shortest = min(r[name]["shortest_m"] for r in rows if r[name]["shortest_m"] is not None)
        one_cell = sum(r[name]["one_cell"] for r in rows)
        at_event = sum(r[name]["one_cell_at_event"] for r in rows)
        problems = sum(r[name]["problems"] for r in rows)
        lines.append(f"| {name} | {total} | {total / length:.2f} | {one_cell} | {at_event} | {shortest:.3f} "
                     f"| {problems} |")
    seconds = [r["after"]["seconds"] for r in rows]
    lines += ["", f"Paths: {sum(r['cells'] for r in rows)} cells, {length:.1f} m. Simplification (`after`, "
              f"warm): median {statistics.median(seconds) * 1e3:.2f} ms, worst {max(seconds) * 1e3:.2f} ms "
              "per path.", "", "## Per case", "",
              "| case | cells | m | " + " | ".join(f"{n}: wp / per m / shortest / 1-cell" for n in names)
              + " |",
              "|---|---|---|" + "---|" * len(names)]
    for r in rows:
        cells = [f"{r[n]['waypoints']} / {r[n]['waypoints'] / r['length_m']:.2f} / "
                 f"{r[n]['shortest_m'] if r[n]['shortest_m'] is None else round(r[n]['shortest_m'], 3)} / "
                 f"{r[n]['one_cell']}" for n in names]
        lines.append(f"| {r['scene']} {r['mission']} s{r['start']} | {r['cells']} | {r['length_m']:.2f} | "
                     + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main() -> None:
    if len(sys.argv) == 4 and sys.argv[1] == "--child":
        child(sys.argv[2], int(sys.argv[3]))
        return
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--setup", default="ALL")
    parser.add_argument("--profile", default="ltlf")
    parser.add_argument("--tolerance", type=float, default=0.01, help="metres, for the after+tol variant")
    parser.add_argument("--before", type=Path, help="an older tree's src folder, simplified in a child")
    parser.add_argument("--out", type=Path, help="write the markdown here (else stdout)")
    args = parser.parse_args()
    command = "python benchmarks/waypoints.py " + " ".join(sys.argv[1:])
    cases = plan_cases(args.setup, args.profile)
    solved = [c for c in cases if "result" in c]
    skipped = [c for c in cases if "result" not in c]
    before = run_before(args.before, solved) if args.before else None
    rows = measure(solved[:1], args.tolerance, None if before is None else before[:1])  # compile, warm
    rows = measure(solved, args.tolerance, before)
    text = markdown(rows, skipped, args, command)
    if args.out:
        args.out.write_text(text, encoding="utf-8")
    else:
        print(text)


if __name__ == "__main__":
    main()
