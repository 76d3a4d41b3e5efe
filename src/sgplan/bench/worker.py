"""Run one benchmark case in this process and measure it (the child side of every executor).

``python -m sgplan.bench.worker`` reads ``{"case": {...}, "gallery_dir": str | null}`` as JSON on stdin
and writes one JSON object (the measurements, see :func:`measure`) as the last line of stdout. Each case
runs in a fresh process so that its peak memory (``ru_maxrss`` of this process) is its own and a crash
takes down nothing but the case.
"""

from __future__ import annotations

import contextlib
import json
import os
import resource
import sys
import threading
import time
import traceback
from pathlib import Path
from typing import Any

from sgplan.bench.cases import Case
from sgplan.errors import PlanningError, SgplanError

LEVELS = ("anchor", "occupancy", "object", "room", "floor")
"""Hierarchy levels, in the order of the ``exp_<level>`` result columns."""

MEASURED = (
    "status", "reason", "start_cell", "cost_m", "first_cost_m", "cost_ratio", "first_time_s",
    "optimal_time_s", "num_iterations", "expansions", *(f"exp_{level}" for level in LEVELS), "load_s",
    "precompute_s", "search_s", "peak_rss_mb", "guidance", "path_cells", "queues", "iterations", "gallery",
)
"""The fields :func:`measure` reports (``None`` where a case did not get that far)."""


def queue_level(queue: str) -> str:
    """The hierarchy level of a queue name such as ``"LLM/room"`` (``PlanResult.queues``)."""
    return queue.rsplit("/", 1)[-1]


def _peak_rss_mb() -> float:
    # Linux reports ru_maxrss in KiB.
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def measure(case: Case, gallery_dir: str | Path | None = None) -> dict[str, Any]:
    """Plan ``case`` and return its measurements (JSON-ready; the fields of :data:`MEASURED`).

    Never raises for a case that fails: a :class:`PlanningError` gives its status (``invalid-start``,
    ``infeasible``, ``error``) and message as ``reason``; any other exception gives ``error``.
    """
    t0 = time.perf_counter()
    out: dict[str, Any] = dict.fromkeys(MEASURED)
    out["status"] = "error"
    try:
        _plan_case(case, gallery_dir, out, t0)
    except PlanningError as error:
        out.update(status=error.status, reason=str(error))
    except SgplanError as error:
        out.update(status="error", reason=str(error))
    except Exception as error:  # noqa: BLE001 - a bug: recorded like a failure, with the traceback on stderr
        traceback.print_exc()
        out.update(status="error", reason=f"{type(error).__name__}: {error}")
    out["peak_rss_mb"] = _peak_rss_mb()
    return out


def _plan_case(case: Case, gallery_dir: str | Path | None, out: dict[str, Any], t0: float) -> None:
    import sgplan
    from sgplan.pipeline import finite_or_none, iteration_records

    building = sgplan.load_scene(case.scene_dir)
    mission = sgplan.load_mission(case.mission_dir, profile=case.profile)
    loaded_s = time.perf_counter() - t0
    # Unchecked: the bench measures the planner; the checker's agreement is tested in tests/planning.
    result = sgplan.plan(building, mission, case.start, setup=case.setup, profile=case.profile,
                         time_limit_s=case.time_limit_s, verify=False)
    its = result.iterations
    out.update(
        status=result.status,
        reason=None if result.status == "optimal" else "the search time limit ran out before the optimum",
        start_cell=list(result.start),
        # Rows guided by the offline fallback say so, so they are not mistaken for LLM guidance.
        guidance=result.guidance or "none",
        load_s=loaded_s + result.timings["prepare_s"],
        precompute_s=result.timings["precompute_s"],
        search_s=result.timings["search_s"],
        queues=list(result.queues),
        iterations=iteration_records(its),
        num_iterations=len(its),
        expansions=int(sum(its[-1].expansions)) if its else 0,
        cost_m=finite_or_none(result.cost_m),
        path_cells=None if result.path is None else len(result.path),
    )
    if its:
        out.update(first_time_s=its[0].time_s, first_cost_m=its[0].cost_m)
        for level in LEVELS:
            out[f"exp_{level}"] = sum(
                n for q, n in zip(result.queues, its[-1].expansions) if queue_level(q) == level
            )
    if result.status == "optimal" and its:
        out["optimal_time_s"] = its[-1].time_s
        out["cost_ratio"] = its[0].cost_m / result.cost_m if result.cost_m > 0 else 1.0
    if gallery_dir is not None and result.path is not None:
        out["gallery"] = [
            str(p) for p in result.draw(gallery_dir, stem=f"{case.slug}_floor", automaton=False)
        ]


PARENT_ENV = "SGPLAN_BENCH_PARENT"
"""Environment variable by which an executor tells its workers the pid of the process that runs them."""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    return True


def exit_when_orphaned(poll_s: float = 1.0) -> None:
    """Exit as soon as the process that runs this worker dies: workers run in their own session (a
    terminal's Ctrl-C goes to the sweep only), so nothing else would stop them if the sweep were killed
    outright. The executor's pid comes from ``$SGPLAN_BENCH_PARENT``, which also covers a sweep killed
    while this worker was still starting (and a wrapper command between the two)."""
    first_parent = os.getppid()
    sweep = int(os.environ.get(PARENT_ENV) or first_parent)

    def watch() -> None:
        while os.getppid() == first_parent and _alive(sweep):
            time.sleep(poll_s)
        os._exit(3)

    threading.Thread(target=watch, name="sgplan-orphan-watch", daemon=True).start()


def main() -> int:
    """Entry point of ``python -m sgplan.bench.worker`` (see the module docstring)."""
    exit_when_orphaned()
    request = json.loads(sys.stdin.read())
    case = Case.from_dict(request["case"])
    real_stdout = sys.stdout
    # Anything the planner or a library prints goes to stderr: stdout carries only the result line.
    with contextlib.redirect_stdout(sys.stderr):
        measured = measure(case, request.get("gallery_dir"))
    real_stdout.write(json.dumps(measured, allow_nan=False) + "\n")
    real_stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
