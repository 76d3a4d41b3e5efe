"""Growth of sgplan with building size: synthetic buildings, one subprocess per case.

For each size (cell edge ``cell_m`` and rooms per floor set the grid size; ``--floors`` the floors) and each
mission (k goals, sequenced ``F(g1 & F(g2 & ...))`` or unordered ``F g1 & ... & F gk``, goals = reach
distinct objects), a child process generates the building (:func:`sgplan.scene.synthetic.generate_building`),
builds grid and labels (``make_problem``), the planning domain, and plans (``--setup``, NO-LLM by default:
synthetic missions carry no LLM guidance). It prints seconds per part, the child's peak RSS, grid and
free cells, automaton states and expansions; then least-squares growth exponents (time ~ free_cells^b)
per part and mission, over the sizes that finished.

    .venv/bin/python benchmarks/scaling.py                          # 0.25M .. 4M grid cells, 1-2 floors
    .venv/bin/python benchmarks/scaling.py --sizes 0.25 1 4 16 --floors 1 2 10 --goals 2 5 9
    .venv/bin/python benchmarks/scaling.py --timeout 120            # per case, seconds

Sizes are target GRID cells in millions (all floors); the achieved count is printed. The machine is
shared: compare within one run.
"""

from __future__ import annotations

import argparse
import json
import math
import resource
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def _building(target_cells: float, floors: int, rooms: int, seed: int):
    """A synthetic building whose grid has about ``target_cells`` cells over all floors."""
    from sgplan.scene.synthetic import generate_building

    probe = generate_building(num_floors=1, rooms_per_floor=rooms, num_objects=0, cell_m=0.05, seed=seed)
    rows, cols = probe.floors[0].shape
    cell_m = 0.05 * math.sqrt(rows * cols * floors / target_cells)  # area per floor is fixed in metres
    return generate_building(num_floors=floors, rooms_per_floor=rooms, num_objects=3 * rooms * floors,
                             cell_m=cell_m, seed=seed)


def run_case(target_m: float, floors: int, goals: int, order: str, setup: str, seed: int) -> dict:
    """One case in this process; returns seconds per part and sizes."""
    import numpy as np

    from sgplan.mission import mission_from_formula
    from sgplan.pipeline import make_problem
    from sgplan.planning import plan

    row: dict = {"target_m": target_m, "floors": floors, "goals": goals, "order": order}
    t0 = time.perf_counter()
    building = _building(target_m * 1e6, floors, rooms=max(4, goals), seed=seed)
    row["building_s"] = time.perf_counter() - t0
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
    row["automaton_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    problem = make_problem(building, mission, (0, 0, 0)).problem
    # Start at the free cell nearest the middle of floor 0 (the domain, built later, checks it).
    free = np.argwhere(problem.grid.traversable[0])
    centre = free[np.argmin(((free - free.mean(axis=0)) ** 2).sum(axis=1))]
    problem.start = (int(centre[0]), int(centre[1]), 0)
    row["grid_labels_s"] = time.perf_counter() - t0
    row["grid_cells"] = int(np.prod(problem.grid.shape))
    row["free_cells"] = int(problem.grid.traversable.sum())
    row["states"] = int(problem.automaton.num_states)
    t0 = time.perf_counter()
    domain = problem.domain
    row["domain_s"] = time.perf_counter() - t0
    before = domain.precompute_s
    result = plan(problem, setup)
    row["actions_s"] = result.precompute_s - before  # composite action maps (setups using them) + kernel load
    row["search_s"] = result.search_s
    row["cost"] = result.cost_m
    row["expansions"] = result.expansions
    row["status"] = result.status
    row["rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
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


PARTS = (
    "building_s",
    "automaton_s",
    "grid_labels_s",
    "domain_s",
    "actions_s",
    "search_s",
    "wall_s",
    "rss_mb",
)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--sizes", nargs="+", type=float, default=[0.25, 1.0, 4.0], help="millions of grid cells"
    )
    parser.add_argument("--floors", nargs="+", type=int, default=[1, 2])
    parser.add_argument("--goals", nargs="+", type=int, default=[2, 5])
    parser.add_argument("--orders", nargs="+", default=["sequenced", "unordered"])
    parser.add_argument("--setup", default="NO-LLM")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per case")
    parser.add_argument(
        "--one", nargs=4, metavar=("SIZE", "FLOORS", "GOALS", "ORDER"), help=argparse.SUPPRESS
    )
    args = parser.parse_args()
    if args.one:
        size, floors, goals, order = args.one
        print(json.dumps(run_case(float(size), int(floors), int(goals), order, args.setup, args.seed)))
        return 0

    print(
        f"{'size M':>6} {'fl':>2} {'goals':>9} {'grid':>9} {'free':>9} {'Q':>4} "
        + " ".join(f"{p[:-2]:>9}" for p in PARTS)
        + f" {'expans':>9}"
    )
    rows = []
    for floors in args.floors:
        for goals in args.goals:
            for order in args.orders:
                for size in args.sizes:
                    cmd = [sys.executable, __file__, "--setup", args.setup, "--seed", str(args.seed),
                           "--one", str(size), str(floors), str(goals), order]
                    t0 = time.perf_counter()
                    try:
                        out = subprocess.run(
                            cmd, capture_output=True, text=True, cwd=REPO, timeout=args.timeout, check=False
                        )
                    except subprocess.TimeoutExpired:
                        print(
                            f"{size:>6} {floors:>2} {goals:>2} {order[:6]:>6} "
                            f"timed out after {args.timeout:g} s"
                        )
                        continue
                    wall = time.perf_counter() - t0
                    if out.returncode != 0:
                        print(
                            f"{size:>6} {floors:>2} {goals:>2} {order[:6]:>6} "
                            f"failed: {out.stderr.strip()[-300:]}"
                        )
                        continue
                    row = json.loads(out.stdout.strip().splitlines()[-1])
                    row["wall_s"] = wall
                    rows.append(row)
                    print(
                        f"{size:>6} {floors:>2} {goals:>2} {order[:6]:>6} "
                        f"{row['grid_cells']:>9} {row['free_cells']:>9} "
                        f"{row['states']:>4} "
                        + " ".join(f"{row[p]:>9.2f}" for p in PARTS)
                        + f" {row['expansions']:>9}",
                        flush=True,
                    )
    print(
        "\ngrowth exponents b in (part ~ free_cells^b), per floors / goals / order, "
        "over the sizes that finished"
    )
    for floors in args.floors:
        for goals in args.goals:
            for order in args.orders:
                mine = [r for r in rows if (r["floors"], r["goals"], r["order"]) == (floors, goals, order)]
                if len(mine) < 2:
                    continue
                xs = [r["free_cells"] for r in mine]
                print(f"{floors:>2} floors {goals} {order:<9} " + " ".join(
                    f"{p[:-2]}={fit_exponent(xs, [r[p] for r in mine]):.2f}" for p in PARTS))
    return 0


if __name__ == "__main__":
    sys.exit(main())
