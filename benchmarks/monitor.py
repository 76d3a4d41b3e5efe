"""What monitoring a 10,000-pose trajectory costs, on the 15 shipped Gibson missions (the issue's target:
<= 10 ms, JIT excluded).

For each mission (ltlf profile, the first of starts 0-4 it is solvable from) the optimal A* path is
planned, and three 10,000-pose trajectories are made from it:

- ``10 Hz``: poses interpolated along the path (many consecutive poses in one cell, as a robot's
  localisation at 10 Hz would give them);
- ``cells``: a pose on every cell, out along the path and back, repeated (every pose a new cell);
- ``0.5 m``: a pose every 0.5 m along the same out-and-back polyline (the monitor reads the cells between
  them: about ten per pose).

Timed, in one process: ``Monitor.observe_xy`` of the whole trajectory in one call, on a fresh monitor
made beforehand (its construction is not timed), median of ``--repeat``; then, apart, the first reading
of ``status.left`` (what is left, in words: made on demand, once per state); and the same poses fed one
call per pose. The first call of the process (loading or compiling the kernel) is reported on its own,
not in the medians.

    .venv/bin/python benchmarks/monitor.py > benchmarks/results/monitor.md

Needs the Gibson data (see sgplan.datasets); about a minute.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from functools import partial
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import sgplan
from sgplan.datasets import SCENES, find_gibson_root
from sgplan.errors import PlanningError
from sgplan.execution.monitor import Monitor

POSES = 10_000
SHAPES = ("10 Hz", "cells", "0.5 m")


def trajectories(centres: np.ndarray) -> dict[str, np.ndarray]:
    """The three ``(10000, 3)`` trajectories of a path's cell centres ``(n, 3)`` (x_m, y_m, floor)."""
    t = np.linspace(0, len(centres) - 1, POSES)
    i = np.floor(t).astype(int)
    j = np.minimum(i + 1, len(centres) - 1)
    same = centres[i, 2] == centres[j, 2]
    frac = np.where(same, t - i, 0.0)[:, None]
    drive = np.column_stack([centres[i, :2] * (1 - frac) + centres[j, :2] * frac, centres[i, 2]])
    loop = np.concatenate([centres, centres[-2:0:-1]])
    cells = np.resize(loop, (POSES, 3))
    steps = np.hypot(*np.diff(loop[:, :2], axis=0).T)
    along = np.concatenate([[0.0], np.cumsum(np.where(np.diff(loop[:, 2]) == 0, steps, 0.0))])
    picks = np.searchsorted(along, np.arange(0.0, along[-1], 0.5))
    sparse = np.resize(loop[np.unique(picks)], (POSES, 3))
    return {"10 Hz": drive, "cells": cells, "0.5 m": sparse}


def timed(monitor: Monitor, poses: np.ndarray) -> tuple[float, int, float]:
    """Seconds of one ``observe_xy`` call, the cells it read, seconds of the first reading of ``left``."""
    t0 = time.perf_counter()
    status = monitor.observe_xy(poses)
    t1 = time.perf_counter()
    _ = status.left
    return t1 - t0, status.cells, time.perf_counter() - t1


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        sys.exit("Gibson data not found (set SGPLAN_GIBSON_DIR)")
    rows, first_call = [], None
    for scene in SCENES:
        session = sgplan.Session(sgplan.load_scene(scene, root))
        for number in range(1, 6):
            mission = sgplan.load_mission(root / scene / "missions" / str(number))
            for start in range(5):
                try:
                    result = session.plan(mission, start, setup="A*")
                    break
                except PlanningError:
                    continue
            else:
                continue
            centres = np.array([(w.x_m, w.y_m, w.floor) for w in result.waypoints])
            make = partial(Monitor.in_session, session, mission)
            if first_call is None:
                first_call = timed(make(), centres[:2])[0]
            for shape, poses in trajectories(centres).items():
                whole = [timed(make(), poses) for _ in range(args.repeat)]
                one = make()
                t0 = time.perf_counter()
                for pose in poses:
                    one.observe_xy(pose)
                per_pose = (time.perf_counter() - t0) / POSES
                rows.append((f"{scene} {number}", start, shape, whole[0][1],
                             statistics.median(t for t, _, _ in whole), per_pose,
                             statistics.median(w for _, _, w in whole)))
    print(f"Command: `.venv/bin/python benchmarks/monitor.py --repeat {args.repeat}`\n")
    print(f"First call of the process (kernel loaded from numba's cache or compiled): {first_call * 1e3:.1f} "
          "ms; not in the times below.\n")
    print("| mission | start | trajectory | cells read | one call, 10,000 poses (ms) | one call per pose "
          "(µs) | `left` in words, first read (ms) |")
    print("|---|---|---|---|---|---|---|")
    for name, start, shape, cells, whole_s, per_pose_s, words_s in rows:
        print(f"| {name} | {start} | {shape} | {cells:,} | {whole_s * 1e3:.2f} | {per_pose_s * 1e6:.1f} | "
              f"{words_s * 1e3:.1f} |")
    print("\n| trajectory | cases | cells read (median) | one call: median (ms) | max (ms) | cases over "
          "10 ms | per pose: median (µs) |")
    print("|---|---|---|---|---|---|---|")
    for shape in SHAPES:
        mine = [r for r in rows if r[2] == shape]
        times = [r[4] * 1e3 for r in mine]
        print(f"| {shape} | {len(mine)} | {statistics.median(r[3] for r in mine):,.0f} | "
              f"{statistics.median(times):.2f} | {max(times):.2f} | {sum(t > 10 for t in times)} | "
              f"{statistics.median(r[5] for r in mine) * 1e6:.0f} |")
    words = [r[6] * 1e3 for r in rows]
    print(f"\n`left` in words, first read per state: median {statistics.median(words):.1f} ms, "
          f"max {max(words):.1f} ms (then a look-up).")


if __name__ == "__main__":
    main()
