"""The distance fields of a run's label regions, kept across scene changes and repaired, not recomputed.

h_LTL reads, for each label that can move the automaton, a field of every cell's distance to the cells
carrying that label (:mod:`sgplan.planning.ltl_heuristic`, fixed point in whole units). A
:class:`FieldStore` keeps one field per label bitmask over a run's one cell numbering
(:mod:`sgplan.execution.graph`): to the whole region of that bitmask, not only its part reachable from
the robot, since both agree on every cell the robot can reach (a path from such a cell never leaves its
component) and the whole region survives the robot moving on. After a change the store is told which
cells left or joined the graph or changed label; a field asked for later is brought up to date by
:func:`~sgplan.execution._repair.repair_field`, exactly as a full recomputation would make it, at the
cost of the cells whose distance changes.
"""

from __future__ import annotations

from collections import Counter

import numpy as np

from sgplan.execution._repair import EXACT, RECOMPUTE, repair_field
from sgplan.execution.graph import in_graph
from sgplan.planning.cells import CellGraph
from sgplan.planning.ltl_heuristic import unit_costs, unit_field


class FieldStore:
    """Distance fields by label bitmask, at one unit, repaired lazily after changes.

    A repair that would invalidate more than ``invalidate_fraction`` of the cells leaves the field a lower
    bound instead (still 1-Lipschitz over the moves, so h_LTL stays consistent and the search exact, only
    less informed; :func:`~sgplan.execution._repair.repair_field`); one that would lower more than
    ``lower_fraction`` of them recomputes the field. ``exact`` says which fields are exact.
    ``counts`` tallies ``computed`` (whole fields), ``repaired`` (exactly), ``bounded`` (left lower
    bounds) and ``reused`` (handed out as they were), for tests and benchmarks.
    """

    def __init__(self, invalidate_fraction: float = 0.005, lower_fraction: float = 0.03) -> None:
        self.invalidate_fraction = invalidate_fraction
        self.lower_fraction = lower_fraction
        self._fields: dict[int, np.ndarray] = {}
        # Per field, the changes since it was right: (cells that left or joined the graph, relabelled
        # cells, their bitmasks before).
        self._pending: dict[int, list[tuple[np.ndarray, np.ndarray, np.ndarray]]] = {}
        self.exact: dict[int, bool] = {}
        self._size: dict[int, int] = {}  # cells of each field's region when it was computed
        self._unit_m: float | None = None
        self.counts: Counter[str] = Counter()

    def changed(self, moved: np.ndarray, relabelled: np.ndarray, masks_before: np.ndarray) -> None:
        """Note that the cells ``moved`` (numbers) left or joined the graph, and that the cells
        ``relabelled`` changed label bitmask (``masks_before``: theirs before): a field is repaired only
        from those of the relabelled cells that joined or left its own region."""
        if moved.size or relabelled.size:
            for pending in self._pending.values():
                pending.append((moved, relabelled, masks_before))

    def forget(self) -> None:
        """Drop every field (the bitmasks now mean other propositions)."""
        self._fields.clear()
        self._pending.clear()
        self.exact.clear()

    def field(self, graph: CellGraph, masks: np.ndarray, mask: int, unit_m: float) -> np.ndarray | float:
        """``(N,)`` uint32: every cell's distance in units of ``unit_m`` to the cells of ``graph`` whose
        bitmask (``masks``, per cell) is ``mask``, as :func:`unit_field` computes it, or a lower bound of it
        (see the class); or, when some distance does not fit in 32 bits, the largest one (a float: ask again
        with a coarser unit). The array is the store's: read it, do not change it.

        Costs a full Dijkstra the first time (or at a new unit), then the cells changed since (bounded by
        the fractions of the class, past which one full Dijkstra).
        """
        if unit_m != self._unit_m:
            self.forget()
            self._unit_m = unit_m
        kept = self._fields.get(mask)
        if kept is not None and not self._pending[mask]:
            self.counts["reused"] += 1
            return kept
        if kept is not None and self._repair(graph, masks, mask, kept, unit_m):
            return kept
        field = unit_field(graph, np.flatnonzero((masks == mask) & in_graph(graph)), unit_m)
        self.counts["computed"] += 1
        if isinstance(field, np.ndarray):
            self._fields[mask], self._pending[mask], self.exact[mask] = field, [], True
            self._size[mask] = int(np.count_nonzero(field == 0))
        else:
            self._fields.pop(mask, None)
        return field

    def _repair(self, graph: CellGraph, masks: np.ndarray, mask: int, kept: np.ndarray,
                unit_m: float) -> bool:
        """Bring ``kept`` up to date in place; False when it must be recomputed instead: also when most of
        the region's cells are new targets (a moved or added object's reach), whose distances change
        almost everywhere -- a full Dijkstra is the cheaper way there."""
        parts, joined = [], 0
        for moved, relabelled, before in self._pending[mask]:
            now = masks[relabelled] == mask
            parts += [moved, relabelled[(before == mask) | now]]
            joined += int(np.count_nonzero(now & (before != mask)))
        seeds = np.unique(np.concatenate(parts))
        self._pending[mask] = []
        if 2 * joined > int(np.count_nonzero(masks[seeds] == mask)) + self._size.get(mask, 0):
            return False
        steps, stairs = unit_costs(graph, unit_m)
        done = np.zeros(2, dtype=np.int64)
        outcome = repair_field(graph.cell_at, graph.cell_pos, graph.step_offset, steps.astype(np.int64),
                               graph.stairs_first, graph.stairs_from, graph.stairs_to,
                               stairs.astype(np.int64), masks, mask, kept, seeds,
                               int(self.invalidate_fraction * graph.num_cells),
                               int(self.lower_fraction * graph.num_cells), done)
        if outcome == RECOMPUTE:
            return False
        self.exact[mask] = self.exact[mask] and outcome == EXACT
        self.counts["repaired" if outcome == EXACT else "bounded"] += 1
        return True
