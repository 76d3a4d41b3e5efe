"""Planner parts that depend only on the building, kept across missions by a :class:`sgplan.Session`.

A part is built once per key, the key naming everything the part depends on, and then shared, read-only,
by every planning problem of the session. The parts kept (:mod:`sgplan.planning.domain`):

- ``cell_graph``: the cell graph of an occupancy grid (key: the grid object);
- ``action_tables``: the composite action families, their source cells and per-room tables (key: grid,
  reach radius);
- ``action_maps``: the shortest-path fields (distances, predecessors) of those families,
  filled lazily by the search as it needs them (key: grid, reach radius, and the connected component of
  the start, which sets where a map's early stop may end);
- ``label_runs``: the runs of equal labels along those maps' paths (key: the same, and a digest of the
  cells' labels: shared by problems whose cells carry the same labels, e.g. one mission from several
  starts or setups);
- ``distance_field``: the exact distance from every cell to a set of target cells, the terms of h_LTL
  (key: grid, the target cells);
- ``label_boundary``: the cells where a move enters another label region, where h_LTL's fields are
  combined (key: grid, a digest of the cells' labels).

Memory is bounded: :meth:`SharedParts.trim` (a :class:`Session` calls it after each plan) drops the least
recently used parts until the bytes they hold (``nbytes`` of each part, measured then, since action maps
grow as searches fill them) are within ``max_bytes``. A dropped part is rebuilt by the next problem that
needs it. Problems already holding a dropped part keep it alive until they are freed.

A problem without a :class:`SharedParts` builds every part itself (:func:`shared_part`). Parts that keep
more, up to date across changes of the building (a run's), also serve the domain's
:class:`~sgplan.planning.domain.KeptParts`.
"""

from __future__ import annotations

import hashlib
import os
from collections import Counter, OrderedDict
from collections.abc import Callable, Hashable
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

if TYPE_CHECKING:
    from sgplan.planning.cells import CellGraph

T = TypeVar("T")

DEFAULT_MAX_BYTES = 1 << 30
"""Default cap of a session's shared parts (1 GiB; ``SGPLAN_SESSION_BYTES`` overrides it): about 6 Gibson
buildings' worth of prebuilt action maps and distance fields."""


def default_max_bytes() -> int:
    """``$SGPLAN_SESSION_BYTES`` (an integer number of bytes) if set, else :data:`DEFAULT_MAX_BYTES`."""
    value = os.environ.get("SGPLAN_SESSION_BYTES")
    if value is None or not value.strip():
        return DEFAULT_MAX_BYTES
    try:
        return max(int(value), 0)
    except ValueError:
        from sgplan.errors import PlanningError

        raise PlanningError(f"SGPLAN_SESSION_BYTES must be a whole number of bytes, got {value!r}") from None


def part_bytes(part: Any) -> int:
    """Bytes a part holds: its ``nbytes()`` method if it has one, else the sum over its numpy arrays
    (the part itself, or the values of its ``__dict__`` / items of a tuple)."""
    measure = getattr(part, "nbytes", None)
    if callable(measure):
        return int(measure())
    if isinstance(part, np.ndarray):
        return int(part.nbytes)
    values = part if isinstance(part, tuple) else getattr(part, "__dict__", {}).values()
    return sum(int(v.nbytes) for v in values if isinstance(v, np.ndarray))


class SharedParts:
    """Building-only planner parts by ``(name, key)``, least recently used dropped beyond ``max_bytes``.

    ``builds`` counts the parts built per name, ``evictions`` the parts dropped per name.
    """

    def __init__(self, max_bytes: int | None = None) -> None:
        self.max_bytes = default_max_bytes() if max_bytes is None else int(max_bytes)
        self._parts: OrderedDict[tuple[str, Hashable], Any] = OrderedDict()
        self.builds: Counter[str] = Counter()
        self.evictions: Counter[str] = Counter()

    @property
    def keeps(self) -> bool:
        """Whether parts are kept at all (``max_bytes > 0``)."""
        return self.max_bytes > 0

    def get(self, name: str, key: Hashable, build: Callable[[], T]) -> T:
        """The part ``name`` for ``key``, built by ``build()`` the first time (or after it was dropped;
        every time when nothing is kept). The part must not be changed by its users, except a part
        designed to fill itself lazily (action maps): every later problem of the session gets the same
        object."""
        if not self.keeps:
            self.builds[name] += 1
            return build()
        slot = (name, key)
        if slot in self._parts:
            self._parts.move_to_end(slot)
        else:
            self._parts[slot] = build()
            self.builds[name] += 1
        part: T = self._parts[slot]
        return part

    def kept(self, name: str) -> dict[Hashable, Any]:
        """The parts called ``name`` held now, by key (oldest first)."""
        return {key: part for (kind, key), part in self._parts.items() if kind == name}

    def nbytes(self) -> int:
        """Bytes held by the parts now."""
        return sum(part_bytes(part) for part in self._parts.values())

    def trim(self) -> int:
        """Drop the least recently used parts until the rest hold at most ``max_bytes``; returns the bytes
        still held."""
        sizes = {slot: part_bytes(part) for slot, part in self._parts.items()}
        total = sum(sizes.values())
        for slot in list(self._parts):  # oldest first
            if total <= self.max_bytes:
                break
            del self._parts[slot]
            total -= sizes[slot]
            self.evictions[slot[0]] += 1
        return total

    def __len__(self) -> int:
        return len(self._parts)

    def distance_field(self, grid: Hashable, graph: CellGraph, cells: np.ndarray, unit_m: float
                       ) -> np.ndarray | float:
        """The ``distance_field`` part: :func:`~sgplan.planning.ltl_heuristic.unit_field` of ``graph`` (the
        cell graph of ``grid``) to ``cells`` (sorted cell indices) in units of ``unit_m``, kept read-only
        by grid, unit and target cells. A subclass may serve it otherwise (a run repairs its fields across
        scene changes, :mod:`sgplan.execution.parts`)."""
        from sgplan.planning.ltl_heuristic import unit_field

        if not self.keeps:
            return unit_field(graph, cells, unit_m)
        cells = np.ascontiguousarray(cells, dtype=np.int64)
        key = (grid, unit_m, len(cells), hashlib.blake2b(cells.tobytes(), digest_size=16).digest())

        def build() -> np.ndarray | float:
            field = unit_field(graph, cells, unit_m)
            if isinstance(field, np.ndarray):
                field.flags.writeable = False
            return field

        return self.get("distance_field", key, build)


def shared_part(parts: SharedParts | None, name: str, key: Hashable, build: Callable[[], T]) -> T:
    """``parts.get(name, key, build)``, or ``build()`` when there is nothing to share with."""
    return build() if parts is None else parts.get(name, key, build)
