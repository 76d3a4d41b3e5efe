"""What the report reads of a plan: structural types, so both plan result classes fit.

``sgplan.planning.amra.SearchResult`` (the planner's) and ``sgplan.result.PlanResult`` (the public API's,
which also has events) both satisfy :class:`PlanOutcome`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np


class Iteration(Protocol):
    """One AMRA* iteration as the report reads it (:class:`sgplan.planning.amra.IterationRecord`)."""

    w1: float
    w2: float
    cost_m: float
    bound: float
    time_s: float


class PathEvent(Protocol):
    """An event along the path as the report reads it (:class:`sgplan.outputs.events.Event`)."""

    floor: int
    row: int
    col: int

    def describe(self) -> str: ...


class PlanOutcome(Protocol):
    """What the report reads of a plan result (both ``sgplan.planning.amra.SearchResult`` and
    ``sgplan.result.PlanResult`` fit): the path rows ``(row, col, floor, ...)`` or ``None``, the cost in
    metres, the status, the setup and the iterations."""

    path: np.ndarray | None
    cost_m: float
    status: str
    setup: str
    iterations: Sequence[Any]
