"""The distance fields of a run's label regions, kept across scene changes and repaired, not recomputed.

h_LTL reads, for each label that can move the automaton, a field of every cell's distance to the cells
carrying that label (:mod:`sgplan.planning.ltl_heuristic`, fixed point in whole units), as one
cell-major matrix (a column per label). A :class:`FieldStore` keeps that matrix over a run's one cell
numbering (:mod:`sgplan.execution.graph`), a column per label bitmask: to the whole region of that
bitmask, not only its part reachable from the robot, since both agree on every cell the robot can reach
(a path from such a cell never leaves its component) and the whole region survives the robot moving on.
After a change the store is told which cells left or joined the graph or changed label; a column asked
for later is brought up to date in place by :func:`~sgplan.execution._repair.repair_field`, exactly as a
full recomputation would make it, at the cost of the cells whose distance changes. The matrix is handed
out as it is, not assembled per plan; only when the labels asked for change (the robot's progress needs
fewer, a label region appears) is it laid out anew, the columns no longer asked for kept aside (and
repaired when asked for again).
"""

from __future__ import annotations

from collections import Counter

import numpy as np

from sgplan.execution._repair import EXACT, LOWER_BOUND, RECOMPUTE, repair_field
from sgplan.execution.graph import in_graph_cells
from sgplan.intsets import unique_sorted
from sgplan.planning.cells import CellGraph
from sgplan.planning.ltl_heuristic import unit_costs, unit_field


class FieldStore:
    """Distance fields by label bitmask, at one unit, kept as the columns of one matrix and repaired
    lazily after changes.

    A repair that would lower more than ``lower_fraction`` of the cells recomputes the field instead (a
    repair costs more per cell it touches than a full Dijkstra: a heap, two phases). One that would
    invalidate more than ``invalidate_fraction`` of them leaves the field a lower bound when ``bound``
    (still 1-Lipschitz over the moves, so h_LTL stays consistent and the search exact,
    :func:`~sgplan.execution._repair.repair_field`; the search after it is less informed until the field
    is recomputed), else recomputes it. Bounding is the default: on the Gibson replanning benchmark the
    recomputed fields cost more than the states the bounded ones made the search expand
    (``benchmarks/results/replanning.md``, ``--exact-fields``). ``exact`` says which fields are exact.
    ``counts`` tallies ``computed`` (whole fields), ``repaired`` (exactly), ``bounded`` (left lower
    bounds), ``reused`` (handed out as they were) and ``laid_out`` (the matrix laid out anew), for tests
    and benchmarks.
    """

    def __init__(self, invalidate_fraction: float = 0.005, lower_fraction: float = 0.03,
                 bound: bool = True) -> None:
        self.invalidate_fraction = invalidate_fraction
        self.lower_fraction = lower_fraction
        self.bound = bound
        self._matrix = np.zeros((0, 0), dtype=np.uint32)
        self._columns: list[int] = []  # the bitmask of each column of the matrix
        self._aside: dict[int, np.ndarray] = {}  # fields of bitmasks not asked for by the last plan
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
        self._matrix = np.zeros((0, 0), dtype=np.uint32)
        self._columns = []
        self._aside = {}
        self._pending.clear()
        self.exact.clear()

    def fields(self, graph: CellGraph, masks: np.ndarray, wanted: list[int], unit_m: float
               ) -> np.ndarray | float:
        """``(N, F)`` uint32, column ``i`` every cell's distance in units of ``unit_m`` to the cells of
        ``graph`` whose bitmask (``masks``, per cell) is ``wanted[i]``, as :func:`unit_field` computes it,
        or a lower bound of it (see the class); or, when some distance does not fit in 32 bits, the
        largest one (a float: ask again with a coarser unit). The matrix is the store's: read it, do not
        change it (the next call may repair it in place).

        Costs a full Dijkstra per field the first time (or at a new unit), then the cells changed since
        (bounded by the fractions of the class, past which one full Dijkstra); a copy of the matrix when
        ``wanted`` differs from the last call's.
        """
        if unit_m != self._unit_m or self._matrix.shape[0] not in (0, graph.num_cells):
            self.forget()  # another unit, or the cells were numbered anew
            self._unit_m = unit_m
        if wanted != self._columns:
            self._lay_out(wanted, graph.num_cells)
        for i, mask in enumerate(wanted):
            column = self._matrix[:, i]
            if mask in self._pending and not self._pending[mask]:
                self.counts["reused"] += 1
            elif mask not in self._pending or not self._repair(graph, masks, mask, column, unit_m):
                region = np.flatnonzero(masks == mask)
                field = unit_field(graph, region[in_graph_cells(graph, region)], unit_m)
                self.counts["computed"] += 1
                if not isinstance(field, np.ndarray):
                    self.forget()
                    return field
                column[:] = field
                self._pending[mask], self.exact[mask] = [], True
                self._size[mask] = int(np.count_nonzero(field == 0))
        return self._matrix

    def _lay_out(self, wanted: list[int], num_cells: int) -> None:
        """A matrix with the columns ``wanted``: those kept (in the matrix or aside) copied in, the others
        left to compute; the columns no longer wanted put aside."""
        kept = {mask: self._matrix[:, i] for i, mask in enumerate(self._columns)} | self._aside
        matrix = np.empty((num_cells, len(wanted)), dtype=np.uint32)
        for i, mask in enumerate(wanted):
            if mask in kept:
                matrix[:, i] = kept[mask]
        self._aside = {mask: np.ascontiguousarray(field) for mask, field in kept.items()
                       if mask not in wanted}
        self._matrix, self._columns = matrix, list(wanted)
        self.counts["laid_out"] += 1

    def _repair(self, graph: CellGraph, masks: np.ndarray, mask: int, kept: np.ndarray, unit_m: float
                ) -> bool:
        """Bring ``kept`` up to date in place; False when it must be recomputed instead: also when most of
        the region's cells are new targets (a moved or added object's reach), whose distances change
        almost everywhere -- a full Dijkstra is the cheaper way there."""
        parts, joined = [], 0
        for moved, relabelled, before in self._pending[mask]:
            now = masks[relabelled] == mask
            parts += [moved, relabelled[(before == mask) | now]]
            joined += int(np.count_nonzero(now & (before != mask)))
        seeds = unique_sorted(np.concatenate(parts))
        self._pending[mask] = []
        if 2 * joined > int(np.count_nonzero(masks[seeds] == mask)) + self._size.get(mask, 0):
            return False
        steps, stairs = unit_costs(graph, unit_m)
        done = np.zeros(2, dtype=np.int64)
        outcome = repair_field(graph.cell_at, graph.cell_pos, graph.step_offset, steps.astype(np.int64),
                               graph.stairs_first, graph.stairs_from, graph.stairs_to,
                               stairs.astype(np.int64), masks, mask, kept, self.exact[mask], seeds,
                               int(self.invalidate_fraction * graph.num_cells),
                               int(self.lower_fraction * graph.num_cells), done)
        if outcome == RECOMPUTE or (outcome == LOWER_BOUND and not self.bound):
            return False
        self.exact[mask] = self.exact[mask] and outcome == EXACT
        self.counts["repaired" if outcome == EXACT else "bounded"] += 1
        return True
