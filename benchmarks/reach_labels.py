"""What the ``visible`` reach model costs against the ``box`` window, in one run: the label cells of a whole
Gibson scene, and the planning domain's object regions.

Per scene, with the two models timed back to back in every repetition (the machine is shared: compare the
ratio, take the best of ``--repeat``):

- *labels*: the cells of every proposition of the scene -- each room entered, each object reached at the
  scene's reach radius (:func:`sgplan.scene.labels.proposition_cells`, the sparse form a session keeps and
  the label rasters are made of);
- *domain*: the composite action tables of a planning domain (``PlanningDomain.timings["action_tables"]``:
  every object's region among its room's free cells, and the room and floor families) for mission 1 from
  the first free initial position.

Then, in a fresh process, the first visible region of a run, where numba loads the cached kernel: on its
own (numba's start-up included), and after a plan has loaded the planner's kernels (what it adds to a
process that plans anyway). Last, why the object's own room is see-through: per scene, the objects that
no free cell (robot radius of the scene) reaches under ``box``, ``visible``, and ``visible`` with every
non-floor cell opaque (the category maps draw unlabelled furniture as wall: a sink sits in a counter).

    .venv/bin/python benchmarks/reach_labels.py [--scenes Benevolence] [--repeat 5]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SCENES = ("Allensville", "Benevolence", "Collierville")
MODELS = ("box", "visible")
FIRST_CALL = """
import sys, time
import sgplan
from sgplan.scene.reach import object_reach_cells
building = sgplan.load_scene("demo")
if sys.argv[1] == "after-a-plan":
    sgplan.plan(building, sgplan.mission_from_formula('F "enter(room_5)"', building), 0, reach_model="box")
obj = next(iter(building.objects()))
t0 = time.perf_counter()
object_reach_cells(building.floors[0], obj, 0.6, "visible")
print(time.perf_counter() - t0)
"""


def label_seconds(building, model: str) -> float:
    from sgplan.scene.labels import Proposition, proposition_cells

    props = [Proposition("enter", r.uuid) for r in building.rooms()]
    props += [Proposition("reach", o.uuid) for o in building.objects()]
    t0 = time.perf_counter()
    for prop in props:
        proposition_cells(building, prop, None, model)
    return time.perf_counter() - t0


def domain_seconds(building, grid, mission, model: str) -> float:
    from sgplan import PlanOptions
    from sgplan.assembly import make_problem
    from sgplan.errors import PlanningError
    from sgplan.planning.domain import domain_of

    options = PlanOptions(reach_model=model)
    labels = mission.labels(building, None, model)
    for start in building.initial_cells:
        if grid.traversable[start[2], start[0], start[1]]:
            problem = make_problem(building, mission, start, options, grid=grid, labels=labels).problem
            try:
                return domain_of(problem).timings["action_tables"]
            except PlanningError:
                continue
    return float("nan")


def out_of_reach(building, grid) -> dict[str, list[str]]:
    """The objects (``name uuid``) that no free cell reaches, per rule: ``box``, ``visible`` and
    ``all-opaque`` (visible with every non-floor cell but the object's own opaque)."""
    from sgplan.scene._sight import visible_cells
    from sgplan.scene.dilate import radius_widths, within_distance
    from sgplan.scene.model import CatCode
    from sgplan.scene.reach import object_reach_cells

    radius = building.reach_radius_m
    lost: dict[str, list[str]] = {"box": [], "visible": [], "all-opaque": []}
    for obj in building.objects():
        floor = building.floors[building.room(uuid=obj.room_uuid).floor]
        free = grid.traversable[floor.index]
        name = f"{obj.name} {obj.uuid}"
        for model in ("box", "visible"):
            if not free.reshape(-1)[object_reach_cells(floor, obj, radius, model)].any():
                lost[model].append(name)
        target = floor.cat_map == obj.id
        ground = floor.cat_map == CatCode.GROUND
        widest = radius_widths(floor.resolution_m, radius, *floor.shape)
        viewers = ground & free & within_distance(target, floor.resolution_m, radius)
        seen = visible_cells(~ground & ~target, target, viewers, widest)
        if not seen.any():
            lost["all-opaque"].append(name)
    return lost


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="+", default=list(SCENES))
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(argv)

    import sgplan
    from sgplan.datasets import scene_dir
    from sgplan.scene.grid import build_occupancy_grid

    first = {}
    for when in ("alone", "after-a-plan"):
        run = subprocess.run([sys.executable, "-c", FIRST_CALL, when], capture_output=True, text=True,
                             check=True, cwd=REPO)
        first[when] = float(run.stdout)
    print("| scene | objects | labels box s | labels visible s | ratio | domain box s | domain visible s "
          "| ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for scene in args.scenes:
        building = sgplan.load_scene(scene)
        grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
        mission = sgplan.load_mission(scene_dir(scene) / "missions" / "1")
        for model in MODELS:  # warm: numba's kernels, the category maps' pages
            label_seconds(building, model)
        labels = dict.fromkeys(MODELS, float("inf"))
        domain = dict.fromkeys(MODELS, float("inf"))
        for _ in range(args.repeat):
            for m in MODELS:
                labels[m] = min(labels[m], label_seconds(building, m))
                domain[m] = min(domain[m], domain_seconds(building, grid, mission, m))
        print(f"| {scene} | {sum(1 for _ in building.objects())} | {labels['box']:.3f} | "
              f"{labels['visible']:.3f} | {labels['visible'] / labels['box']:.2f} | {domain['box']:.3f} | "
              f"{domain['visible']:.3f} | {domain['visible'] / domain['box']:.2f} |", flush=True)
    print(f"\nFirst visible region of a fresh process (numba loads the cached kernel): "
          f"{first['alone']:.3f} s alone, {first['after-a-plan']:.3f} s after a plan")
    print("\n| scene | objects | no free cell reaches it: box | visible "
          "| visible, every non-floor cell opaque |")
    print("|---|---|---|---|---|")
    for scene in args.scenes:
        building = sgplan.load_scene(scene)
        lost = out_of_reach(building, build_occupancy_grid(building, building.robot_radius_m or 0.0))
        cells = [f"{len(lost[k])}" + (f" ({', '.join(lost[k])})" if 0 < len(lost[k]) <= 4 else "")
                 for k in ("box", "visible", "all-opaque")]
        print(f"| {scene} | {sum(1 for _ in building.objects())} | {' | '.join(cells)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
