"""A bounded pool of plan workers: plans run off the event loop, a few at a time, and a request beyond
what the pool can take is turned away at once (503 with ``Retry-After``) instead of queueing without end.

Threads, not processes: a plan reads the scene's warm :class:`sgplan.Session` (grids, label masks,
action maps, distance fields: hundreds of MB on a Gibson scene) that a process would have to hold a copy
of. The event loop stays free while a plan runs because the plan holds the GIL only between its compiled
kernels (benchmarks/serve_load.py measures what ``explain`` and ``observe`` see meanwhile).
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from typing import TypeVar

from sgplan.serve.errors import HTTPProblem

T = TypeVar("T")


class WorkPool:
    """At most ``workers`` jobs run at once and ``backlog`` more wait; :meth:`run` refuses the rest.

    ``retry_after_s`` is what a refused client is told to wait (the ``Retry-After`` header).
    """

    def __init__(
        self, workers: int, backlog: int, *, retry_after_s: int = 1, name: str = "sgplan-plan"
    ) -> None:
        self.workers = workers
        self.backlog = backlog
        self.retry_after_s = retry_after_s
        self._executor = ThreadPoolExecutor(max_workers=workers, thread_name_prefix=name)
        self._slots = threading.BoundedSemaphore(workers + backlog)
        self._lock = threading.Lock()
        self.refused = 0
        self.in_flight = 0

    def submit(self, job: Callable[[], T]) -> Future[T]:
        """Start ``job`` on a worker (or queue it), or raise 503 when ``workers + backlog`` are taken.
        The slot is given back when the job ends, whether or not anyone still waits for it."""
        if not self._slots.acquire(blocking=False):
            with self._lock:
                self.refused += 1
            raise HTTPProblem(
                503,
                f"every plan worker is busy ({self.workers} planning, {self.backlog} waiting); retry in "
                f"{self.retry_after_s} s",
                retry_after_s=self.retry_after_s,
            )
        with self._lock:
            self.in_flight += 1
        try:
            future = self._executor.submit(job)
        except RuntimeError:  # the pool is shutting down
            self._release()
            raise HTTPProblem(503, "the server is shutting down", retry_after_s=self.retry_after_s) from None
        future.add_done_callback(lambda _: self._release())
        return future

    async def run(self, job: Callable[[], T]) -> T:
        """:meth:`submit` and await the result on the running event loop."""
        return await asyncio.wrap_future(self.submit(job))

    def _release(self) -> None:
        with self._lock:
            self.in_flight -= 1
        self._slots.release()

    def shutdown(self) -> None:
        """Wait for the running jobs; queued ones are dropped."""
        self._executor.shutdown(wait=True, cancel_futures=True)
