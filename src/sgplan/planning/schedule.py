"""AMRA*'s weight schedule: the (w1, w2) of each iteration (reference-algorithm.md §6).

w1 weighs the heuristics in every queue's key, w2 bounds how far a level queue's key may exceed the
anchor's; an iteration's path costs at most w1 * w2 times the optimum, and the last iteration, at
``last`` (by default (1, 1)), is exactly optimal.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from sgplan.errors import PlanningError
from sgplan.planning._search import TAG_MASK

MAX_ITERATIONS = TAG_MASK
"""The longest weight schedule (closed sets are tagged with the iteration number modulo 256)."""


@dataclass(frozen=True)
class WeightSchedule:
    """(w1, w2) start at ``first`` and are multiplied by ``decay`` (floored at ``last``) after each
    iteration; the iteration run at ``last`` is the final one.

    Raises
    ------
    PlanningError
        ``decay`` outside (0, 1), ``last`` below 1 or above ``first``, or more than :data:`MAX_ITERATIONS`
        iterations.
    """

    first: tuple[float, float] = (10.0, 20.0)
    last: tuple[float, float] = (1.0, 1.0)
    decay: float = 0.5

    def __post_init__(self) -> None:
        first, last, decay = self.first, self.last, self.decay
        if not (0 < decay < 1) or min(last) < 1 or first[0] < last[0] or first[1] < last[1]:
            raise PlanningError(f"bad weight schedule {first} -> {last} with decay {decay}")
        if len(self) > MAX_ITERATIONS:
            raise PlanningError(
                f"weight schedule {first} -> {last} with decay {decay} has more than {MAX_ITERATIONS} "
                "iterations (the search tags closed states with the iteration in 8 bits); lower the decay "
                "factor"
            )

    def __iter__(self) -> Iterator[tuple[float, float]]:
        """The (w1, w2) of each iteration, in order."""
        w1, w2 = float(self.first[0]), float(self.first[1])
        while True:
            yield w1, w2
            if w1 <= self.last[0] and w2 <= self.last[1]:
                return
            w1, w2 = max(w1 * self.decay, self.last[0]), max(w2 * self.decay, self.last[1])

    def __len__(self) -> int:
        """Iterations in the schedule (counted up to one past :data:`MAX_ITERATIONS`)."""
        count = 0
        for count, _ in enumerate(self, start=1):
            if count > MAX_ITERATIONS:
                break
        return count


PAPER_SCHEDULE = WeightSchedule()
"""The paper's schedule: (10, 20) halving to (1, 1), six iterations."""
