"""The reach-model table: every shipped Gibson case under the ``box`` and the ``visible`` reach models, each
optimum checked by an independent exact solver.

For the 3 scenes x 5 missions x 5 starts (the cases ``sgplan bench`` runs, one session per scene as its
workers keep one), planned with setup ALL under one semantics profile (default ``ltlf``), it prints one
Markdown row per case: the optimal cost (metres) or the outcome (``invalid-start``, ``infeasible``,
``unsatisfiable``) under each model, whether the two differ, and what an exact product-graph Dijkstra
finds on the same grid, labels and automaton (``=`` it agrees to 1e-6 m; its run is skipped, ``-``, when
the start cell is not free, and shared by the two models when their labels are equal). Then the counts.

The solver is the compiled one of the benchmarks (``--solver c``, benchmarks/dijkstra_reference: seconds
per case) or the tests' oracle (``--solver python``, tests/planning/oracle.py: minutes per Gibson case).
Needs the Gibson data (and a C compiler for ``c``).

    .venv/bin/python benchmarks/reach_model_table.py > reach-model.md
    .venv/bin/python benchmarks/reach_model_table.py --scenes Allensville --missions 2 --solver python
"""

from __future__ import annotations

import argparse
import hashlib
import math
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from benchmarks.dijkstra_reference.reference import solve  # the repository's, on the path above
from tests.planning.oracle import optimal_cost

SCENES = ("Allensville", "Benevolence", "Collierville")
MODELS = ("box", "visible")
TOLERANCE_M = 1e-6


def exact_cost(problem, solver: str) -> float:
    """The optimum of ``problem`` (metres, ``inf`` without a path) by the chosen exact solver."""
    if solver == "c":
        return solve(problem)["cost"]
    return optimal_cost(problem.grid, problem.labels, problem.automaton, problem.start, problem.profile)


def solve_case(session, folder: Path, start: int, profile: str, model: str, oracles: dict,
               solver: str) -> tuple[str, str]:
    """``(sgplan's outcome, the solver's verdict)`` of one case under one reach model. ``oracles`` caches
    the solver's cost per (start cell, labelling, automaton)."""
    from sgplan import PlanOptions, load_mission
    from sgplan.assembly import make_problem
    from sgplan.errors import PlanningError
    from sgplan.starts import start_cell

    mission = load_mission(folder, profile=profile)
    options = PlanOptions(setup="ALL", profile=profile, reach_model=model)
    try:
        cost = session.plan(mission, start, options=options).cost_m
        outcome = f"{cost:.4f}"
    except PlanningError as error:
        cost, outcome = math.inf, error.status
    grid = session.grid(session.radii(options.robot_radius_m).robot_m)
    cell, _ = start_cell(session.building, grid, start)
    if not grid.traversable[cell[2], cell[0], cell[1]]:
        return outcome, "-"
    labels = session.labels(mission, None, model)  # the plan's: the session keeps them
    labelling = hashlib.blake2b(labels.tobytes(), digest_size=16).digest()
    key = (cell, labelling, mission.automaton.table.tobytes())
    if key not in oracles:
        problem = make_problem(session.building, mission, cell, options, grid=grid, labels=labels).problem
        oracles[key] = exact_cost(problem, solver)
    exact = oracles[key]
    agrees = (math.isinf(exact) and math.isinf(cost)) or abs(exact - cost) <= TOLERANCE_M
    return outcome, "=" if agrees else f"DISAGREES ({exact:.6f})"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="+", default=list(SCENES))
    parser.add_argument("--missions", nargs="+", type=int, default=[1, 2, 3, 4, 5])
    parser.add_argument("--starts", nargs="+", type=int, default=[0, 1, 2, 3, 4])
    parser.add_argument("--profile", default="ltlf", choices=("ltlf", "authors"))
    parser.add_argument("--solver", default="c", choices=("c", "python"))
    args = parser.parse_args(argv)

    import sgplan
    from sgplan.datasets import scene_dir

    t0 = time.perf_counter()
    solver = {"c": "benchmarks/dijkstra_reference", "python": "tests/planning/oracle.py"}[args.solver]
    print(f"Profile {args.profile}, setup ALL; costs in metres; exact solver: {solver} "
          f"(= agrees within {TOLERANCE_M:g} m).\n")
    print("| scene | mission | start | box | visible | differs | exact box | exact visible |")
    print("|---|---|---|---|---|---|---|---|")
    totals = {"cases": 0, "differ": 0, "disagree": 0, "checked": 0}
    for scene in args.scenes:
        session = sgplan.Session(scene_dir(scene))
        oracles: dict = {}
        for mission in args.missions:
            folder = scene_dir(scene) / "missions" / str(mission)
            for start in args.starts:
                results = [solve_case(session, folder, start, args.profile, m, oracles, args.solver)
                           for m in MODELS]
                (box, box_check), (visible, visible_check) = results
                differs = box != visible
                totals["cases"] += 1
                totals["differ"] += differs
                totals["checked"] += sum(check != "-" for _, check in results)
                totals["disagree"] += sum(check.startswith("DISAGREES") for _, check in results)
                print(f"| {scene} | {mission} | {start} | {box} | {visible} | {'yes' if differs else ''} | "
                      f"{box_check} | {visible_check} |", flush=True)
    print(f"\n{totals['cases']} cases; {totals['differ']} differ between the models; the solver checked "
          f"{totals['checked']} outcomes and disagreed on {totals['disagree']}; "
          f"{time.perf_counter() - t0:.0f} s.")
    return 1 if totals["disagree"] else 0


if __name__ == "__main__":
    sys.exit(main())
