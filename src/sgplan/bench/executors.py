"""Executors: run cases in worker processes, locally or on Ray; yield result rows.

Every case runs in a ``python -m sgplan.bench.worker`` process apart from the sweep (crash isolation),
killed after the per-case wall timeout. The local executor keeps ``jobs`` long-lived workers
(:mod:`sgplan.bench.serving`) that run case after case, and replaces one only after a crash or a timeout;
with ``reuse_workers=False``, and on Ray, each case gets a fresh process (:func:`run_isolated`). An
executor's :meth:`run` is a generator of rows in completion order; closing it (an interrupt) kills the
running workers and records nothing for them.
"""

from __future__ import annotations

import json
import os
import queue
import shlex
import shutil
import subprocess
import sys
import threading
import time
from collections.abc import Iterable, Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor, as_completed
from pathlib import Path
from typing import Any

from sgplan.bench.cases import BenchError, Case
from sgplan.bench.results import failed_row, make_row
from sgplan.bench.serving import ServingWorker, death, peak_rss_of
from sgplan.bench.worker import PARENT_ENV

DEFAULT_CASE_TIMEOUT_S = 600.0


WORKER_ENV = "SGPLAN_BENCH_WORKER"
"""Environment variable that replaces the worker command (shell words), e.g. to pin workers to cores
(``taskset -c 1 python -m sgplan.bench.worker``) or to profile them."""


def worker_command() -> list[str]:
    """The worker command: ``$SGPLAN_BENCH_WORKER`` split into shell words if set, else this
    interpreter running :mod:`sgplan.bench.worker`."""
    custom = os.environ.get(WORKER_ENV, "").strip()
    if custom:
        try:
            words = shlex.split(custom)
        except ValueError as exc:
            raise BenchError(f"${WORKER_ENV}={custom!r} is not a valid command line: {exc}") from None
        if shutil.which(words[0]) is None:
            raise BenchError(f"${WORKER_ENV}: cannot find the program {words[0]!r}")
        return words
    return [sys.executable, "-m", "sgplan.bench.worker"]


def _worker_env() -> dict[str, str]:
    env = dict(os.environ)
    env[PARENT_ENV] = str(os.getpid())  # the worker exits if this process dies
    # One case per core: keep numeric libraries from starting their own thread pools in each worker.
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
        env[name] = "1"
    # The worker must import the same sgplan as this process (also from a source checkout).
    source = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = os.pathsep.join(filter(None, (source, env.get("PYTHONPATH"))))
    return env


def run_isolated(
    case: Case,
    *,
    timeout_s: float = DEFAULT_CASE_TIMEOUT_S,
    gallery_dir: str | None = None,
    command: Sequence[str] | None = None,
    executor: str = "local",
    running: set[subprocess.Popen] | None = None,
    cancel: threading.Event | None = None,
) -> dict[str, Any]:
    """Run ``case`` in a fresh worker process and return its result row (never raises for the case).

    Parameters
    ----------
    timeout_s:
        wall seconds after which the worker is killed and the row gets status ``wall-timeout``.
    command:
        the worker command (default :func:`worker_command`); it reads the request JSON on stdin and
        prints the measurements as its last stdout line.
    running, cancel:
        for a local executor: the live process is kept in ``running`` while it runs, and killed at once
        if ``cancel`` is set.
    """
    request = json.dumps({"case": case.to_dict(), "gallery_dir": gallery_dir})
    t0 = time.perf_counter()
    argv = list(command or worker_command())
    try:
        proc = subprocess.Popen(
            argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
            env=_worker_env(),
            start_new_session=True,  # a terminal Ctrl-C reaches the sweep, which then stops the workers
        )
    except OSError as error:  # every case would fail the same way: stop the sweep
        raise BenchError(f"cannot start the worker {argv[0]!r}: {error.strerror or error}") from None
    if running is not None:
        running.add(proc)
    try:
        if cancel is not None and cancel.is_set():
            proc.kill()
        try:
            stdout, stderr = proc.communicate(request, timeout=timeout_s)
        except subprocess.TimeoutExpired:
            rss = peak_rss_of(proc.pid)
            proc.kill()
            proc.communicate()
            return failed_row(
                case,
                "wall-timeout",
                f"killed after the per-case wall timeout of {timeout_s:g} s",
                wall_s=time.perf_counter() - t0,
                executor=executor,
                peak_rss_mb=rss,
            )
    finally:
        if running is not None:
            running.discard(proc)
    wall_s = time.perf_counter() - t0
    lines = stdout.strip().splitlines()
    if proc.returncode == 0 and lines:
        try:
            measured = json.loads(lines[-1])
        except json.JSONDecodeError:
            measured = None
        if isinstance(measured, dict) and "status" in measured:
            return make_row(case, measured, wall_s=wall_s, executor=executor)
    return failed_row(case, "crashed", death(proc.returncode, stderr), wall_s=wall_s, executor=executor)


class LocalExecutor:
    """Run cases on this machine, ``jobs`` at a time (default: one per core), in ``jobs`` long-lived
    worker processes (``reuse_workers``, the default; a worker's command gets ``--serve``) or in a fresh
    process per case (then each case's peak memory is its process's alone, and it is slower)."""

    name = "local"

    def __init__(self, jobs: int | None = None, *, timeout_s: float = DEFAULT_CASE_TIMEOUT_S,
                 gallery_dir: str | None = None, command: Sequence[str] | None = None,
                 reuse_workers: bool = True) -> None:
        self.jobs = max(1, jobs or os.cpu_count() or 1)
        self.timeout_s = timeout_s
        self.gallery_dir = gallery_dir
        self.command = list(command) if command else worker_command()
        self.reuse_workers = reuse_workers
        self.workers_started = 0
        """Worker processes started by the last :meth:`run` (long-lived mode)."""

    def run(self, cases: Iterable[Case]) -> Iterator[dict[str, Any]]:
        """Rows of ``cases`` as they finish."""
        running: set[subprocess.Popen] = set()
        idle: queue.SimpleQueue[ServingWorker] = queue.SimpleQueue()
        live: set[ServingWorker] = set()
        cancel = threading.Event()
        self.workers_started = 0

        def serve(case: Case) -> dict[str, Any]:
            try:
                worker = idle.get_nowait()
            except queue.Empty:
                worker = ServingWorker(self.command, _worker_env())
                live.add(worker)
                self.workers_started += 1
            row, healthy = worker.run(case, timeout_s=self.timeout_s, gallery_dir=self.gallery_dir,
                                      executor=self.name, cancel=cancel)
            if healthy and not cancel.is_set():
                idle.put(worker)
            else:  # crashed, timed out or stopped: never asked again
                live.discard(worker)
                worker.kill()
            return row

        def isolated(case: Case) -> dict[str, Any]:
            return run_isolated(case, timeout_s=self.timeout_s, gallery_dir=self.gallery_dir,
                                command=self.command, executor=self.name, running=running, cancel=cancel)

        pool = ThreadPoolExecutor(max_workers=self.jobs, thread_name_prefix="sgplan-bench")
        futures = [pool.submit(serve if self.reuse_workers else isolated, case) for case in cases]
        try:
            for future in as_completed(futures):
                yield future.result()
        finally:
            cancel.set()
            pool.shutdown(wait=False, cancel_futures=True)
            for proc in list(running):
                proc.kill()
            for worker in list(live):
                worker.kill()  # idle ones hold nothing of value; busy ones are stopped (not recorded)
            pool.shutdown(wait=True)


class RayExecutor:
    """Run cases as Ray tasks (one CPU each), on a local Ray started with ``jobs`` CPUs or on the cluster
    at ``address``. Every node needs sgplan installed and the data folder at the same path.

    An already initialised Ray (e.g. ``ray.init(num_cpus=2)`` by the caller) is used as it is.
    """

    name = "ray"

    def __init__(self, jobs: int | None = None, *, address: str | None = None,
                 timeout_s: float = DEFAULT_CASE_TIMEOUT_S, gallery_dir: str | None = None,
                 command: Sequence[str] | None = None) -> None:
        self.jobs = jobs if jobs or address else os.cpu_count()  # None: whatever the cluster offers
        self.address = address
        self.timeout_s = timeout_s
        self.gallery_dir = gallery_dir
        self.command = list(command) if command else worker_command()

    def run(self, cases: Iterable[Case]) -> Iterator[dict[str, Any]]:
        """Rows of ``cases`` as they finish."""
        try:
            import ray
        except ImportError:
            raise BenchError("the Ray executor needs Ray: pip install 'sgplan[ray]'") from None
        started = not ray.is_initialized()
        if started:
            try:
                if self.address:
                    ray.init(address=self.address, log_to_driver=False)
                else:
                    ray.init(num_cpus=self.jobs, include_dashboard=False, log_to_driver=False)
            except (ConnectionError, RuntimeError, ValueError, TimeoutError) as error:
                where = f"the Ray cluster at {self.address}" if self.address else "a local Ray"
                raise BenchError(f"cannot start {where}: {error}") from None
        task = ray.remote(num_cpus=1, max_retries=0)(run_isolated)
        pending = {
            task.remote(case, timeout_s=self.timeout_s, gallery_dir=self.gallery_dir, command=self.command,
                        executor=self.name): case
            for case in cases
        }
        try:
            while pending:
                (ref,), _ = ray.wait(list(pending), num_returns=1)
                case = pending.pop(ref)
                try:
                    yield ray.get(ref)
                except ray.exceptions.RayError as error:  # the Ray worker or its node died
                    yield failed_row(
                        case, "crashed", f"the Ray task failed: {error}", wall_s=None, executor=self.name
                    )
        finally:
            for ref in pending:
                ray.cancel(ref, force=True)
            if started:
                ray.shutdown()
