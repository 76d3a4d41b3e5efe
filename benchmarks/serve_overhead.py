"""What the service adds to the library's own work, in process (no HTTP): a replan after a change, a pose
report, a one-shot plan.

For each pair the same work is done alternately through the library (``Run.change`` + ``Run.plan``,
``Run.observe``, ``Session.plan``) and through the service's calls (:class:`sgplan.serve.service.
MissionService`: the plan pool's thread, the run's lock, the database transaction, the answer's dict),
on the same scene and warm; the medians and their difference are reported. The HTTP layer's share is in
``benchmarks/serve_load.py``'s numbers (the same requests over loopback).

    .venv/bin/python benchmarks/serve_overhead.py --scene Benevolence --repeat 30

Needs the serve extra and the Gibson data.
"""

from __future__ import annotations

import argparse
import ast
import asyncio
import json
import os
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from sgplan.datasets import find_gibson_root
from sgplan.errors import SgplanError
from sgplan.serve.config import ServeConfig
from sgplan.serve.models import ChangesRequest, ObserveRequest, PlanRequest, RunRequest
from sgplan.serve.service import MissionService


def timed(work: Callable[[], Any]) -> float:
    t0 = time.perf_counter()
    work()
    return 1000 * (time.perf_counter() - t0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="Benevolence")
    parser.add_argument("--mission", default="1")
    parser.add_argument("--repeat", type=int, default=30)
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        raise SystemExit("the Gibson data is needed")
    formula = json.dumps(
        ast.literal_eval((root / args.scene / "missions" / args.mission / "GPT_LTL_formula.txt").read_text())
    )
    service = MissionService.start(ServeConfig(scenes=(args.scene,), state_dir=Path(tempfile.mkdtemp())))
    loop = asyncio.new_event_loop()
    service.runs.attach_loop(loop)
    body = {"scene": args.scene, "formula": formula, "start": {"index": 0}, "options": {"setup": "A*"}}
    answer = loop.run_until_complete(service.runs.create(RunRequest.model_validate(body)))
    live = service.runs._runs[answer["id"]]
    doors = [d["rooms"] for d in service.scenes[args.scene].doors]
    host = service.scenes[args.scene]
    understood = service.missions.understand(host, PlanRequest.model_validate(body))
    waypoints = answer["plan"]["waypoints"]
    poses = [[w["x_m"], w["y_m"], w["floor"]] for w in waypoints[1:101]]
    rows: dict[str, tuple[list[float], list[float]]] = {
        k: ([], []) for k in ("change + replan", "observe", "plan")
    }
    run = live.run
    assert run is not None

    def library(kind: str, rooms: list[str]) -> None:
        run.change([{"kind": kind, "rooms": rooms}])
        run.plan  # noqa: B018 - reading it replans

    def served(kind: str, rooms: list[str]) -> None:
        loop.run_until_complete(
            service.runs.change(live.id, ChangesRequest(changes=[{"kind": kind, "rooms": rooms}]))
        )

    usable = []
    for door in doors:  # warm, and leave out the doors a change may not touch (the robot stands in one)
        try:
            library("close_door", door)
        except SgplanError:
            continue
        library("open_door", door)
        usable.append(door)
    doors = usable
    standing = ObserveRequest(poses=poses[:1] * 100)  # the robot stands still: the run stays as it is
    plan_body = PlanRequest.model_validate(body)
    for k in range(args.repeat):
        door = doors[k % len(doors)]
        rows["change + replan"][0].append(timed(lambda door=door: library("close_door", door)))
        library("open_door", door)
        rows["change + replan"][1].append(timed(lambda door=door: served("close_door", door)))
        served("open_door", door)
        rows["observe"][0].append(timed(lambda: run.observe(standing.poses)))
        rows["observe"][1].append(timed(lambda: service.runs.observe(live.id, standing)))
        rows["plan"][0].append(
            timed(
                lambda: host.session.plan(
                    understood.mission, 0, setup="A*", explanation=understood.explanation
                )
            )
        )
        rows["plan"][1].append(timed(lambda: loop.run_until_complete(service.plan(plan_body))))
    print(
        f"Command: `.venv/bin/python benchmarks/serve_overhead.py {' '.join(sys.argv[1:])}`; mission "
        f"{args.mission}; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores\n"
    )
    print("| work | library p50 ms | service p50 ms | service overhead ms |")
    print("|---|---|---|---|")
    for name, (library_ms, service_ms) in rows.items():
        a, b = statistics.median(library_ms), statistics.median(service_ms)
        print(f"| {name} | {a:.1f} | {b:.1f} | {b - a:+.1f} |")
    service.close()


if __name__ == "__main__":
    main()
