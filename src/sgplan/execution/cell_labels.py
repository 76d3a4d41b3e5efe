"""The mission's labels over a run's cell numbering, kept up to date across scene changes.

Every plan needs, per cell, the bitmask of the propositions that hold there, a compact label id (the
automaton's table is indexed by it) and whether the cell lies on a label boundary (h_LTL's entry cells,
:func:`sgplan.planning.ltl_heuristic.label_boundary`). Computed afresh they cost passes over every cell of
the numbering; a scene change touches a few: the cells that left or joined the graph and those whose label
changed. :class:`CellLabels` keeps the three arrays and updates them there.

Compact ids are handed out once per bitmask and kept for the whole run (a bitmask no cell carries any
more keeps its id, unused), so a change never renumbers the labels of the cells it did not touch.
"""

from __future__ import annotations

import numpy as np

from sgplan.intsets import unique_sorted
from sgplan.planning.cells import CellGraph
from sgplan.planning.domain import compact_labels, label_index_dtype
from sgplan.planning.ltl_heuristic import label_boundary, mark_boundary


class CellLabels:
    """The labels of a run's cells (see the module).

    Parameters
    ----------
    candidates:
        the run's numbering, unmasked (:func:`sgplan.execution.graph.candidate_graph`).
    graph:
        the current mask of it.
    labels:
        the label raster ``(floors, rows, cols)`` of the mission's propositions.

    Attributes
    ----------
    masks:
        ``(N,)`` the bitmask of every cell of the numbering (masked cells too).
    label_masks, cell_label:
        the bitmask of each compact id (int64, in the order the ids were handed out) and each cell's id.
    boundary:
        ``(N,)`` bool, :func:`~sgplan.planning.ltl_heuristic.label_boundary` of ``graph``.
    """

    def __init__(self, candidates: CellGraph, graph: CellGraph, labels: np.ndarray) -> None:
        self.masks = candidates.gather(labels)
        if self.masks.size and int(self.masks.min()) < 0:
            raise ValueError(f"label raster holds a negative bitmask ({int(self.masks.min())})")
        self.label_masks, self.cell_label = compact_labels(self.masks, int(self.masks.max(initial=0)) + 1)
        self._ids = {int(mask): i for i, mask in enumerate(self.label_masks.tolist())}
        self.boundary = label_boundary(graph, self.cell_label)

    def update(self, graph: CellGraph, moved: np.ndarray, cells: np.ndarray, masks: np.ndarray) -> None:
        """Follow a change: ``graph`` is the new mask, ``moved`` the cells (numbers) that left or joined it,
        ``cells`` those whose bitmask is now ``masks``. Costs those cells and their neighbours."""
        if cells.size:
            self.masks[cells] = masks
            distinct = unique_sorted(masks)
            fresh = [m for m in distinct.tolist() if m not in self._ids]  # new ids, ascending
            if fresh:
                self._ids.update({mask: len(self._ids) + i for i, mask in enumerate(fresh)})
                self.label_masks = np.concatenate([self.label_masks, np.array(fresh, dtype=np.int64)])
                wide = label_index_dtype(len(self.label_masks))
                if np.dtype(wide).itemsize > self.cell_label.dtype.itemsize:
                    self.cell_label = self.cell_label.astype(wide)
            ids = np.array([self._ids[m] for m in distinct.tolist()], dtype=self.cell_label.dtype)
            self.cell_label[cells] = ids[np.searchsorted(distinct, masks)]
        for touched in (moved, cells):
            mark_boundary(graph.cell_at, graph.cell_pos, graph.step_offset, graph.stairs_first,
                          graph.stairs_from, graph.stairs_to, self.cell_label, touched.astype(np.int64), True,
                          self.boundary)
