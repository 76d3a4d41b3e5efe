"""Plans of requests under the server's limits: a wall-clock deadline per request and a cancel flag.

:class:`Budget` is what one request may spend: its deadline (:class:`sgplan.planning.termination.Deadline`,
from the server's ``request_time_limit_s``) and a :class:`~sgplan.planning.termination.CancelFlag` another
thread may set; both stop a running search at its next poll, which keeps the best path so far.
:func:`plan_on_host` is what a plan worker runs for a one-shot plan: on one of the scene's sessions that
no other plan uses (a search fills its session's action maps), with the mission already understood
(translated and explained once, :mod:`sgplan.serve.missions`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from sgplan.options import PlanOptions
from sgplan.planning.termination import CancelFlag, Deadline, Termination
from sgplan.serve.errors import HTTPProblem

if TYPE_CHECKING:
    from sgplan.result import PlanResult
    from sgplan.serve.missions import Understood
    from sgplan.serve.models import Options, Start
    from sgplan.serve.scenes import SceneHost


@dataclass(frozen=True)
class Budget:
    """What one request may spend: ``seconds`` of wall clock from now, and a cancel flag."""

    seconds: float
    deadline: Deadline
    cancel: CancelFlag = field(default_factory=CancelFlag)

    @classmethod
    def of(cls, seconds: float) -> Budget:
        return cls(seconds, Deadline.after(seconds))

    @property
    def stop_when(self) -> Termination:
        """The search's termination condition: the deadline or the cancel flag."""
        return self.deadline | self.cancel

    @property
    def expired(self) -> bool:
        return time.monotonic() >= self.deadline.at

    @property
    def left_s(self) -> float:
        """Seconds until the deadline (0 once it passed)."""
        return max(0.0, self.deadline.at - time.monotonic())

    def late(self) -> HTTPProblem:
        """408: the deadline came before any path was found."""
        return HTTPProblem(
            408,
            f"no path within the server's time limit of {self.seconds:g} s per request; retry later, or give "
            "the plan a budget (options.time_limit_s, max_expansions) to get the best path so far",
            retry_after_s=1,
        )


def plan_options(options: Options) -> PlanOptions:
    """The request's options as the planner's :class:`sgplan.PlanOptions` (validated again there)."""
    return PlanOptions(**options.model_dump(exclude_none=True))


def plan_on_host(
    host: SceneHost, understood: Understood, start: Start | None, options: Options, budget: Budget
) -> PlanResult:
    """Plan ``understood`` on ``host`` from ``start`` with ``options``, stopping when ``budget`` runs out.

    Raises
    ------
    HTTPProblem
        408 when the deadline passed before any path was found (waiting for a free session included).
    SgplanError
        what :func:`sgplan.plan` raises (a bad start, an infeasible mission ...).
    """
    try:
        with host.planner(budget.left_s) as session:  # waiting for a free session counts too
            result = session.plan(
                understood.mission,
                None if start is None else start.spec(),
                options=plan_options(options),
                explanation=understood.explanation,
                termination=budget.stop_when,
            )
    except TimeoutError:  # no session came free before the deadline
        raise budget.late() from None
    # A budget of the request's own (expansions, search seconds) gives its best path, or none, with status
    # "timeout"; the server's deadline without a path is the server's to answer for.
    if result.path is None and result.status == "timeout" and budget.expired:
        raise budget.late()
    return result
