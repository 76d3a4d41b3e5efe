"""Termination conditions (time, expansions, deadline, cancel, any of them) and how the AMRA* driver polls
them: exact expansion limits, a cancel from a second thread taking effect within one chunk, the best path
so far kept, nothing built when stopped before the start."""

from __future__ import annotations

import threading
import time
from functools import lru_cache

import numpy as np
import pytest

import sgplan
from sgplan.errors import PlanningError
from sgplan.planning import PlanningProblem, plan
from sgplan.planning.amra import CHUNK_EXPANSIONS
from sgplan.planning.checker import check_path
from sgplan.planning.termination import (
    AnyOf,
    CancelFlag,
    Deadline,
    ExpansionLimit,
    Progress,
    Stop,
    Termination,
    TimeLimit,
    any_of,
)

from .instances import automaton, open_building, open_grid


class Watch(Termination):
    """Never stops; remembers every progress it is shown (and runs ``on_poll`` on each)."""

    def __init__(self, on_poll=None) -> None:
        self.seen: list[Progress] = []
        self.on_poll = on_poll

    def check(self, progress: Progress) -> Stop | None:
        self.seen.append(progress)
        if self.on_poll is not None:
            self.on_poll(progress)
        return None


def _detour(n: int = 300) -> PlanningProblem:
    """An open n x n hall, a goal across a band the mission forbids (open at one end): tens of chunks of
    search to the optimum, the first path within the first chunks."""
    building = open_building(rows=n, cols=n)
    grid = open_grid(building)
    labels = np.zeros(grid.shape, dtype=np.uint32)
    labels[0, n - 3, n // 2] = 1  # p0, the goal
    labels[0, n // 2, : n - 4] = 2  # p1, a band to avoid
    return PlanningProblem(building, grid, labels, automaton("F p0 & G !p1", ("p0", "p1")), (2, n // 2, 0))


@lru_cache(maxsize=1)
def _full_search() -> tuple[int, float]:
    """Expansions and cost of the detour problem searched to the optimum (A*)."""
    watch = Watch()
    result = plan(_detour(), "A*", termination=watch)
    return watch.seen[-1].expansions, result.cost_m


# -- the conditions --------------------------------------------------------------------------------------


def test_each_condition_fires_at_its_limit_with_its_status_and_reason() -> None:
    assert TimeLimit(2.0).check(Progress(search_s=1.9)) is None
    ran_out = Stop("timeout", "the search time limit of 2 s ran out")
    assert TimeLimit(2.0).check(Progress(search_s=2.0)) == ran_out
    assert ExpansionLimit(10).check(Progress(expansions=9)) is None
    assert ExpansionLimit(10).check(Progress(expansions=10)).status == "timeout"
    assert ExpansionLimit(10).expansions_left(Progress(expansions=4)) == 6
    assert ExpansionLimit(10).expansions_left(Progress(expansions=40)) == 0
    assert Deadline.after(60).check(Progress()) is None
    assert Deadline(time.monotonic() - 1).check(Progress()) == Stop("timeout", "the deadline passed")
    flag = CancelFlag()
    assert flag.check(Progress()) is None and not flag.cancelled
    flag.cancel("the user pressed stop")
    assert flag.cancelled and flag.check(Progress()) == Stop("cancelled", "the user pressed stop")


@pytest.mark.parametrize("bad", [lambda: TimeLimit(-1.0), lambda: TimeLimit(float("nan")),
                                 lambda: ExpansionLimit(-1), lambda: ExpansionLimit(2.5),  # type: ignore[arg-type]
                                 lambda: ExpansionLimit(True), lambda: Deadline.after(float("inf"))])
def test_a_bad_limit_is_refused_with_what_is_allowed(bad) -> None:
    with pytest.raises(PlanningError, match=">= 0"):
        bad()


def test_any_of_stops_at_the_first_that_fires_and_counts_the_fewest_expansions_left() -> None:
    flag = CancelFlag()
    either = TimeLimit(5.0) | ExpansionLimit(100) | flag
    assert isinstance(either, AnyOf) and len(either.conditions) == 3  # flat, not nested
    assert either.check(Progress(search_s=1.0, expansions=50)) is None
    assert either.check(Progress(search_s=6.0, expansions=500)).reason.startswith("the search time limit")
    assert either.check(Progress(search_s=1.0, expansions=500)).reason == "the expansion limit of 100 ran out"
    flag.cancel()
    assert either.check(Progress(search_s=1.0)).status == "cancelled"
    assert either.check(Progress(search_s=6.0)).status == "timeout"  # both fire: the first in order says why
    assert (flag | TimeLimit(0.0)).check(Progress()).status == "cancelled"
    assert either.expansions_left(Progress(expansions=30)) == 70
    assert (ExpansionLimit(50) | ExpansionLimit(20)).expansions_left(Progress()) == 20
    assert (TimeLimit(1.0) | flag).expansions_left(Progress()) is None
    assert any_of(None, None) is None and any_of(None, flag) is flag
    assert any_of(TimeLimit(1.0), None, flag) == AnyOf((TimeLimit(1.0), flag))


# -- the driver polls them -------------------------------------------------------------------------------


def test_an_expansion_limit_stops_the_search_exactly_there() -> None:
    full, _ = _full_search()
    limit = full // 2 + 123  # not a multiple of the chunk
    watch = Watch()
    result = plan(_detour(), "A*", termination=watch | ExpansionLimit(limit))
    assert result.status == "timeout" and result.stop_reason == f"the expansion limit of {limit} ran out"
    assert watch.seen[-1].expansions == limit
    assert all(b.expansions - a.expansions <= CHUNK_EXPANSIONS for a, b in zip(watch.seen, watch.seen[1:]))


def test_a_time_limit_stops_the_search_once_that_much_search_time_passed() -> None:
    result = plan(_detour(), "A*", termination=TimeLimit(1e-4))
    assert result.status == "timeout" and result.search_s >= 1e-4
    assert result.stop_reason == "the search time limit of 0.0001 s ran out"


def test_a_cancel_from_another_thread_takes_effect_within_one_chunk() -> None:
    """The search is running (past its first chunks) when a second thread cancels; the driver stops at its
    next poll: at most one chunk of expansions later, and the best path so far is kept and valid."""
    full, optimum = _full_search()
    problem = _detour()
    cancel = CancelFlag()
    at_cancel: list[int] = []
    cancelled_at = [0.0]

    def cancel_elsewhere() -> None:
        cancelled_at[0] = time.perf_counter()
        cancel.cancel()

    def maybe_cancel(progress: Progress) -> None:
        if not at_cancel and progress.expansions >= 5 * CHUNK_EXPANSIONS:  # past the first path
            at_cancel.append(progress.expansions)
            other = threading.Thread(target=cancel_elsewhere)
            other.start()
            other.join()  # the flag is set on the other thread while the search waits here, mid-way

    watch = Watch(maybe_cancel)
    result = plan(problem, "A*", termination=watch | cancel)
    stopped_at = time.perf_counter()
    assert at_cancel and at_cancel[0] < full  # the cancel came while the search had work left
    assert result.status == "cancelled" and result.stop_reason == "cancelled"
    assert watch.seen[-1].expansions <= at_cancel[0] + CHUNK_EXPANSIONS
    assert stopped_at - cancelled_at[0] < 1.0  # one chunk: milliseconds, with ample room for a loaded machine
    # The best path so far: found in the iteration the cancel cut short, or an earlier one.
    assert result.path is not None and optimum - 1e-9 <= result.cost_m <= result.iterations[-1].cost_m
    check = check_path(result.path, problem.grid, problem.labels, problem.automaton, problem.profile)
    assert check.valid and check.cost_m == pytest.approx(result.cost_m, abs=1e-9)


def test_a_cancel_between_iterations_keeps_the_path_and_runs_no_more_search() -> None:
    """Cancelled from a second thread as the first iteration ends: no more expansions are made; the
    iterations whose bound already holds without search are still recorded (their bounds are free)."""
    cancel = CancelFlag()

    def on_iteration(record) -> None:
        other = threading.Thread(target=cancel.cancel)
        other.start()
        other.join()

    result = plan(_detour(), "A*", termination=cancel, callback=on_iteration)
    first = result.iterations[0]
    assert result.status == "cancelled" and first.bound == 200.0 and len(result.iterations) < 6
    assert all(it.expansions == first.expansions and it.cost_m == first.cost_m for it in result.iterations)
    # The path the parent pointers give now: its cells' g may have improved since the goal was reached.
    assert result.path is not None and result.cost_m <= first.cost_m


def test_a_search_cancelled_before_it_starts_builds_nothing() -> None:
    problem = _detour()
    cancel = CancelFlag()
    cancel.cancel()
    result = plan(problem, "NO-LLM", termination=cancel)
    assert result.status == "cancelled" and result.path is None and result.iterations == []
    assert result.precompute_s == 0.0 and problem.built_domain is None  # no domain was built


def test_the_public_plan_takes_a_termination_with_the_options_budgets() -> None:
    demo = sgplan.load_scene("demo")
    mission = sgplan.mission_from_formula('F "enter(room_5)" & F "reach(object_28)"', demo)
    cancel = CancelFlag()
    cancel.cancel()
    stopped = sgplan.plan(demo, mission, 0, setup="NO-LLM", termination=cancel)
    assert stopped.status == "cancelled" and stopped.path is None and stopped.bound is None
    assert stopped.to_dict()["status"] == "cancelled"
    cut = sgplan.plan(demo, mission, 0, setup="NO-LLM", max_expansions=1, termination=CancelFlag())
    assert cut.status == "timeout"  # the options' budget still applies beside the given condition
    whole = sgplan.plan(demo, mission, 0, setup="NO-LLM", termination=Deadline.after(600))
    assert whole.status == "optimal" and whole.verified
