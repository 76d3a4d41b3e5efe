"""Run a sweep: the cases not yet in the results store, on an executor, recording each as it finishes."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

from sgplan.bench.cases import Case
from sgplan.bench.results import RETRYABLE, ResultStore
from sgplan.runtime.process import raise_swallowed_interrupt


class Executor(Protocol):
    """Anything that runs cases and yields their result rows as they finish (see bench.executors)."""

    name: str

    def run(self, cases: Iterable[Case]) -> Iterator[dict[str, Any]]: ...


@dataclass
class SweepSummary:
    """What a call of :func:`run_sweep` did: cases in the sweep, already recorded (skipped), run now,
    statuses of the rows recorded now, the wall seconds of the call, and whether it was interrupted."""

    total: int
    skipped: int
    ran: int = 0
    statuses: dict[str, int] = field(default_factory=dict)
    wall_s: float = 0.0
    interrupted: bool = False


def pending_cases(cases: Sequence[Case], store: ResultStore, *, retry: bool = False) -> list[Case]:
    """The cases to run: those without a row in ``store`` (with ``retry``, also those whose last row
    is ``crashed`` or ``wall-timeout``)."""
    def todo(case: Case) -> bool:
        row = store.get(case.key)
        return row is None or (retry and row["status"] in RETRYABLE)

    return [case for case in cases if todo(case)]


def run_sweep(
    cases: Sequence[Case],
    store: ResultStore,
    executor: Executor,
    *,
    retry: bool = False,
    on_start: Callable[[int, int], None] | None = None,
    on_row: Callable[[dict[str, Any]], None] | None = None,
) -> SweepSummary:
    """Run the cases of ``cases`` that ``store`` lacks on ``executor``; append every row as it arrives.

    ``on_start(to_run, skipped)`` is called once before the first case, ``on_row(row)`` after each row
    is stored. An interrupt (KeyboardInterrupt) stops the executor's workers and propagates as
    :class:`SweepInterrupted` with the summary so far; every row stored before it stays, so calling
    again with the same cases runs only the rest. (A row stored in the instant before the interrupt may
    be missing from ``summary.ran``; the store is the truth.)
    """
    t0 = time.perf_counter()
    todo = pending_cases(cases, store, retry=retry)
    summary = SweepSummary(total=len(cases), skipped=len(cases) - len(todo))
    if on_start is not None:
        on_start(len(todo), summary.skipped)
    try:
        if todo:
            rows = executor.run(todo)
            try:
                for row in rows:
                    store.append(row)
                    summary.ran += 1
                    summary.statuses[row["status"]] = summary.statuses.get(row["status"], 0) + 1
                    if on_row is not None:
                        on_row(row)
                    raise_swallowed_interrupt()
            finally:
                # A generator executor stops its workers when closed (on an interrupt, or a failed append).
                close = getattr(rows, "close", None)
                if close is not None:
                    close()
    except KeyboardInterrupt as stop:
        summary.interrupted = True
        summary.wall_s = time.perf_counter() - t0
        raise SweepInterrupted(summary, getattr(stop, "signum", None)) from None
    summary.wall_s = time.perf_counter() - t0
    return summary


class SweepInterrupted(KeyboardInterrupt):
    """A sweep stopped by an interrupt; ``summary`` says what it did until then (``interrupted`` set),
    ``signum`` which signal stopped it if known."""

    def __init__(self, summary: SweepSummary, signum: int | None = None) -> None:
        super().__init__("sweep interrupted")
        self.summary = summary
        self.signum = signum
