"""One plan of a request on a warm scene, under the server's time limit.

:func:`plan_on_host` is what a plan worker runs: it takes the scene's plan lock (one search at a time per
session), plans with the scene's :class:`sgplan.Session` and the mission already understood (translated
and explained once, :mod:`sgplan.serve.missions`), and stops the search when the request's deadline
comes (the best path so far is kept; none found: 408).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

from sgplan.serve.errors import HTTPProblem

if TYPE_CHECKING:
    from sgplan.result import PlanResult
    from sgplan.serve.missions import Understood
    from sgplan.serve.models import Options, Start
    from sgplan.serve.scenes import SceneHost


@dataclass(frozen=True)
class Deadline:
    """When a request must be answered (:func:`time.monotonic` seconds) and how long it was given."""

    at: float
    seconds: float

    @classmethod
    def after(cls, seconds: float) -> Deadline:
        return cls(time.monotonic() + seconds, seconds)

    def left_s(self) -> float:
        return self.at - time.monotonic()


def plan_on_host(
    host: SceneHost, understood: Understood, start: Start | None, options: Options, deadline: Deadline
) -> PlanResult:
    """Plan ``understood`` on ``host`` from ``start`` with ``options``, stopping at ``deadline``.

    Raises
    ------
    HTTPProblem
        408 when the deadline passed before any path was found (waiting for the lock included).
    SgplanError
        what :func:`sgplan.plan` raises (a bad start, an infeasible mission ...).
    """
    with host.lock:
        left = deadline.left_s()
        if left <= 0:
            raise _late(deadline)
        limit = left if options.time_limit_s is None else min(options.time_limit_s, left)
        result = host.session.plan(
            understood.mission,
            None if start is None else start.spec(),
            setup=options.setup,
            profile=options.profile,
            robot_radius_m=options.robot_radius_m,
            reach_radius_m=options.reach_radius_m,
            time_limit_s=limit,
            max_expansions=options.max_expansions,
            explanation=understood.explanation,
        )
    # The search's own clock runs behind the wall clock: when the server's limit stopped it, the deadline
    # has passed; a budget of the request's (expansions, a shorter time) stops it before.
    if result.status == "timeout" and result.path is None and deadline.left_s() <= 0:
        raise _late(deadline)
    return result


def _late(deadline: Deadline) -> HTTPProblem:
    return HTTPProblem(
        408,
        f"no path within the server's time limit of {deadline.seconds:g} s per request; "
        "retry later, or give the plan a budget (options.time_limit_s, max_expansions) to get "
        "the best path so far",
        retry_after_s=1,
    )
