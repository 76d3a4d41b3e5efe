"""Run benchmark cases in this process and measure them (the child side of every executor).

``python -m sgplan.bench.worker`` reads one request ``{"case": {...}, "gallery_dir": str | null}`` as JSON
on stdin and writes one JSON object (the measurements, see :func:`measure`) as the last line of stdout.

``python -m sgplan.bench.worker --serve`` is a long-lived worker: it reads requests one per line and
answers each with one line, until stdin closes; the local executor keeps one per job and starts a fresh one
only after a crash or a wall timeout (a crash still takes down nothing but its case). It keeps the last
scene's :class:`sgplan.Session` (building, grids, label masks, action maps, distance fields) for the next
cases of the same scene, and
resets the kernel's peak-memory mark before every case (Linux), so ``peak_rss_mb`` is the peak during the
case (which includes what the process already holds: interpreter, libraries, the kept scene).
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
from sgplan.planning.setups import LEVEL_NAMES, get_setup

MEASURED = (
    "status", "reason", "start_cell", "cost_m", "first_cost_m", "cost_ratio", "first_time_s",
    "optimal_time_s", "num_iterations", "expansions", *(f"exp_{level}" for level in LEVEL_NAMES), "load_s",
    "precompute_s", "search_s", "peak_rss_mb", "guidance", "path_cells", "scene_reused", "ltlf_accepts",
    "queues", "iterations", "gallery", "ltlf_violations",
)
"""The fields :func:`measure` reports (``None`` where a case did not get that far). ``scene_reused``: the
worker kept the scene's session (building, grids, action maps, distance fields) from an earlier case;
``ltlf_accepts`` / ``ltlf_violations``: an ``authors`` path read under ``ltlf``
(:mod:`sgplan.bench.ltlf_check`)."""


def _peak_rss_mb() -> float:
    """Peak resident memory (MiB) since the last :func:`reset_peak_rss` (Linux), else of the process."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except (OSError, ValueError, IndexError):
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB; the whole process


def reset_peak_rss() -> bool:
    """Reset this process's peak-memory mark to its current size (Linux >= 4.0: ``/proc/self/clear_refs``);
    returns whether it could."""
    try:
        with open("/proc/self/clear_refs", "w") as refs:
            refs.write("5")
        return True
    except OSError:
        return False


class SceneKeeper:
    """The :class:`sgplan.Session` of the last scene folder asked for: consecutive cases of one scene
    share its building, grids, label masks, action maps and h_LTL distance fields (only one scene is kept,
    and its session's planner parts are capped by bytes, so memory stays one scene's)."""

    def __init__(self) -> None:
        self.folder: str | None = None
        self.session: Any = None
        self.loads = 0

    def session_for(self, folder: str) -> Any:
        import sgplan

        if folder != self.folder:
            self.folder, self.session = None, None  # the old scene is freed before the new one loads
            self.session = sgplan.Session(sgplan.load_scene(folder))
            self.folder = folder
            self.loads += 1
        return self.session


def measure(case: Case, gallery_dir: str | Path | None = None, scenes: SceneKeeper | None = None
            ) -> dict[str, Any]:
    """Plan ``case`` and return its measurements (JSON-ready; the fields of :data:`MEASURED`).

    Never raises for a case that fails: a :class:`PlanningError` gives its status (``invalid-start``,
    ``infeasible``, ``error``) and message as ``reason``; any other exception gives ``error``. With
    ``scenes``, the building comes from (and stays in) it.
    """
    t0 = time.perf_counter()
    out: dict[str, Any] = dict.fromkeys(MEASURED)
    out["status"] = "error"
    try:
        _plan_case(case, gallery_dir, out, t0, scenes or SceneKeeper())
    except PlanningError as error:
        out.update(status=error.status, reason=str(error))
    except SgplanError as error:
        out.update(status="error", reason=str(error))
    except Exception as error:  # noqa: BLE001 - a bug: recorded like a failure, with the traceback on stderr
        traceback.print_exc()
        out.update(status="error", reason=f"{type(error).__name__}: {error}")
    out["peak_rss_mb"] = _peak_rss_mb()
    return out


def _plan_case(case: Case, gallery_dir: str | Path | None, out: dict[str, Any], t0: float,
               scenes: SceneKeeper) -> None:
    import sgplan
    from sgplan.outputs.jsontext import finite_or_none, iteration_records

    out["scene_reused"] = scenes.folder == case.scene_dir
    session = scenes.session_for(case.scene_dir)
    mission = sgplan.load_mission(case.mission_dir, profile=case.profile)
    loaded_s = time.perf_counter() - t0
    # Unchecked: the bench measures the planner; the checker's agreement is tested in tests/planning.
    # Action maps built before the search clock starts: the paper's accounting of first-path times.
    options = sgplan.PlanOptions(setup=case.setup, profile=case.profile, reach_model=case.reach_model,
                                 time_limit_s=case.time_limit_s, verify=False, prebuild_actions=True)
    result = session.plan(mission, case.start, options=options)
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
        by_level = get_setup(case.setup).expansions_by_level(its[-1].expansions)
        out.update({f"exp_{level}": n for level, n in by_level.items()})
    if result.status == "optimal" and its:
        out["optimal_time_s"] = its[-1].time_s
        out["cost_ratio"] = its[0].cost_m / result.cost_m if result.cost_m > 0 else 1.0
    if case.profile == "authors" and result.path is not None:
        out.update(_ltlf_reading(case, result))
    if gallery_dir is not None and result.path is not None:
        pictures = result.draw(gallery_dir, stem=f"{case.slug}_floor", formats=("png",), automaton=False)
        out["gallery"] = [str(p) for p in pictures]


def _ltlf_reading(case: Case, result: Any) -> dict[str, Any]:
    """``ltlf_accepts`` and ``ltlf_violations`` of an ``authors`` path (:func:`ltlf_reading`)."""
    import numpy as np

    import sgplan
    from sgplan.bench.ltlf_check import ltlf_reading
    from sgplan.explain.referents import referents_of
    from sgplan.outputs.waypoints import leg_costs

    path, authors = result.path, result.mission.automaton
    ltlf = sgplan.load_mission(case.mission_dir, profile="ltlf", guidance=False).automaton
    entities = referents_of(list(authors.aps), result.mission.propositions, result.building)
    costs = np.concatenate([[0.0], np.cumsum(leg_costs(path, result.grid))])
    labels = result.labels[path[:, 2], path[:, 0], path[:, 1]]
    accepts, violations = ltlf_reading(path, labels, costs, authors, ltlf, lambda p: entities[p].phrase())
    return {"ltlf_accepts": accepts, "ltlf_violations": [v.to_dict() for v in violations]}


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


SERVE_FLAG = "--serve"
"""Argument that makes the worker long-lived (one request per stdin line, one answer per stdout line)."""


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``python -m sgplan.bench.worker [--serve]`` (see the module docstring)."""
    exit_when_orphaned()
    serve = SERVE_FLAG in (sys.argv[1:] if argv is None else argv)
    requests = iter(sys.stdin.readline, "") if serve else iter([sys.stdin.read()])
    real_stdout = sys.stdout
    if serve:
        # Answers get a private copy of stdout and file descriptor 1 becomes stderr, so that nothing else
        # (compiled code writing to fd 1 included) can put a line between two answers.
        sys.stdout.flush()
        real_stdout = os.fdopen(os.dup(1), "w")
        os.dup2(2, 1)
    scenes = SceneKeeper()
    # Anything the planner or a library prints goes to stderr: stdout carries only the result lines.
    with contextlib.redirect_stdout(sys.stderr):
        for text in requests:
            if not text.strip():
                continue
            request = json.loads(text)
            reset_peak_rss()
            measured = measure(Case.from_dict(request["case"]), request.get("gallery_dir"), scenes)
            real_stdout.write(json.dumps(measured, allow_nan=False) + "\n")
            real_stdout.flush()
    return 0


if __name__ == "__main__":
    from sgplan.runtime.process import exit_now, prepare_own_process

    prepare_own_process()  # a process of sgplan's own (no BLAS probe, fewer garbage-collector passes)
    exit_now(main())  # results are written: skip the interpreter's teardown
