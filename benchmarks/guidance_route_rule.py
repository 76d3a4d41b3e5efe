"""How much does filtering guidance calls help the planner? Measured on GPT-4's shipped guidance.

For each shipped Gibson mission (authors profile) and start, plans with setup ALL three times:
``shipped`` (the authors' llm_heuristic.yaml as it is; the planner skips calls it cannot use), ``valid``
(only calls that pass :func:`sgplan.llm.guidance.validate_call`, as sgplan's guidance step keeps),
``route`` (those, also cut at the first break of the route rule, :func:`sgplan.llm.guidance.route_break`;
sgplan reports such breaks but does not cut, because of what this measures), and once with NO-LLM. Prints per
variant the entries changed, and means of the first path's search time,
first cost / optimal cost, search time to the optimum and expansions.

    .venv/bin/python benchmarks/guidance_route_rule.py              # starts 0 and 3
    .venv/bin/python benchmarks/guidance_route_rule.py --starts 0 1 2 3 4

Needs the Gibson data (see sgplan.datasets). About 4 minutes for two starts on 2 cores.
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from sgplan.assembly import make_problem
from sgplan.datasets import SCENES, find_gibson_root
from sgplan.errors import PlanningError
from sgplan.llm.guidance import Guidance, route_break, validate_call
from sgplan.mission import load_mission_folder
from sgplan.options import PlanOptions
from sgplan.planning import plan
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.model import Building

VARIANTS = ("shipped", "valid", "route")


def filtered(guidance: Guidance, building: Building, variant: str) -> tuple[Guidance, int]:
    """``guidance`` under ``variant``, and how many entries it changed."""
    out: Guidance = {}
    changed = 0
    for room, states in guidance.items():
        out[room] = {}
        for q, calls in states.items():
            kept = list(calls or [])
            if variant != "shipped":
                kept = [c for c in (validate_call(str(call), building)[0] for call in kept) if c]
            if variant == "route":
                kept = _until_break(kept, int(room))
            changed += kept != list(calls or [])
            out[room][q] = kept
    return out, changed


def _until_break(calls: list[str], room: int) -> list[str]:
    """The calls before the first break of the route rule."""
    for k in range(len(calls), 0, -1):
        if not route_break(calls[:k], room):
            return calls[:k]
    return []


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, nargs="+", default=[0, 3])
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        sys.exit("Gibson data not found: set SGPLAN_GIBSON_DIR or place it at ../shared/datasets/gibson-3dsg")
    rows: dict[str, list[tuple[float, float, float, int]]] = {v: [] for v in (*VARIANTS, "NO-LLM")}
    changed = {v: 0 for v in VARIANTS}
    entries = 0
    for name in SCENES:
        building = load_authors_scene(root / name)
        for mission_dir in sorted((root / name / "missions").iterdir()):
            mission = load_mission_folder(mission_dir, profile="authors")
            shipped = mission.guidance
            entries += sum(len(states) for states in shipped.values())
            for variant in VARIANTS:
                mission.guidance, n = filtered(shipped, building, variant)
                changed[variant] += n
                for start in args.starts:
                    _run(rows[variant], building, mission, start)
            for start in args.starts:
                _run(rows["NO-LLM"], building, mission, start, setup="NO-LLM")
            print(f"{name} mission {mission_dir.name} done", file=sys.stderr, flush=True)
    print(f"{entries} guidance entries; changed by the variant: "
          + ", ".join(f"{v} {changed[v]}" for v in VARIANTS))
    print("| guidance | n | 1st path search (s) | 1st cost / opt. | search to opt. (s) | expansions |")
    print("|---|---|---|---|---|---|")
    for variant, measured in rows.items():
        if measured:
            first, ratio, opt, exp = (statistics.fmean(col) for col in zip(*measured))
            print(f"| {variant} | {len(measured)} | {first:.4f} | {ratio:.4f} | {opt:.3f} | {exp:,.0f} |")
    return 0


def _run(out: list, building: Building, mission, start: int, setup: str = "ALL") -> None:
    try:
        options = PlanOptions(profile="authors")
        problem = make_problem(building, mission, building.initial_cells[start], options).problem
        result = plan(problem, setup)
    except PlanningError:
        return  # invalid start or infeasible: nothing to compare
    first, last = result.iterations[0], result.iterations[-1]
    out.append((first.time_s, first.cost_m / result.cost_m, last.time_s, result.expansions))


if __name__ == "__main__":
    sys.exit(main())
