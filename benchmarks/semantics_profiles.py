"""Where the semantics profile changes the answer: every shipped mission and start under three readings.

- ``authors``: the authors' C++ (start label not read, a missing automaton edge keeps the state);
- ``strict``: missing edges reject, start label not read (the "strict" column of
  reference-algorithm.md §11);
- ``ltlf``: sgplan's default (missing edges reject AND the start label is read).

Prints one Markdown table of optimal costs (metres; ``invalid-start`` / ``infeasible`` otherwise) and
marks the cases where the readings disagree. All three use the authors' ``box`` reach model, so that only
the reading changes (benchmarks/reach_model_table.py compares the reach models). Needs the Gibson data
(see sgplan.datasets).

    .venv/bin/python benchmarks/semantics_profiles.py [--scenes Allensville Benevolence]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

READINGS = {"authors": ("authors", "authors"), "strict": ("ltlf", "authors"), "ltlf": ("ltlf", "ltlf")}
"""reading -> (how automaton.aut's missing edges are read, which planning profile)."""


def solve(building, folder: Path, start: tuple[int, int, int], reading: str) -> str:
    from sgplan.assembly import make_problem
    from sgplan.errors import PlanningError
    from sgplan.mission import load_mission_folder
    from sgplan.options import PlanOptions
    from sgplan.planning import plan

    hoa_profile, plan_profile = READINGS[reading]
    mission = load_mission_folder(folder, profile=hoa_profile)
    try:
        options = PlanOptions(profile=plan_profile, reach_model="box")
        problem = make_problem(building, mission, start, options).problem
        return f"{plan(problem, 'ALL').cost_m:.4f}"
    except PlanningError as error:
        return error.status


def main() -> None:
    from sgplan.datasets import SCENES, find_gibson_root
    from sgplan.scene.authors import load_authors_scene

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="+", default=list(SCENES))
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        sys.exit("Gibson data not found (set SGPLAN_GIBSON_DIR)")
    print("| scene | mission | start | authors | strict | ltlf |")
    print("|---|---|---|---|---|---|")
    for scene in args.scenes:
        building = load_authors_scene(root / scene)
        for mission in range(1, 6):
            folder = root / scene / "missions" / str(mission)
            for k, start in enumerate(building.initial_cells):
                costs = [solve(building, folder, start, reading) for reading in READINGS]
                mark = " **differs**" if len(set(costs)) > 1 else ""
                print(f"| {scene} | {mission} | {k} | {' | '.join(costs)}{mark} |", flush=True)


if __name__ == "__main__":
    main()
