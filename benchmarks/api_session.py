"""What the public API costs and saves: a :class:`sgplan.Session` against fresh ``sgplan.plan`` calls, and
the robot outputs (simplified waypoints, events) against the planning itself.

Plans every mission of one Gibson scene from one start, first with a fresh call each (grid and labels built
every time), then within one session (grid built once, label masks kept per proposition), checks that the
costs agree, and prints the wall seconds of both, the path and simplified-waypoint counts, and the seconds
of :func:`sgplan.outputs.waypoints.simplify_path` on each path. Needs the Gibson data.

    .venv/bin/python benchmarks/api_session.py [--scene Benevolence] [--start 0] [--setup NO-LLM]
"""

from __future__ import annotations

import argparse
import time


def main() -> None:
    import sgplan
    from sgplan.datasets import scene_dir
    from sgplan.outputs.waypoints import simplify_path

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="Benevolence")
    parser.add_argument("--start", type=int, default=0)
    parser.add_argument("--setup", default="NO-LLM")
    args = parser.parse_args()
    folder = scene_dir(args.scene)
    building = sgplan.load_scene(folder)
    missions = [sgplan.load_mission(p) for p in sorted((folder / "missions").iterdir()) if p.is_dir()]
    sgplan.plan(building, missions[0], args.start, setup=args.setup)  # compile and warm caches first

    t0 = time.perf_counter()
    fresh = [sgplan.plan(building, m, args.start, setup=args.setup) for m in missions]
    fresh_s = time.perf_counter() - t0
    session = sgplan.Session(building)
    t0 = time.perf_counter()
    kept = [session.plan(m, args.start, setup=args.setup) for m in missions]
    session_s = time.perf_counter() - t0
    assert [round(r.cost_m, 9) for r in fresh] == [round(r.cost_m, 9) for r in kept]
    print(f"{len(missions)} missions of {building.name}, start {args.start}, setup {args.setup}")
    print(f"fresh calls {fresh_s:.2f} s, one session {session_s:.2f} s (x{fresh_s / session_s:.2f})")
    print("| mission | cells | simplified waypoints | simplify s | plan wall s |\n|---|---|---|---|---|")
    for folder_name, r in zip(sorted(p.name for p in (folder / "missions").iterdir() if p.is_dir()), kept):
        t0 = time.perf_counter()
        simplify_path(r.path, r.grid, r.labels, r.mission.automaton)
        print(
            f"| {folder_name} | {len(r.path)} | {len(r.waypoints_simplified)} | "
            f"{time.perf_counter() - t0:.3f} | "
            f"{r.timings['wall_s']:.2f} |"
        )


if __name__ == "__main__":
    main()
