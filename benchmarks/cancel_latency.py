"""How long a plan takes to stop once another thread cancels it, on the shipped Gibson missions.

Per case (scene, mission, start, setup; authors profile, a one-off ``sgplan.plan`` as the CLI makes it,
composite action maps built lazily unless ``--prebuild``) one plan runs to the end to time it, then
``2 x --runs`` plans each get a :class:`~sgplan.planning.termination.CancelFlag` that a timer thread sets
at a random moment: half anywhere in that plan's time, half while it searches. Two latencies, from the
moment the timer was due: until the driver's poll saw the flag ("seen": the rest of the chunk running
then, and the timer thread's wait for the GIL where Python code holds it), and until ``plan`` returned
("returned": also the result built from the best path so far: path, waypoints, events, the mission's
explanation). A cancel that comes while the domain is being precomputed is seen when that step ends;
such runs are counted apart ("pre"). Prints per case how many runs were cancelled in the search, before
it, or not at all (the plan ended first: "late"), and the median and worst latencies in milliseconds.

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
    """One plan cancelled by a timer thread ``delay_s`` after it starts; what happened, and how long after
    the timer was due the driver saw the cancel and the plan returned."""
    import sgplan
    from sgplan.planning.termination import CancelFlag, Progress, Stop, Termination

    class Seen(Termination):
        """The cancel flag, noting when the driver's poll first found it set."""

        seen_at = 0.0

        def check(self, progress: Progress) -> Stop | None:
            stop = cancel.check(progress)
            if stop is not None and not self.seen_at:
                self.seen_at = time.perf_counter()
            return stop

    cancel, seen = CancelFlag(), Seen()
    timer = threading.Timer(delay_s, cancel.cancel)
    t0 = time.perf_counter()
    timer.start()
    result = sgplan.plan(building, mission, start, setup=setup, profile="authors", prebuild_actions=prebuild,
                         verify=False, termination=seen)
    ended = time.perf_counter()
    timer.cancel()
    due = t0 + delay_s
    return {"status": result.status, "seen_s": seen.seen_at - due, "returned_s": ended - due,
            "in_search": result.timings["search_s"] > 0.0, "wall_s": ended - t0, **result.timings}


def _stats(values: list[float]) -> str:
    """Median and worst of ``values``, or dashes for none."""
    return f"{statistics.median(values):>7.1f} {max(values):>7.1f}" if values else f"{'-':>7} {'-':>7}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--setups", nargs="+", default=["ALL"])
    parser.add_argument("--runs", type=int, default=12,
                        help="timers per case anywhere in the plan, and as many in its search")
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
    print(f"{'case':<26} {'plan s':>6} {'search':>6} {'pre':>4} {'late':>4} | search: {'seen ms':>15} "
          f"{'returned ms':>15} | pre: {'seen ms':>15}")
    print(f"{'':<26} {'':>6} {'':>6} {'':>4} {'':>4} |         {'med':>7} {'max':>7} {'med':>7} {'max':>7} |"
          f"      {'med':>7} {'max':>7}")
    for scene, number, start in CASES:
        building = sgplan.load_scene(root / scene)
        mission = sgplan.load_mission(root / scene / "missions" / str(number), profile="authors")
        for setup in args.setups:
            whole = cancelled_plan(building, mission, start, setup, args.prebuild, 1e6)  # never due
            in_search: list[dict] = []
            before: list[dict] = []
            late = 0
            # Half the timers anywhere in the plan, half while it searches (from the plan's own timings).
            search_from = whole["prepare_s"] + whole["precompute_s"]
            delays = [rng.uniform(0.0, whole["wall_s"]) for _ in range(args.runs)]
            delays += [search_from + rng.uniform(0.0, whole["search_s"]) for _ in range(args.runs)]
            for delay in delays:
                run = cancelled_plan(building, mission, start, setup, args.prebuild, delay)
                if run["status"] != "cancelled":
                    late += 1  # finished before the timer fired
                    continue
                (in_search if run["in_search"] else before).append(run)
            name = f"{scene} m{number} s{start} {setup}"
            counts = f"{whole['wall_s']:>6.2f} {len(in_search):>6} {len(before):>4} {late:>4}"
            print(f"{name:<26} {counts} |         {_stats([r['seen_s'] * 1e3 for r in in_search])} "
                  f"{_stats([r['returned_s'] * 1e3 for r in in_search])} |      "
                  f"{_stats([r['seen_s'] * 1e3 for r in before])}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
