"""Replanning after scene changes on the Gibson scenes: a run's replan against a fresh plan of the changed
building in a new Session from the same (cell, automaton state).

Scenarios: every shipped mission x starts 0-1 (where solvable) x setups (A*, ALL); at three points of the
optimal path (a quarter, half, three quarters of its cells) four changes that invalidate the rest of it:

- ``close_door``: close the next door the path crosses (the next change of room ahead);
- ``reopen_door``: reopen that door (closed, and replanned, just before);
- ``block``: block 1 m x 1 m of the way 1.5 m ahead of the robot;
- ``move_object``: move the next object the path goes to reach into another room of its floor.

Each change is applied to a run standing at the point, the run replans (``run.change`` + ``run.plan``: the
latency), and a new Session plans the changed building from the robot's cell and state (the fresh plan,
timed the same way; the scene cache is off, so its grid is built as a changed building's would be).
After a measured change the run undoes it (unmeasured) before the next. Costs must agree to 1e-6 m.

Then: monitoring a 10,000-pose trajectory, and 1,000 successive changes on one run (latency of the first
and last hundred replans, peak RSS).

    SGPLAN_NO_CACHE=1 .venv/bin/python benchmarks/replanning.py --out benchmarks/results/replanning.md
    .venv/bin/python benchmarks/replanning.py --scenes Benevolence --missions 4 --setups A*   # one case
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
os.environ.setdefault("SGPLAN_NO_CACHE", "1")

KINDS = ("close_door", "reopen_door", "block", "move_object")
_clock = time.perf_counter  # what measure() times replans and fresh plans with (--cpu: process_time)


def rss_mib(field: str = "VmHWM") -> float:
    """This process's peak (``VmHWM``) or current (``VmRSS``) resident memory, MiB."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024
    return float("nan")


def next_door(run, rest):
    """The (room key, room key) of the next change of room along ``rest`` whose closing leaves the robot's
    cell free, else None."""
    from sgplan.errors import SceneError

    rooms = run.grid.room_map[rest[:, 2], rest[:, 0], rest[:, 1]]
    for i in np.flatnonzero(np.diff(rooms) != 0):
        a, b = int(rooms[i]), int(rooms[i + 1])
        if a <= 0 or b <= 0:
            continue
        keys = (run.building.room(id=a).key, run.building.room(id=b).key)
        try:
            state, _ = run.scene.apply(_close(keys))
        except SceneError:
            continue
        row, col, floor = run.position
        if state.building.floors[floor].cat_map[row, col] == 0:
            return keys
    return None


def _close(keys):
    from sgplan.execution.changes import CloseDoor

    return CloseDoor(keys)


def block_ahead(run, rest):
    """A 1 m x 1 m block centred on the path cell 1.5 m ahead (None when the rest is shorter)."""
    from sgplan.execution.changes import Area, Block
    from sgplan.outputs.waypoints import leg_costs

    ahead = np.cumsum(leg_costs(rest, run.grid))
    at = np.searchsorted(ahead, 1.5)
    if at >= len(ahead):
        return None
    row, col, floor = (int(v) for v in rest[at + 1, :3])
    x, y, _ = run.grid.cell_xyz(floor, (row, col))
    return Block(Area(floor, box_m=(x - 0.5, y - 0.5, x + 0.5, y + 0.5)), "bench")


def move_next_goal(run, rest):
    """Move the next object the rest of the path reaches into the deepest free spot of another room of its
    floor (the change, or None)."""
    from scipy import ndimage

    from sgplan.errors import SceneError
    from sgplan.execution.changes import MoveObject

    labels = run.labels.raster[rest[:, 2], rest[:, 0], rest[:, 1]].astype(np.int64)
    seen = 0
    for label in labels:
        new = int(label) & ~seen
        seen |= int(label)
        for bit, prop in enumerate(run.labels.propositions):
            if not (new >> bit & 1) or prop.kind != "reach" or not run.building.has_object(prop.uuid):
                continue
            obj = run.building.object(uuid=prop.uuid)
            floor = run.building.room(id=obj.room_id).floor
            for room in run.building.floors[floor].rooms.values():
                if room.id == obj.room_id or room.is_staircase:
                    continue
                plan = run.building.floors[floor]
                free = (plan.room_map == room.id) & (plan.cat_map == 0)
                if not free.any():
                    continue
                depth = ndimage.distance_transform_edt(free)
                r, c = np.unravel_index(int(np.argmax(depth)), depth.shape)
                x, y, _ = run.grid.cell_xyz(floor, (int(r), int(c)))
                change = MoveObject(obj.key, (x, y), floor)
                try:
                    run.scene.apply(change)
                except SceneError:
                    continue
                return change
    return None


def measure(run, change, options):
    """(replan seconds, remaining cost, fresh seconds, fresh cost, replan expansions, fresh expansions)
    after ``change`` (expansions 0 where there is no plan)."""
    import sgplan
    from sgplan.errors import MissionError, PlanningError

    t0 = _clock()
    run.change([change])
    plan = run.plan
    replan_s = _clock() - t0
    cost = run.remaining_cost_m if plan is not None else math.inf
    t0 = _clock()
    try:
        result = sgplan.Session(run.building).plan(run.mission, run.position, options=options,
                                                   start_state=run.state)
        fresh = result.cost_m
    except (PlanningError, MissionError):
        result, fresh = None, math.inf
    return (replan_s, cost, _clock() - t0, fresh, _expansions(plan), _expansions(result))


def _expansions(result) -> int:
    """The states a plan's search expanded (all queues, all iterations); 0 without a plan."""
    return sum(result.iterations[-1].expansions) if result is not None and result.iterations else 0


def scenarios(scene, mission_index, start, setup, rows, verbose):
    import sgplan
    from sgplan.datasets import find_gibson_root
    from sgplan.errors import PlanningError
    from sgplan.execution.changes import OpenDoor, Unblock

    root = find_gibson_root()
    building = sgplan.load_scene(scene)
    mission = sgplan.load_mission(root / scene / "missions" / str(mission_index))
    session = sgplan.Session(building)
    options = sgplan.PlanOptions(setup=setup)
    try:
        base = session.plan(mission, start, options=options)
    except PlanningError:
        return
    if base.path is None or len(base.path) < 8:
        return
    for fraction in (0.25, 0.5, 0.75):
        run = sgplan.Run(session, mission, start, options=options)
        run.observe(base.path[1 : int(len(base.path) * fraction), :3], metric=False)
        if run.plan is None or run.remaining_path is None or len(run.remaining_path) < 4:
            continue
        case = {"scene": scene, "mission": mission_index, "start": start, "setup": setup, "point": fraction}
        door = next_door(run, run.remaining_path)
        if door is not None and record(run, case, "close_door", _close(door), rows, verbose):
            record(run, case, "reopen_door", OpenDoor(door), rows, verbose)
        block = block_ahead(run, run.remaining_path)
        if block is not None and record(run, case, "block", block, rows, verbose):
            run.change([Unblock(name="bench")])
        if run.plan is None:
            continue
        moved = move_next_goal(run, run.remaining_path)
        if moved is not None:
            record(run, case, "move_object", moved, rows, verbose)


def record(run, case: dict, kind: str, change, rows: list[dict], verbose: bool) -> bool:
    """Measure ``change`` on ``run`` into ``rows``; False when it cannot apply there (e.g. the inflated door
    would cover the robot's own cell)."""
    from sgplan.errors import SceneError

    try:
        replan_s, cost, fresh_s, fresh, expanded, fresh_expanded = measure(run, change, run.options)
    except SceneError:
        return False
    agree = (math.isinf(cost) and math.isinf(fresh)) or abs(cost - fresh) <= 1e-6
    rows.append({**case, "kind": kind, "replan_s": replan_s, "fresh_s": fresh_s, "cost": cost, "fresh": fresh,
                 "agree": agree, "expanded": expanded, "fresh_expanded": fresh_expanded})
    if verbose:
        where = f"{case['scene']} {case['mission']}/{case['start']} {case['setup']} @{case['point']:.2f}"
        print(f"{where} {kind}: replan {replan_s * 1e3:.1f} ms, fresh {fresh_s * 1e3:.0f} ms, "
              f"cost {cost:.4f} / {fresh:.4f}{'' if agree else '  DISAGREE'}, expansions {expanded} / "
              f"{fresh_expanded}", flush=True)
    return True


def monitoring(scene: str = "Collierville", mission_index: int = 2) -> tuple[int, float]:
    """Seconds to monitor a 10,000-pose trajectory (a plan's dense cells, there and back, repeated)."""
    import sgplan
    from sgplan.datasets import find_gibson_root
    from sgplan.execution.monitor import Monitor

    root = find_gibson_root()
    building = sgplan.load_scene(scene)
    mission = sgplan.load_mission(root / scene / "missions" / str(mission_index))
    session = sgplan.Session(building)
    path = session.plan(mission, 0, setup="A*").path
    cells = np.concatenate([path, path[::-1]] * (10_000 // (2 * len(path)) + 1))[:10_000, :3]
    xy = np.array([[*session.grid().cell_xyz(int(f), (int(r), int(c)))[:2], f] for r, c, f in cells])
    monitor = Monitor.in_session(session, mission)
    monitor.observe_xy(xy[:10])  # load the kernels
    best = math.inf
    for _ in range(5):
        monitor = Monitor.in_session(session, mission)
        t0 = time.perf_counter()
        monitor.observe_xy(xy)
        best = min(best, time.perf_counter() - t0)
    return len(xy), best


def successive(count: int = 1000, scene: str = "Benevolence") -> dict:
    """``count`` changes on one run (a door closed and opened in turn), each followed by a replan. Run in a
    process of its own (:func:`successive_apart`), so that its peak RSS is the run's: one scene, its
    session and the run."""
    import sgplan
    from sgplan.datasets import find_gibson_root
    from sgplan.execution.changes import CloseDoor, OpenDoor

    root = find_gibson_root()
    building = sgplan.load_scene(scene)
    mission = sgplan.load_mission(root / scene / "missions" / "4")
    run = sgplan.Run(sgplan.Session(building), mission, 0, setup="A*")
    rest = run.plan.path
    door = next_door(run, rest[len(rest) // 2 :])
    latencies, rss_100 = [], float("nan")
    for k in range(count):
        change = (CloseDoor if k % 2 == 0 else OpenDoor)(door)
        t0 = time.perf_counter()
        run.change([change])
        assert run.plan is not None
        latencies.append(time.perf_counter() - t0)
        if k == 99:
            rss_100 = rss_mib("VmRSS")
    first, last = statistics.median(latencies[:100]), statistics.median(latencies[-100:])
    return {"changes": count, "first100_ms": first * 1e3, "last100_ms": last * 1e3, "ratio": last / first,
            "rss_100_mib": rss_100, "rss_end_mib": rss_mib("VmRSS"), "peak_rss_mib": rss_mib(), "door": door}


def successive_apart(count: int) -> dict:
    """:func:`successive` in a new interpreter (spawned: nothing of this process's scenes in it)."""
    import multiprocessing

    with multiprocessing.get_context("spawn").Pool(1) as pool:
        return pool.apply(successive, (count,))


def table(rows: list[dict]) -> list[str]:
    lines = ["| setup | change | scenarios | costs agree | replan median (ms) | replan p95 (ms) | "
             "fresh median (ms) | replan / fresh median | expansions replan / fresh |",
             "|---|---|---|---|---|---|---|---|---|"]
    for setup in sorted({r["setup"] for r in rows}):
        for kind in (*KINDS, "all"):
            sel = [r for r in rows if r["setup"] == setup and (kind == "all" or r["kind"] == kind)]
            if not sel:
                continue
            replan = np.array([r["replan_s"] for r in sel]) * 1e3
            fresh = np.array([r["fresh_s"] for r in sel]) * 1e3
            agree = sum(r["agree"] for r in sel)
            expanded = sum(r["expanded"] for r in sel) / max(sum(r["fresh_expanded"] for r in sel), 1)
            lines.append(f"| {setup} | {kind} | {len(sel)} | {agree}/{len(sel)} | {np.median(replan):.1f} | "
                         f"{np.percentile(replan, 95):.1f} | {np.median(fresh):.0f} | "
                         f"{np.median(replan / fresh):.3f} | {expanded:.2f} |")
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenes", nargs="+", default=["Allensville", "Benevolence", "Collierville"])
    parser.add_argument("--missions", nargs="+", type=int, default=[1, 2, 3, 4, 5])
    parser.add_argument("--starts", nargs="+", type=int, default=[0, 1])
    parser.add_argument("--setups", nargs="+", default=["A*", "ALL"])
    parser.add_argument("--successive", type=int, default=1000)
    parser.add_argument("--exact-fields", action="store_true",
                        help="runs recompute an h_LTL field a repair would leave a lower bound (FieldStore)")
    parser.add_argument("--cpu", action="store_true",
                        help="time replans and fresh plans in CPU seconds of this process, not wall clock "
                             "(steadier on a machine shared with other work)")
    parser.add_argument("--out", type=Path)
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args()
    if args.exact_fields:
        import functools

        from sgplan.execution import fields, parts

        parts.FieldStore = functools.partial(fields.FieldStore, invalidate_fraction=0.02, bound=False)
    global _clock
    _clock = time.process_time if args.cpu else time.perf_counter
    started, load_before = time.time(), os.getloadavg()
    rows: list[dict] = []
    for scene in args.scenes:
        for mission in args.missions:
            for start in args.starts:
                for setup in args.setups:
                    scenarios(scene, mission, start, setup, rows, not args.quiet)
    lines = table(rows)
    poses, monitor_s = monitoring()
    lines += ["", f"Monitoring a {poses:,}-pose trajectory (Collierville mission 2, metric poses): "
              f"{monitor_s * 1e3:.1f} ms (best of 5)."]
    if args.successive:
        result = successive_apart(args.successive)
        lines += [f"{result['changes']} successive changes on one run (Benevolence mission 4, A*, the door "
                  f"{result['door'][0]}/{result['door'][1]} closed and opened in turn, a replan after each): "
                  f"median replan {result['first100_ms']:.1f} ms over the first 100, "
                  f"{result['last100_ms']:.1f} ms over the last 100 (x{result['ratio']:.2f}); in a process "
                  f"of its own (one scene, its session, the run): RSS {result['rss_100_mib']:.0f} MiB after "
                  f"100 changes, {result['rss_end_mib']:.0f} MiB after {result['changes']}, peak "
                  f"{result['peak_rss_mib']:.0f} MiB."]
    disagree = [r for r in rows if not r["agree"]]
    seconds = time.time() - started
    load = ", ".join(f"{x:.1f}" for x in (*load_before, *os.getloadavg()))
    lines += ["", f"{len(rows)} scenarios, {len(disagree)} cost disagreements; {seconds:.0f} s; load average "
              f"(1, 5, 15 min) before and after: {load}."]
    text = "\n".join(lines)
    print(text)
    if args.out:
        args.out.write_text(text + "\n")


if __name__ == "__main__":
    main()
