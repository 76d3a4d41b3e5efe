"""How long do the plan pictures and the HTML report take on the Gibson scenes?

For each Gibson scene, plans its mission 1 from the first initial position that the mission accepts
(setup NO-LLM), then times, per floor, building the figure (:func:`sgplan.scene.draw.draw_floor`:
rasters, labels placed, path, arrows) and saving it as PNG and as SVG; then the automaton SVG and the
whole HTML report (:func:`sgplan.report.html.report_html`). Writes the files under ``--out`` so they
can be looked at.

    .venv/bin/python benchmarks/draw_report.py --out /tmp/sgplan-draw

Needs the Gibson data (see sgplan.datasets). About half a minute on 2 cores.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from sgplan.assembly import make_problem
from sgplan.datasets import SCENES, find_gibson_root
from sgplan.errors import PlanningError
from sgplan.mission import load_mission_folder
from sgplan.planning.amra import plan
from sgplan.radii import resolve_radii
from sgplan.report.automaton import automaton_svg, graphviz_available
from sgplan.report.html import report_html
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.draw import MissionView, draw_floor
from sgplan.scene.grid import build_occupancy_grid


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("/tmp/sgplan-draw"))
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        print("Gibson data not found (set SGPLAN_GIBSON_DIR)")
        return 1
    print(f"graphviz: {'yes' if graphviz_available() else 'no (matplotlib automaton drawings)'}")
    print("scene         floor  figure_s  png_s  svg_s  | automaton_s  report_s  report_kB")
    for scene in SCENES:
        building = load_authors_scene(root / scene)
        mission = load_mission_folder(root / scene / "missions" / "1")
        radii = resolve_radii(building)
        grid = build_occupancy_grid(building, radii.robot_m)
        labels = mission.labels(building, radii.reach_m)
        for start in building.initial_cells:
            problem = make_problem(building, mission, start, grid=grid, labels=labels).problem
            try:
                result = plan(problem, "NO-LLM")
                break
            except PlanningError:
                continue
        else:
            print(f"{scene}: mission 1 accepts no initial position")
            continue
        view = MissionView(
            text=mission.text,
            cost_m=result.cost_m,
            propositions=mission.ordered_propositions,
            reach_radius_m=radii.reach_m,
        )
        out = args.out / scene
        out.mkdir(parents=True, exist_ok=True)
        for floor in range(building.num_floors):
            t0 = time.perf_counter()
            fig = draw_floor(building, floor, grid=grid, path=result.path, mission=view)
            t1 = time.perf_counter()
            fig.savefig(out / f"floor_{floor}.png")
            t2 = time.perf_counter()
            fig.savefig(out / f"floor_{floor}.svg")
            t3 = time.perf_counter()
            print(f"{scene:13s} {floor:5d}  {t1 - t0:8.2f}  {t2 - t1:5.2f}  {t3 - t2:5.2f}  |")
        t0 = time.perf_counter()
        automaton_svg(mission.automaton, names=mission.descriptions)
        t1 = time.perf_counter()
        page = report_html(building, grid, result, mission, reach_radius_m=radii.reach_m)
        t2 = time.perf_counter()
        (out / "report.html").write_text(page, encoding="utf-8")
        print(f"{scene:13s} {'-':>5s}  {'':24s}|  {t1 - t0:11.2f}  {t2 - t1:8.2f}  {len(page) / 1e3:9.0f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
