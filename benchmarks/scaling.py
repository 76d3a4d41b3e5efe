"""Growth of sgplan with building size: synthetic buildings, one subprocess per case.

For each size (cell edge and rooms per floor set the grid size; ``--floors`` the floors) and each mission
(k goals, sequenced ``F(g1 & F(g2 & ...))`` or unordered ``F g1 & ... & F gk``, goals = reach distinct
objects), a child process generates the building (:func:`sgplan.scene.synthetic.generate_building`; timed
apart, it stands for loading a scene and is not planning), builds the grid, the labels, the planning
domain, and plans (``--setup``, NO-LLM by default: synthetic missions carry no LLM guidance). Composite
action maps are built lazily inside the search (``prebuild_actions=False``); ``--prebuild`` builds them all
first, as ``sgplan plan`` does today. Per part it prints seconds and the peak RSS reached by the end of
that part (MB), the domain's own parts (cell graph, reachability, h_LTL distance fields, action tables),
grid and free cells, automaton states and expansions; then least-squares growth exponents
(part ~ free_cells^b) per floors / goals / order over the sizes that finished.

    .venv/bin/python benchmarks/scaling.py --sizes 0.25 1 4 --floors 1 2 --goals 2 5
    .venv/bin/python benchmarks/scaling.py --target 16M        # 2 floors, 16M grid cells, 2 goals
    .venv/bin/python benchmarks/scaling.py --target 9goals     # 9 unordered goals, ~1.2M free cells
    .venv/bin/python benchmarks/scaling.py --target 16M --variant before=/tmp/old/src --variant after=src

``--variant NAME=SRC`` runs every case once per source tree (``PYTHONPATH=SRC``), back to back, so that
ratios come from one run on a shared machine. ``--max-rss-gb`` kills a child whose RSS passes the limit
(default 8 GB: the machine is shared). ``plan_s`` is the child's wall time minus the building generation:
the whole process as a CLI call on a loaded scene would pay it (interpreter, imports, numba cache load,
grid, labels, domain, search, exit).
"""

from __future__ import annotations

import time

T_START = time.perf_counter()

import argparse
import inspect
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]

TARGETS = {
    # name: (sizes in M grid cells, floors, goals, orders)
    "16M": ([16.0], [2], [2], ["sequenced", "unordered"]),
    "9goals": ([2.0], [1], [9], ["unordered"]),
}
"""The issue-12 target cases: a 2-floor building of 16M grid cells (~9.6M free), and 9 unordered goals on
a grid of ~1.2M free cells (Gibson-sized)."""


def _building(target_cells: float, floors: int, rooms: int, seed: int):
    """A synthetic building whose grid has about ``target_cells`` cells over all floors."""
    from sgplan.scene.synthetic import generate_building

    probe = generate_building(num_floors=floors, rooms_per_floor=rooms, num_objects=0, cell_m=0.05, seed=seed)
    rows, cols = probe.floors[0].shape
    cell_m = 0.05 * math.sqrt(rows * cols * floors / target_cells)  # area per floor is fixed in metres
    return generate_building(num_floors=floors, rooms_per_floor=rooms, num_objects=3 * rooms * floors,
                             cell_m=cell_m, seed=seed)


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def run_case(
    target_m: float, floors: int, goals: int, order: str, setup: str, seed: int, prebuild: bool
) -> dict:
    """One case in this process; returns seconds and peak RSS per part, and sizes."""
    import numpy as np

    from sgplan import mission_from_formula  # the public one: any source tree has it
    try:
        from sgplan.assembly import make_problem
        from sgplan.radii import resolve_radii
    except ImportError:  # a source tree from before the layout round
        from sgplan.pipeline import make_problem, resolve_radii  # type: ignore[no-redef]
    from sgplan.planning import get_setup, plan
    from sgplan.scene.grid import build_occupancy_grid

    row: dict = {"target_m": target_m, "floors": floors, "goals": goals, "order": order}
    row["import_s"] = time.perf_counter() - T_START
    row["import_mb"] = _peak_mb()

    def part(name: str, t0: float) -> None:
        row[f"{name}_s"] = time.perf_counter() - t0
        row[f"{name}_mb"] = _peak_mb()
        print("PARTIAL " + json.dumps(row), flush=True)  # what finished, should the case be killed later

    t0 = time.perf_counter()
    building = _building(target_m * 1e6, floors, rooms=max(4, goals), seed=seed)
    part("building", t0)
    objects = list(building.objects())
    picks = [objects[i].key for i in np.random.default_rng(seed).choice(len(objects), goals, replace=False)]
    atoms = [f'"reach({key})"' for key in picks]
    if order == "sequenced":
        formula = atoms[-1]
        for atom in reversed(atoms[:-1]):
            formula = f"F({atom} & F {formula})" if formula == atoms[-1] else f"F({atom} & {formula})"
    else:
        formula = " & ".join(f"F {atom}" for atom in atoms)
    t0 = time.perf_counter()
    mission = mission_from_formula(formula)
    part("automaton", t0)
    radii = resolve_radii(building)
    t0 = time.perf_counter()
    grid = build_occupancy_grid(building, radii.robot_m)
    part("grid", t0)
    t0 = time.perf_counter()
    labels = mission.labels(building, radii.reach_m)
    part("labels", t0)
    problem = make_problem(building, mission, (0, 0, 0), grid=grid, labels=labels).problem
    # Start at the free cell nearest the middle of floor 0 (the domain, built later, checks it).
    free = np.argwhere(problem.grid.traversable[0])
    centre = free[np.argmin(((free - free.mean(axis=0)) ** 2).sum(axis=1))]
    problem.start = (int(centre[0]), int(centre[1]), 0)
    row["grid_cells"] = int(np.prod(problem.grid.shape))
    row["free_cells"] = int(problem.grid.traversable.sum())
    row["states"] = int(problem.automaton.num_states)
    del free
    t0 = time.perf_counter()
    # The domain for the setup's levels, as the planner builds it (older source trees: the full one).
    max_level = get_setup(setup).max_level
    domain = _domain_of(problem, max_level)
    part("domain", t0)
    for name, seconds in getattr(domain, "timings", {}).items():
        row[f"dom_{name}_s"] = seconds
    before = domain.precompute_s
    # A one-off plan frees its maps' distances once the search stops reading them, as `sgplan plan` does
    # (older source trees have no such option).
    release = {"release_maps": True} if "release_maps" in inspect.signature(plan).parameters else {}
    result = plan(problem, setup, prebuild_actions=prebuild, **release)
    # Composite action maps built before the search (--prebuild only) and the kernel load.
    row["actions_s"] = result.precompute_s - before
    row["search_s"] = result.search_s
    row["search_mb"] = _peak_mb()
    row["cost"] = result.cost_m
    row["expansions"] = result.expansions
    row["status"] = result.status
    row["rss_mb"] = _peak_mb()
    return row


def fit_exponent(xs: list[float], ys: list[float]) -> float:
    """Least-squares slope of log y against log x (nan with fewer than 2 usable points)."""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    den = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / den if den else float("nan")


TIME_PARTS = ("import_s", "building_s", "grid_s", "labels_s", "domain_s", "actions_s", "search_s", "plan_s")
"""Seconds per part; ``plan_s`` = whole child process minus the building generation."""
MB_PARTS = ("import_mb", "building_mb", "grid_mb", "labels_mb", "domain_mb", "search_mb")
"""Peak RSS (MB) reached by the end of each part; the last one is the process's peak."""


def _run_child(cmd: list[str], env: dict, timeout: float, max_rss_gb: float) -> tuple[str, str, float]:
    """Run ``cmd``; returns (outcome, final JSON row or message, wall seconds). Kills it past the time or
    RSS limit (RSS polled every 50 ms from /proc), then reports the parts it finished."""
    t0 = time.perf_counter()
    # Output goes to a file: a child killed for time or memory still reports the parts it finished.
    with tempfile.TemporaryFile("w+") as sink:
        proc = subprocess.Popen(cmd, stdout=sink, stderr=subprocess.DEVNULL, text=True, cwd=REPO, env=env)
        status_path = Path(f"/proc/{proc.pid}/status")
        worst = 0.0
        killed = ""
        while proc.poll() is None:
            try:
                for line in status_path.read_text().splitlines():
                    if line.startswith("VmRSS:"):
                        worst = max(worst, int(line.split()[1]) / 1024**2)
            except OSError:
                pass
            if worst > max_rss_gb or time.perf_counter() - t0 > timeout:
                proc.kill()
                proc.wait()
                killed = f"RSS {worst:.1f} GB > {max_rss_gb:g} GB" if worst > max_rss_gb else f"{timeout:g} s"
                break
            time.sleep(0.05)
        wall = time.perf_counter() - t0
        sink.seek(0)
        out = sink.read()
    if killed:
        partial = [line for line in out.splitlines() if line.startswith("PARTIAL ")]
        done = ""
        if partial:
            row = json.loads(partial[-1][len("PARTIAL "):])
            done = "; finished: " + ", ".join(
                f"{k[:-2]} {v:.2f} s" for k, v in row.items() if k.endswith("_s") and k != "plan_s"
            ) + f" (peak {max(v for k, v in row.items() if k.endswith('_mb')):.0f} MB)"
        return "killed", f"killed at {killed} after {wall:.0f} s{done}", 0.0
    final = [line for line in out.splitlines() if line.startswith("{")]
    if proc.returncode != 0 or not final:
        return "failed", f"exit code {proc.returncode}", wall
    return "ok", final[-1], wall


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--sizes", nargs="+", type=float, default=[0.25, 1.0, 4.0], help="millions of grid cells"
    )
    parser.add_argument("--floors", nargs="+", type=int, default=[1, 2])
    parser.add_argument("--goals", nargs="+", type=int, default=[2, 5])
    parser.add_argument("--orders", nargs="+", default=["sequenced", "unordered"])
    parser.add_argument("--target", choices=sorted(TARGETS), help="run an issue-12 target case instead")
    parser.add_argument("--setup", default="NO-LLM")
    parser.add_argument("--prebuild", action="store_true", help="build every action map before the search")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per case")
    parser.add_argument("--max-rss-gb", type=float, default=8.0, help="kill a case past this RSS")
    parser.add_argument(
        "--variant", action="append", metavar="NAME=SRC", help="a source tree to time (repeatable)"
    )
    parser.add_argument("--json", type=Path, help="also write every row here")
    parser.add_argument(
        "--one", nargs=4, metavar=("SIZE", "FLOORS", "GOALS", "ORDER"), help=argparse.SUPPRESS
    )
    args = parser.parse_args()
    if args.one:
        size, floors, goals, order = args.one
        row = run_case(float(size), int(floors), int(goals), order, args.setup, args.seed, args.prebuild)
        print(json.dumps(row))
        return 0
    if args.target:
        args.sizes, args.floors, args.goals, args.orders = TARGETS[args.target]
    variants = [v.split("=", 1) for v in args.variant] if args.variant else [["current", ""]]

    head = (
        f"{'variant':>8} {'size M':>6} {'fl':>2} {'goals':>9} {'grid':>9} {'free':>9} {'Q':>4} "
        + " ".join(f"{p[:-2]:>8}" for p in TIME_PARTS)
        + " | MB: "
        + " ".join(f"{p[:-3]:>8}" for p in MB_PARTS)
        + f" {'expans':>9}"
    )
    print(f"seconds per part | peak RSS (MB) by the end of each part; setup {args.setup}, "
          f"action maps {'prebuilt' if args.prebuild else 'lazy'}")
    print(head, flush=True)
    rows = []
    for floors in args.floors:
        for goals in args.goals:
            for order in args.orders:
                for size in args.sizes:
                    for name, src in variants:
                        cmd = [sys.executable, __file__, "--setup", args.setup, "--seed", str(args.seed),
                               "--one", str(size), str(floors), str(goals), order]
                        cmd += ["--prebuild"] if args.prebuild else []
                        env = dict(os.environ)
                        if src:
                            env["PYTHONPATH"] = str(Path(src).resolve())
                        label = f"{name[:8]:>8} {size:>6} {floors:>2} {goals:>2} {order[:6]:>6}"
                        outcome, out, wall = _run_child(cmd, env, args.timeout, args.max_rss_gb)
                        if outcome != "ok":
                            print(f"{label} {outcome}: {out}", flush=True)
                            continue
                        row = json.loads(out)
                        row["variant"] = name
                        row["wall_s"] = wall
                        row["plan_s"] = wall - row["building_s"]
                        rows.append(row)
                        print(
                            f"{label} {row['grid_cells']:>9} {row['free_cells']:>9} {row['states']:>4} "
                            + " ".join(f"{row.get(p, float('nan')):>8.2f}" for p in TIME_PARTS)
                            + " |     "
                            + " ".join(f"{row.get(p, float('nan')):>8.0f}" for p in MB_PARTS)
                            + f" {row['expansions']:>9}",
                            flush=True,
                        )
                        dom = {k[4:-2]: v for k, v in row.items() if k.startswith("dom_")}
                        if dom:
                            print(" " * 9 + "domain: " + ", ".join(f"{k} {v:.2f} s" for k, v in dom.items()))
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))
    print(
        "\ngrowth exponents b in (part ~ free_cells^b), per variant / floors / goals / order, "
        "over the sizes that finished"
    )
    for name, _ in variants:
        for floors in args.floors:
            for goals in args.goals:
                for order in args.orders:
                    key = (name, floors, goals, order)
                    mine = [r for r in rows if (r["variant"], r["floors"], r["goals"], r["order"]) == key]
                    if len(mine) < 2:
                        continue
                    xs = [r["free_cells"] for r in mine]
                    print(f"{name[:8]:>8} {floors:>2} floors {goals} {order:<9} " + " ".join(
                        f"{p[:-2]}={fit_exponent(xs, [r.get(p, 0.0) for r in mine]):.2f}"
                        for p in TIME_PARTS + ("rss_mb",)))
    return 0


if __name__ == "__main__":
    sys.exit(main())


def _domain_of(problem: Any, max_level: int) -> Any:
    """The problem's domain up to ``max_level`` in whichever source tree runs (``--variant``): built by
    ``sgplan.planning.domain.domain_of`` now, by the problem itself (``domain_for`` / ``domain``) before."""
    try:
        from sgplan.planning.domain import domain_of
    except ImportError:
        return problem.domain_for(max_level) if hasattr(problem, "domain_for") else problem.domain
    return domain_of(problem, max_level)
