"""Planner parts that depend only on the building, kept across missions by a :class:`sgplan.Session`.

A part (the cell graph of an occupancy grid, and whatever else the domain precomputation derives from the
building alone) is built once per key, the key naming everything the part depends on (the grid object,
radii, ...), and then shared, read-only, by every planning problem of the session. A problem without a
:class:`SharedParts` builds every part itself (:func:`shared_part`).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Hashable
from typing import Any, TypeVar

T = TypeVar("T")


class SharedParts:
    """Building-only planner parts by ``(name, key)``; ``builds`` counts the parts built per name."""

    def __init__(self) -> None:
        self._parts: dict[tuple[str, Hashable], Any] = {}
        self.builds: Counter[str] = Counter()

    def get(self, name: str, key: Hashable, build: Callable[[], T]) -> T:
        """The part ``name`` for ``key``, built by ``build()`` the first time. The part must not be
        changed by its users: every later problem of the session gets the same object."""
        slot = (name, key)
        if slot not in self._parts:
            self._parts[slot] = build()
            self.builds[name] += 1
        part: T = self._parts[slot]
        return part


def shared_part(parts: SharedParts | None, name: str, key: Hashable, build: Callable[[], T]) -> T:
    """``parts.get(name, key, build)``, or ``build()`` when there is nothing to share with."""
    return build() if parts is None else parts.get(name, key, build)
