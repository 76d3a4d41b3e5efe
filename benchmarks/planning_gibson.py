"""Planner benchmark on the shipped Gibson missions (authors profile), one subprocess per case.

Prints per case: first-path search time, first cost / optimal cost, search time to the optimum,
expansions, load and precompute seconds, whole-process wall seconds and peak RSS (the child's own
``VmHWM``; not ``ru_maxrss``, which Linux carries over an exec from the parent's address space, so a child
started by a parent holding a loaded scene reported the parent's peak), next to the authors' C++
numbers measured on this kind of machine where they exist.

    .venv/bin/python benchmarks/planning_gibson.py                 # the four reference cases
    .venv/bin/python benchmarks/planning_gibson.py --all           # 3 scenes x 5 missions x 5 starts
    .venv/bin/python benchmarks/planning_gibson.py --all --setups ALL NO-LLM A*

With ``--all`` the optimal costs are also compared with the authors' planner's recorded optima.
Needs the Gibson data (see sgplan.datasets).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.append(str(REPO))  # after PYTHONPATH: a variant's own tests/ (planning_vs_dijkstra.py) come first

# (scene, mission, start, setup) -> authors' C++: search s to optimum, whole-process wall s, peak RSS GB.
REFERENCE = {
    ("Allensville", 1, 0, "ALL"): (8.3, 53.0, 4.8),
    ("Benevolence", 1, 0, "ALL"): (8.3, 69.0, 13.9),
    ("Benevolence", 4, 0, "ALL"): (51.5, 137.0, 14.5),
    ("Collierville", 1, 0, "ALL"): (28.7, 91.0, 16.6),
}


def run_one(scene: str, mission: int, start: int, setup: str, profile: str) -> dict:
    """Plan one case in this process; returns the measurements (wall is measured by the parent)."""
    t0 = time.perf_counter()
    from sgplan.datasets import find_gibson_root
    from sgplan.errors import PlanningError
    from sgplan.planning import plan
    from tests.planning.gibson_cases import load_case

    root = find_gibson_root()
    problem = load_case(root, scene, mission, start, profile)
    load_s = time.perf_counter() - t0
    row: dict = {"scene": scene, "mission": mission, "start": start, "setup": setup, "load_s": load_s}
    try:
        result = plan(problem, setup)
    except PlanningError as error:
        row.update(status=error.status, message=str(error))
    else:
        first, last = result.iterations[0], result.iterations[-1]
        row.update(
            status=result.status, first_s=first.time_s, first_cost=first.cost_m, cost=result.cost_m,
            opt_s=last.time_s, expansions=result.expansions, precompute_s=result.precompute_s,
        )
    # VmHWM of this process's own address space (the worker's reader; present in older trees too)
    from sgplan.bench.worker import _peak_rss_mb

    row["rss_mb"] = _peak_rss_mb()
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--all", action="store_true", help="every mission and start of the three scenes")
    parser.add_argument("--setups", nargs="+", default=["ALL"])
    parser.add_argument("--profile", default="authors")
    parser.add_argument(
        "--one", nargs=4, metavar=("SCENE", "MISSION", "START", "SETUP"), help=argparse.SUPPRESS
    )
    args = parser.parse_args()
    if args.one:
        scene, mission, start, setup = args.one
        print(json.dumps(run_one(scene, int(mission), int(start), setup, args.profile)))
        return

    from tests.planning.gibson_cases import STAY_COSTS

    if args.all:
        cases = [(s, m, k, setup) for s in ("Allensville", "Benevolence", "Collierville") for m in range(1, 6)
                 for k in range(5) for setup in args.setups]
    else:
        cases = list(REFERENCE)
    header = (f"{'case':<26} {'status':<13} {'1st s':>8} {'1st/opt':>7} {'opt cost':>9} {'opt s':>7} "
              f"{'expansions':>10} {'load s':>6} {'pre s':>6} {'wall s':>6} {'RSS MB':>7}  reference / check")
    print(header)
    for scene, mission, start, setup in cases:
        t0 = time.perf_counter()
        out = subprocess.run(
            [
                sys.executable,
                __file__,
                "--profile",
                args.profile,
                "--one",
                scene,
                str(mission),
                str(start),
                setup,
            ],
            capture_output=True,
            text=True,
            cwd=REPO,
        )
        wall = time.perf_counter() - t0
        if out.returncode != 0:
            print(f"{scene} {mission} {start} {setup}: failed\n{out.stderr[-2000:]}")
            continue
        row = json.loads(out.stdout.strip().splitlines()[-1])
        name = f"{scene} m{mission} s{start} {setup}"
        note = ""
        if (scene, mission, start, setup) in REFERENCE:
            opt_ref, wall_ref, rss_ref = REFERENCE[(scene, mission, start, setup)]
            note = f"C++ {opt_ref} s / {wall_ref} s / {rss_ref} GB"
        expected = STAY_COSTS.get((scene, mission), (None,) * 5)[start] if args.profile == "authors" else None
        if "cost" in row:
            if (scene, mission) in STAY_COSTS:
                same = expected is not None and abs(round(row['cost'], 4) - expected) < 1e-4
                note += f" {'ok' if same else 'MISMATCH'}"
            print(
                f"{name:<26} {row['status']:<13} {row['first_s']:>8.4f} "
                f"{row['first_cost'] / row['cost']:>7.4f} "
                f"{row['cost']:>9.4f} {row['opt_s']:>7.3f} {row['expansions']:>10} {row['load_s']:>6.2f} "
                f"{row['precompute_s']:>6.2f} {wall:>6.2f} {row['rss_mb']:>7.0f}  {note}",
                flush=True,
            )
        else:
            if (scene, mission) in STAY_COSTS:
                note += f" {'ok' if expected is None else 'MISMATCH'}"
            print(
                f"{name:<26} {row['status']:<13} {'':>8} {'':>7} {'':>9} {'':>7} {'':>10} "
                f"{row['load_s']:>6.2f} "
                f"{'':>6} {wall:>6.2f} {row['rss_mb']:>7.0f}  {note}",
                flush=True,
            )


if __name__ == "__main__":
    main()
