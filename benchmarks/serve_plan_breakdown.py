"""Where a warm one-shot ``plan`` request of the service spends its time, in process (no HTTP).

The server's own process set-up (:func:`sgplan.cli.prepare_own_process`), one :class:`MissionService` on
the scene; every (Gibson mission, initial position 0-4) pair that has a plan is planned once first
(warm: kernels loaded, the session's grid, labels and parts built). Then the plan worker's job of
``POST /api/plan`` (:func:`sgplan.serve.planning.plan_on_host`, the answer's dict and its JSON text, as
the route sends it) runs ``--repeat`` times over all pairs: the wall time per request (p50, p95, per
mission), the process's CPU time per request, and, in a second pass under cProfile, the cumulative time
per request of the planner's parts (a function's time includes the parts it calls; cProfile's own
overhead inflates them alike).

    .venv/bin/python benchmarks/serve_plan_breakdown.py --scene Benevolence --setup 'A*' --repeat 3

Needs the serve extra and the Gibson data.
"""

from __future__ import annotations

import argparse
import ast
import cProfile
import json
import os
import pstats
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

from sgplan.cli import prepare_own_process
from sgplan.datasets import find_gibson_root
from sgplan.errors import SgplanError
from sgplan.serve.config import ServeConfig
from sgplan.serve.models import PlanRequest
from sgplan.serve.planning import Budget, plan_on_host
from sgplan.serve.service import MissionService

PARTS = (
    ("staging (labels, problem, scene checks)", "api.py", "_stage"),
    ("  the problem's domain (h_LTL, reach)", "domain.py", "build_domain"),
    ("  scene checks from the start", "api.py", "_check_in_scene"),
    ("search (AMRA*, its memory, path rows)", "amra.py", "plan"),
    ("outputs (check, waypoints, events)", "api.py", "_add_outputs"),
    ("  dense waypoints", "waypoints.py", "path_waypoints"),
    ("  simplified waypoints", "result.py", "simplify_waypoints"),
    ("  independent path check", "checker.py", "check_path"),
    ("  events", "events.py", "path_events"),
    ("kernel cache probe", "jit.py", "announce_compile"),
    ("answer dict (PlanResult.to_dict)", "result.py", "to_dict"),
    ("answer JSON text", "__init__.py", "dumps"),
)


def plan_requests(scene: str, setup: str) -> list[tuple[str, PlanRequest]]:
    root = find_gibson_root()
    if root is None:
        raise SystemExit("the Gibson data is needed (see sgplan.datasets)")
    cases = []
    for folder in sorted((root / scene / "missions").iterdir(), key=lambda f: int(f.name)):
        formula = json.dumps(ast.literal_eval((folder / "GPT_LTL_formula.txt").read_text()))
        for k in range(5):
            body = {"scene": scene, "formula": formula, "start": {"index": k}, "options": {"setup": setup}}
            cases.append((f"{folder.name} (start {k})", PlanRequest.model_validate(body)))
    return cases


def answer(service: MissionService, request: PlanRequest) -> bytes:
    """What the plan route sends (without HTTP): the plan's dict as JSON text, as Starlette encodes it."""
    host = service.scenes[request.scene]
    understood = service.missions.understand(host, request, request.start.spec() if request.start else None)
    result = plan_on_host(host, understood, request.start, request.options, Budget.of(60.0))
    return json.dumps(result.to_dict(), ensure_ascii=False, allow_nan=False, indent=None,
                      separators=(",", ":")).encode()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="Benevolence")
    parser.add_argument("--setup", default="A*")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    prepare_own_process()
    service = MissionService.start(ServeConfig(scenes=(args.scene,), state_dir=Path(tempfile.mkdtemp())))
    cases = []
    for name, request in plan_requests(args.scene, args.setup):
        try:
            answer(service, request)
        except SgplanError:  # a start the mission forbids: a 422, not a plan
            continue
        cases.append((name, request))
    times: dict[str, list[float]] = {name: [] for name, _ in cases}
    cpu0 = time.process_time()
    for _ in range(args.repeat):
        for name, request in cases:
            t0 = time.perf_counter()
            answer(service, request)
            times[name].append(1000 * (time.perf_counter() - t0))
    cpu_ms = 1000 * (time.process_time() - cpu0) / (args.repeat * len(cases))
    every = [t for ts in times.values() for t in ts]
    print(f"Command: `.venv/bin/python benchmarks/serve_plan_breakdown.py --scene {args.scene} --setup "
          f"'{args.setup}' --repeat {args.repeat}`; load average {os.getloadavg()[0]:.1f} on "
          f"{os.cpu_count()} cores; {len(cases)} (mission, start) pairs with a plan\n")
    print(f"warm plan request in process: p50 {statistics.median(every):.1f} ms, "
          f"p95 {statistics.quantiles(every, n=20)[-1]:.1f} ms over {len(every)} requests; CPU time of the "
          f"process {cpu_ms:.1f} ms per request (less sensitive to the machine's load than wall time)\n")
    print("| mission | p50 ms |\n|---|---|")
    for name, ts in times.items():
        print(f"| {name} | {statistics.median(ts):.1f} |")
    profile = cProfile.Profile()
    profile.enable()
    for _, request in cases:
        answer(service, request)
    profile.disable()
    stats: Any = pstats.Stats(profile).stats
    print(f"\nunder cProfile, one pass over the {len(cases)} pairs: cumulative ms per request\n")
    print("| part | ms per request |\n|---|---|")
    for label, file, function in PARTS:
        total = sum(v[3] for (f, _, fn), v in stats.items() if f.endswith(file) and fn == function)
        print(f"| {label} | {1000 * total / len(cases):.1f} |")


if __name__ == "__main__":
    main()
