"""How long a plan takes to stop once another thread cancels it, on the shipped Gibson missions.

Per case (scene, mission, start, setup; authors profile, a one-off ``sgplan.plan`` as the CLI makes it,
composite action maps built lazily unless ``--prebuild``) one plan runs to the end to time it, then
``--runs`` plans each get a :class:`~sgplan.planning.termination.CancelFlag` that a timer thread sets at a
random moment of that time. The latency is from the moment the timer was due to the moment ``plan``
returned: the wait for the GIL (the compiled search holds it during a chunk), the rest of the chunk, and
the return with the best path so far. A cancel that comes while the domain is being precomputed takes
effect when that step ends; such runs are counted apart ("pre"). Prints per case the runs cancelled in
the search and before it, and the median and worst latency of each (milliseconds).

    .venv/bin/python benchmarks/cancel_latency.py                       # the four reference cases, ALL
    .venv/bin/python benchmarks/cancel_latency.py --setups ALL A* --runs 20 --prebuild
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import threading
import time

CASES = (("Allensville", 1, 0), ("Benevolence", 1, 0), ("Benevolence", 4, 0), ("Collierville", 1, 0))


def cancelled_plan(building, mission, start: int, setup: str, prebuild: bool, delay_s: float) -> dict:
    """One plan cancelled by a timer thread ``delay_s`` after it starts; what happened and how long the
    plan ran past the moment the timer was due."""
    import sgplan
    from sgplan.planning.termination import CancelFlag

    cancel = CancelFlag()
    timer = threading.Timer(delay_s, cancel.cancel)
    t0 = time.perf_counter()
    timer.start()
    result = sgplan.plan(building, mission, start, setup=setup, profile="authors", prebuild_actions=prebuild,
                         verify=False, termination=cancel)
    ended = time.perf_counter()
    timer.cancel()
    return {"status": result.status, "latency_s": ended - (t0 + delay_s),
            "in_search": result.timings["search_s"] > 0.0, "wall_s": ended - t0}


def _stats(values: list[float]) -> str:
    """Median and worst of ``values``, or dashes for none."""
    return f"{statistics.median(values):>7.1f} {max(values):>7.1f}" if values else f"{'-':>7} {'-':>7}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--setups", nargs="+", default=["ALL"])
    parser.add_argument("--runs", type=int, default=12, help="cancelled plans per case")
    parser.add_argument("--prebuild", action="store_true", help="build the action maps before the search")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    import sgplan
    from sgplan.datasets import find_gibson_root

    root = find_gibson_root()
    if root is None:
        print("cancel_latency: the Gibson data is not found (see sgplan.datasets)", file=sys.stderr)
        return 2
    rng = random.Random(args.seed)
    print(f"{'case':<28} {'plan s':>7} {'search':>6} {'pre':>4} {'late':>5} {'search ms med':>13} {'max':>7} "
          f"{'pre ms med':>10} {'max':>7}")
    for scene, number, start in CASES:
        building = sgplan.load_scene(root / scene)
        mission = sgplan.load_mission(root / scene / "missions" / str(number), profile="authors")
        for setup in args.setups:
            whole = cancelled_plan(building, mission, start, setup, args.prebuild, 1e6)  # never due
            in_search, before, late = [], [], 0
            for _ in range(args.runs):
                run = cancelled_plan(building, mission, start, setup, args.prebuild,
                                     rng.uniform(0.0, whole["wall_s"]))
                if run["status"] != "cancelled":
                    late += 1  # finished before the timer fired
                    continue
                (in_search if run["in_search"] else before).append(run["latency_s"] * 1e3)
            name = f"{scene} m{number} s{start} {setup}"
            print(f"{name:<28} {whole['wall_s']:>7.2f} {len(in_search):>6} {len(before):>4} {late:>5} "
                  f"      {_stats(in_search)}    {_stats(before)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
