"""What a plan in a worker thread costs the thread beside it: the GIL held by the planner's kernels.

A service plans in worker threads while its event loop and request threads answer ``explain`` and
``observe``. Here one thread plans each Gibson mission of ``--scene`` from its first plannable start,
warm (a kept Session, every plan made once first), while the main thread ticks: ``time.sleep(1 ms)`` in
a loop, noting each gap between two ticks. A kernel that holds the GIL makes the ticker wait until it
returns; one compiled with ``nogil=True`` does not. Reported per plan: its wall time, the ticker's gap
p50 / max and ticks, and a digest of the result (status, cost, path) so two builds can be compared for
identical search results.

    .venv/bin/python benchmarks/plan_beside.py --scene Benevolence --setups "A*" ALL

Needs the Gibson data.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import sys
import threading
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import sgplan
from sgplan.datasets import find_gibson_root
from sgplan.errors import PlanningError


def ticked(work: object) -> tuple[float, np.ndarray]:
    """Run ``work()`` in a thread; the seconds it took and the gaps (s) between the main thread's ticks."""
    done = threading.Event()
    gaps: list[float] = []

    def run() -> None:
        work()  # type: ignore[operator]
        done.set()

    thread = threading.Thread(target=run)
    t0 = last = time.perf_counter()
    thread.start()
    while not done.is_set():
        time.sleep(0.001)
        now = time.perf_counter()
        gaps.append(now - last)
        last = now
    thread.join()
    return time.perf_counter() - t0, np.array(gaps)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="Benevolence")
    parser.add_argument("--setups", nargs="+", default=["A*", "ALL"])
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        raise SystemExit("the Gibson data is needed")
    session = sgplan.Session(sgplan.load_scene(args.scene))
    print(
        f"Command: `.venv/bin/python benchmarks/plan_beside.py {' '.join(sys.argv[1:])}`; "
        f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores\n"
    )
    print("| mission | setup | plan ms | ticker gap p50 ms | max ms | ticks | result digest |")
    print("|---|---|---|---|---|---|---|")
    for folder in sorted((root / args.scene / "missions").iterdir()):
        mission = sgplan.load_mission(folder)
        for setup in args.setups:
            start = None
            for k in range(5):
                try:
                    session.plan(mission, k, setup=setup)  # warm: parts built, kernels loaded
                    start = k
                    break
                except PlanningError:
                    continue
            if start is None:
                continue
            box: list[sgplan.PlanResult] = []
            seconds, gaps = ticked(lambda: box.append(session.plan(mission, start, setup=setup)))  # noqa: B023
            result = box[0]
            digest = hashlib.sha256(np.ascontiguousarray(result.path).tobytes()).hexdigest()[:12]
            print(
                f"| {folder.name} (start {start}) | {setup} | {1000 * seconds:.0f} | "
                f"{1000 * np.median(gaps):.1f} | {1000 * gaps.max():.1f} | {len(gaps)} | "
                f"{result.status} {result.cost_m:.6f} m {digest} |"
            )
    print(f"\nload average at the end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
