"""When a search stops before its optimum: small composable termination conditions.

As OMPL separates its ``PlannerTerminationCondition`` from the planner, a condition here is a value the
search driver (:func:`sgplan.planning.amra.plan`) polls; it knows nothing of the search but the
:class:`Progress` it is shown, and says why the search must stop (a :class:`Stop`) or ``None``:

- :class:`TimeLimit`: seconds of search (the driver's clock over the compiled search, as
  ``PlanOptions.time_limit_s``; the domain's precomputation does not count);
- :class:`ExpansionLimit`: expansions, summed over the queues (the driver never lets a chunk run past it);
- :class:`Deadline`: a moment on the wall clock (:func:`time.monotonic`), e.g. a service request's;
- :class:`CancelFlag`: set by :meth:`CancelFlag.cancel`, from any thread;
- any of them together: ``TimeLimit(5) | cancel`` (:class:`AnyOf`), stopping at the first that fires.

A time, deadline or expansion limit stops with status ``"timeout"``, a cancel with ``"cancelled"``; either
way the plan keeps the best path found so far. When a condition fires is bounded by how often it is
polled: the driver polls before the domain is built, before the search starts and before every chunk of
at most :data:`sgplan.planning.amra.CHUNK_EXPANSIONS` expansions, so a condition takes effect within one
chunk (with the composite action maps that chunk builds, and, between two iterations, the re-keying of
the open list). A cancel while the domain is being precomputed takes effect when that step ends.

>>> from sgplan.planning.termination import CancelFlag, ExpansionLimit, Progress, TimeLimit
>>> cancel = CancelFlag()
>>> stop_when = TimeLimit(5.0) | ExpansionLimit(10_000) | cancel
>>> stop_when.check(Progress(search_s=1.0, expansions=20_000)).reason
'the expansion limit of 10000 ran out'
>>> cancel.cancel()
>>> stop_when.check(Progress(search_s=0.0, expansions=0)).status
'cancelled'
"""

from __future__ import annotations

import math
import threading
import time
from dataclasses import dataclass

from sgplan.errors import PlanningError

TIMEOUT, CANCELLED = "timeout", "cancelled"
"""The statuses of a stopped search (a plan whose search ran to the end is ``"optimal"``)."""


@dataclass(frozen=True)
class Progress:
    """Where a search stands when a condition is polled: ``search_s`` seconds of search so far, and
    ``expansions`` (all queues)."""

    search_s: float = 0.0
    expansions: int = 0


@dataclass(frozen=True)
class Stop:
    """Why a search stopped: ``status`` (:data:`TIMEOUT` or :data:`CANCELLED`) and a one-line ``reason``."""

    status: str
    reason: str


class Termination:
    """A termination condition (the base of those of this module; see the module docstring)."""

    def check(self, progress: Progress) -> Stop | None:
        """Why the search must stop now, or ``None`` to go on."""
        raise NotImplementedError

    def expansions_left(self, progress: Progress) -> int | None:
        """How many more expansions the search may make before this condition fires (``None``: it does
        not count expansions); the driver sizes its chunks by it."""
        return None

    def __or__(self, other: Termination) -> AnyOf:
        return AnyOf((self, other))


@dataclass(frozen=True)
class TimeLimit(Termination):
    """Stop once ``seconds`` of search have passed."""

    seconds: float

    def __post_init__(self) -> None:
        if not (isinstance(self.seconds, (int, float)) and math.isfinite(self.seconds) and self.seconds >= 0):
            raise PlanningError(f"a time limit must be a finite number of seconds >= 0, got {self.seconds!r}")

    def check(self, progress: Progress) -> Stop | None:
        if progress.search_s >= self.seconds:
            return Stop(TIMEOUT, f"the search time limit of {self.seconds:g} s ran out")
        return None


@dataclass(frozen=True)
class ExpansionLimit(Termination):
    """Stop once ``count`` expansions have been made."""

    count: int

    def __post_init__(self) -> None:
        if not (isinstance(self.count, int) and not isinstance(self.count, bool) and self.count >= 0):
            raise PlanningError(f"an expansion limit must be a whole number >= 0, got {self.count!r}")

    def check(self, progress: Progress) -> Stop | None:
        if progress.expansions >= self.count:
            return Stop(TIMEOUT, f"the expansion limit of {self.count} ran out")
        return None

    def expansions_left(self, progress: Progress) -> int | None:
        return max(0, self.count - progress.expansions)


@dataclass(frozen=True)
class Deadline(Termination):
    """Stop once the wall clock (:func:`time.monotonic`) reaches ``at``; :meth:`after` makes one."""

    at: float

    @classmethod
    def after(cls, seconds: float) -> Deadline:
        """The deadline ``seconds`` from now."""
        if not (isinstance(seconds, (int, float)) and math.isfinite(seconds) and seconds >= 0):
            raise PlanningError(f"a deadline must be a finite number of seconds >= 0 away, got {seconds!r}")
        return cls(time.monotonic() + seconds)

    def check(self, progress: Progress) -> Stop | None:
        if time.monotonic() >= self.at:
            return Stop(TIMEOUT, "the deadline passed")
        return None


class CancelFlag(Termination):
    """Stop once :meth:`cancel` was called, from any thread (a :class:`threading.Event` underneath)."""

    def __init__(self) -> None:
        self._event = threading.Event()
        self._reason = "cancelled"

    def cancel(self, reason: str = "cancelled") -> None:
        """Ask the search to stop (it stops at its next poll; see the module docstring)."""
        self._reason = reason
        self._event.set()

    @property
    def cancelled(self) -> bool:
        return self._event.is_set()

    def check(self, progress: Progress) -> Stop | None:
        return Stop(CANCELLED, self._reason) if self._event.is_set() else None

    def __repr__(self) -> str:
        return f"CancelFlag(cancelled={self.cancelled})"


@dataclass(frozen=True)
class AnyOf(Termination):
    """Stop as soon as any of ``conditions`` does (the first one's :class:`Stop`, in order)."""

    conditions: tuple[Termination, ...]

    def check(self, progress: Progress) -> Stop | None:
        for condition in self.conditions:
            stop = condition.check(progress)
            if stop is not None:
                return stop
        return None

    def expansions_left(self, progress: Progress) -> int | None:
        counts = [n for n in (c.expansions_left(progress) for c in self.conditions) if n is not None]
        return min(counts) if counts else None

    def __or__(self, other: Termination) -> AnyOf:
        return AnyOf((*self.conditions, other))


def any_of(*conditions: Termination | None) -> Termination | None:
    """The condition that fires when any of the given ones does (``None``s left out): ``None`` for none,
    the condition itself for one."""
    given = [c for c in conditions if c is not None]
    if not given:
        return None
    return given[0] if len(given) == 1 else AnyOf(tuple(given))
