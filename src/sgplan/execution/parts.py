"""The planner's parts of a run's building, carried from one version of the building to the next.

A :class:`sgplan.Session` keeps the parts that depend only on the building (:mod:`sgplan.planning.shared`)
keyed by the grid they were built for. A run's building changes; :class:`RunParts` serves the planning
problems of the run's *current* building -- an incremental planning domain -- and on
:meth:`RunParts.advance` carries over what a change did not void, updating the rest from the cells the
change touched:

- the cell graph keeps the run's one numbering (:mod:`sgplan.execution.graph`): the change only masks
  or unmasks the cells whose traversability changed;
- the cells' labels -- bitmasks, compact label ids, label boundaries -- are updated at the cells that
  changed and around them (:mod:`sgplan.execution.cell_labels`);
- the robot's connected component is followed across the change (:mod:`sgplan.execution.component`),
  not flooded anew;
- the h_LTL distance fields are kept as one matrix and repaired from the cells that left or joined the
  graph or changed label (:mod:`sgplan.execution.fields`), not recomputed;
- the composite action tables keep their families and indices; the maps and label runs that a change
  may have altered (those of the rooms or floors it touched, of moved objects, of rooms the robot can
  reach more of) are forgotten and rebuilt by the next search that needs them
  (:mod:`sgplan.execution.actions`).

Every plan over these parts equals a plan over parts built afresh for the changed building
(``tests/execution/test_parts.py``, ``test_component.py``, ``test_cell_labels.py``, ``test_fields.py``).
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Collection, Hashable, Mapping
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from sgplan.execution.actions import RunActions, with_other_labels
from sgplan.execution.cell_labels import CellLabels
from sgplan.execution.component import Component
from sgplan.execution.fields import FieldStore
from sgplan.execution.graph import LabelMask, OutsideNumbering, candidate_graph, masked_graph, remasked
from sgplan.execution.regrid import GridChange
from sgplan.intsets import unique_sorted
from sgplan.planning.cells import CellGraph
from sgplan.planning.domain import KeptParts
from sgplan.planning.shared import SharedParts
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building

if TYPE_CHECKING:
    from sgplan.planning.domain import ActionParts
    from sgplan.planning.problem import PlanningProblem

T = TypeVar("T")

class RunParts(SharedParts, KeptParts):
    """Planner parts for the problems of one run's current grid and labels (see the module).

    Parameters
    ----------
    grid:
        the run's occupancy grid before any change.
    labels:
        its label raster (``(floors, rows, cols)`` bitmasks of the mission's propositions).
    scene:
        the building of ``grid`` without its blocks and closed doors (which cells could become
        traversable: :func:`~sgplan.execution.graph.candidate_graph`).

    Every part is the run's own and kept (no byte cap: the run's parts grow with its building, not with
    the missions planned).
    """

    def __init__(self, grid: OccupancyGrid, labels: np.ndarray, scene: Building) -> None:
        super().__init__()
        self._number(grid, labels, candidate_graph(grid, scene))

    def _number(self, grid: OccupancyGrid, labels: np.ndarray, candidates: CellGraph) -> None:
        """Serve ``grid`` and ``labels`` over the numbering ``candidates``, every per-cell part anew."""
        self.grid, self.labels, self.candidates = grid, labels, candidates
        self.graph = masked_graph(candidates, grid.traversable)
        self.labelling = CellLabels(candidates, self.graph, labels)
        self.fatal = LabelMask()
        self.component = Component()
        self.fields = FieldStore()
        self.actions = RunActions(candidates)
        self._parts.clear()

    def with_labels(self, labels: np.ndarray) -> RunParts:
        """Parts for the same grid and numbering with other labels (another mission's propositions): the
        labels, the component and the fields anew. Costs a pass over the cells."""
        other = copy.copy(self)
        other._parts = type(self._parts)()
        other.labels, other.labelling = labels, CellLabels(self.candidates, self.graph, labels)
        other.fatal, other.component, other.fields = LabelMask(), Component(), FieldStore()
        other.actions = with_other_labels(self.actions)
        return other

    @property
    def keeps(self) -> bool:
        return True

    @property
    def masks(self) -> np.ndarray:
        """``(N,)`` the label bitmask of every cell of the numbering."""
        return self.labelling.masks

    def _serves(self, grid: Hashable, graph: CellGraph | None = None) -> None:
        if grid is not self.grid or (graph is not None and graph is not self.graph):
            raise ValueError("the run's parts serve its current grid and cell graph only")

    def get(self, name: str, key: Hashable, build: Callable[[], T]) -> T:
        """As :meth:`SharedParts.get`, for the current grid only; the cell graph is the run's masked one."""
        self._serves(key[0] if isinstance(key, tuple) else key)
        if name == "cell_graph":
            part: Any = self.graph
            return part
        return super().get(name, key, build)

    def cell_labels(self, grid: Hashable, graph: CellGraph, labels: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
        """The compact labels kept (:class:`~sgplan.execution.cell_labels.CellLabels`): ids are the run's,
        so some may be unused."""
        self._serves(grid, graph)
        if labels is not self.labels:
            raise ValueError("the run's parts serve its current labels only")
        return self.labelling.label_masks, self.labelling.cell_label

    def _avoiding(self, avoid: np.ndarray) -> CellGraph:
        """The graph without the cells of the bitmasks ``avoid`` (:class:`~sgplan.execution.graph.LabelMask`);
        the component and the fields start afresh when ``avoid`` changes (another mission's)."""
        if self.fatal.set(self.graph, self.labelling.masks, avoid):
            self.component, self.fields = Component(), FieldStore()
        return self.fatal.of(self.graph)

    def reachable(self, grid: Hashable, graph: CellGraph, start_cell: int, avoid: np.ndarray) -> np.ndarray:
        """The component kept (:class:`~sgplan.execution.component.Component`), over the graph without the
        cells of ``avoid``."""
        self._serves(grid, graph)
        graph = self._avoiding(avoid)  # first: it may start the component afresh
        return self.component.of(graph, start_cell)

    def label_boundary(self, grid: Hashable, graph: CellGraph) -> np.ndarray:
        self._serves(grid, graph)
        return self.labelling.boundary

    def label_fields(self, grid: Hashable, graph: CellGraph, masks: np.ndarray, unit_m: float,
                     avoid: np.ndarray) -> np.ndarray | float:
        """The fields kept by bitmask (:class:`~sgplan.execution.fields.FieldStore`), each to its whole
        region: equal to the field of the region's part reachable from the start on every cell reachable
        from it, the only cells h_LTL reads; over the graph without the cells of ``avoid``."""
        self._serves(grid, graph)
        graph = self._avoiding(avoid)  # first: it may start the fields afresh
        return self.fields.fields(graph, self.labelling.masks, [int(m) for m in masks], unit_m)

    def action_parts(self, problem: PlanningProblem, graph: CellGraph, cell_label: np.ndarray,
                     reachable: np.ndarray) -> ActionParts:
        """The composite action parts kept across changes (:class:`~sgplan.execution.actions.RunActions`);
        ``cell_label`` is the run's own (:meth:`cell_labels`)."""
        self._serves(problem.grid, graph)
        return self.actions.parts(problem, reachable)

    def advance(self, grid: OccupancyGrid, change: GridChange, labels: np.ndarray, relabelled: np.ndarray,
                scene: Building, at: tuple[int, int, int] | None = None, objects: Collection[int] = (),
                changed: Mapping[int, np.ndarray] | None = None) -> None:
        """Serve ``grid`` and ``labels`` from now on: the grid and labels after a scene change whose effect
        on traversability is ``change`` and which changed the labels at the flat raster positions
        ``relabelled``; ``scene``: the changed building without its blocks and closed doors; ``at``: the
        robot's cell ``(row, col, floor)``, if known (whose component to follow); ``objects``: the uuids of
        the objects the change moved, added or removed; ``changed``: the cells (floor -> flat positions)
        whose category changed (lines of sight to objects may cross them).

        Costs a copy of the graph's padded index, and work over the changed cells and their neighbours
        (the fields are repaired when next asked for; the component may flood the smaller side of a
        split). A change that made traversable a cell the numbering does not hold
        (:class:`~sgplan.execution.graph.OutsideNumbering`) numbers the cells anew, with every part
        rebuilt."""
        try:
            graph, moved = remasked(self.graph, self.candidates, change, in_place=True)
        except OutsideNumbering:
            self._number(grid, labels, candidate_graph(grid, scene))
            return
        cells = self.candidates.cell_ids(relabelled)
        held = cells >= 0
        cells, positions = cells[held], relabelled[held]
        before = self.labelling.masks[cells]
        self.graph = graph
        self.labelling.update(graph, moved, cells, labels.reshape(-1)[positions])
        self.actions.advance(moved, np.sort(cells), objects, changed)
        # Over the graph without the fatal labels' cells, a relabelled cell may have left or joined it too.
        switched = cells[self.fatal.avoided(self.labelling.masks[cells]) != self.fatal.avoided(before)]
        if switched.size:
            moved = unique_sorted(np.concatenate([moved, switched]))
        self.fatal.update(graph, moved, self.labelling.masks)
        avoiding = self.fatal.of(graph)
        self.fields.changed(moved, cells, before)
        self.component.update(avoiding, moved, None if at is None else avoiding.cell_id(*at))
        self.grid, self.labels = grid, labels
