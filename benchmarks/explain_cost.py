"""What saying back a mission costs next to preparing its plan, on the 15 shipped Gibson missions.

For each mission (ltlf profile, start 0) times, in one process: ``make_problem`` (grid + labels, what
every plan pays anyway), ``explain_mission`` (the explanation), ``check_mission_in_scene`` on the
prepared grid and labels (the checks before search) and ``ensure_folder_fits_scene``. Prints one row per
mission and the ratio of the totals to ``make_problem``. Each timing is the best of ``--repeat`` runs.

    .venv/bin/python benchmarks/explain_cost.py
    .venv/bin/python benchmarks/explain_cost.py --repeat 5

Needs the Gibson data (see sgplan.datasets). Under a minute.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from sgplan.assembly import make_problem
from sgplan.datasets import SCENES, find_gibson_root
from sgplan.explain import explain_mission
from sgplan.explain.checks import check_mission_in_scene
from sgplan.formats import load_scene
from sgplan.mission import load_mission_folder
from sgplan.mission.identity import ensure_folder_fits_scene


def best_of(repeat: int, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> tuple[float, Any]:
    times, value = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        value = fn(*args, **kwargs)
        times.append(time.perf_counter() - t0)
    return min(times), value


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        sys.exit("Gibson data not found (set SGPLAN_GIBSON_DIR)")
    totals = {"make_problem": 0.0, "explain": 0.0, "check": 0.0, "identity": 0.0}
    print(
        f"{'mission':16} {'make_problem':>12} {'explain':>9} {'method':>9} {'check':>8} {'identity':>9}  "
        "findings"
    )
    for scene in SCENES:
        building = load_scene(root / scene)
        for number in range(1, 6):
            folder = root / scene / "missions" / str(number)
            mission = load_mission_folder(folder)
            start = building.initial_cells[0]
            t_make, prepared = best_of(args.repeat, make_problem, building, mission, start)
            t_explain, explanation = best_of(args.repeat, explain_mission, mission, building)
            t_check, check = best_of(args.repeat, check_mission_in_scene, mission, building, start,
                                     grid=prepared.problem.grid, labels=prepared.problem.labels)
            t_id, _ = best_of(args.repeat, ensure_folder_fits_scene, folder, mission.propositions, building)
            for key, value in zip(totals, (t_make, t_explain, t_check, t_id)):
                totals[key] += value
            kinds = ",".join(f.kind for f in check.findings) or "-"
            print(f"{scene + '/' + str(number):16} {t_make * 1e3:10.1f}ms {t_explain * 1e3:7.1f}ms "
                  f"{explanation.method:>9} {t_check * 1e3:6.1f}ms {t_id * 1e3:7.1f}ms  {kinds}")
    base = totals["make_problem"]
    print("totals: " + ", ".join(f"{k} {v:.3f} s ({v / base:.2f}x make_problem)" for k, v in totals.items()))


if __name__ == "__main__":
    main()
