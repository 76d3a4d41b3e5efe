"""The planner's parts of a run's building, carried from one version of the building to the next.

A :class:`sgplan.Session` keeps the parts that depend only on the building (:mod:`sgplan.planning.shared`)
keyed by the grid they were built for. A run's building changes; :class:`RunParts` serves the planning
problems of the run's *current* building, and on :meth:`RunParts.advance` carries over what a change did
not void:

- the cell graph keeps the run's one numbering (:mod:`sgplan.execution.graph`): the change only masks
  or unmasks the cells whose traversability changed;
- the h_LTL distance fields are repaired from the cells that left or joined the graph or changed label
  (:mod:`sgplan.execution.fields`), not recomputed;
- the composite action tables, their maps and label runs are dropped and rebuilt lazily by the next
  search that needs them (they depend on the start's component and on exact shortest paths that a
  change may lengthen or shorten anywhere on a floor).
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Any, TypeVar

import numpy as np

from sgplan.execution.fields import FieldStore
from sgplan.execution.graph import OutsideNumbering, candidate_graph, masked_graph, remasked
from sgplan.execution.regrid import GridChange
from sgplan.planning.cells import CellGraph
from sgplan.planning.shared import SharedParts
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building

T = TypeVar("T")

_PER_VERSION = ("action_tables", "action_maps", "label_runs")
"""Parts rebuilt lazily after each change (see the module)."""


class RunParts(SharedParts):
    """Planner parts for the problems of one run's current grid and labels (see the module).

    Parameters
    ----------
    grid:
        the run's occupancy grid before any change.
    labels:
        its label raster (``(floors, rows, cols)`` bitmasks of the mission's propositions).
    building:
        the building of ``grid`` (which cells could become traversable: :mod:`sgplan.execution.graph`).
    max_bytes:
        the cap of the parts rebuilt per version (action tables and maps), as :class:`SharedParts`;
        the graph and the fields are the run's own and always kept.
    """

    def __init__(self, grid: OccupancyGrid, labels: np.ndarray, building: Building,
                 max_bytes: int | None = None) -> None:
        super().__init__(max_bytes)
        self.grid = grid
        self.candidates = candidate_graph(grid, building)
        self.graph = masked_graph(self.candidates, grid.traversable)
        self.fields = FieldStore()
        self.labels = labels
        self.masks = self.graph.gather(labels)

    @property
    def keeps(self) -> bool:
        return True

    def get(self, name: str, key: Hashable, build: Callable[[], T]) -> T:
        """As :meth:`SharedParts.get`, for the current grid only; the cell graph is the run's masked one."""
        grid = key[0] if isinstance(key, tuple) else key
        if grid is not self.grid:
            raise ValueError(f"the run's parts serve its current grid only, not another ({name})")
        if name == "cell_graph":
            part: Any = self.graph
            return part
        return super().get(name, key, build)

    def distance_field(self, grid: Hashable, graph: CellGraph, cells: np.ndarray, unit_m: float
                       ) -> np.ndarray | float:
        """The field to the whole label region ``cells`` belong to (:class:`FieldStore`): equal to the
        field of ``cells`` (its part reachable from the start) on every cell reachable from the start, the
        only cells h_LTL reads."""
        if grid is not self.grid or graph is not self.graph:
            raise ValueError("the run's parts serve its current grid and cell graph only")
        return self.fields.field(graph, self.masks, int(self.masks[int(cells[0])]), unit_m)

    def advance(self, grid: OccupancyGrid, change: GridChange, labels: np.ndarray, relabelled: np.ndarray,
                building: Building) -> None:
        """Serve ``grid`` and ``labels`` from now on: the grid and labels after a scene change whose effect
        on traversability is ``change`` and which changed the labels at the flat raster positions
        ``relabelled``.

        Costs a copy of the graph's padded index and of the cells' bitmasks, and bookkeeping of the changed
        cells (the fields are repaired when next asked for). A change that made traversable a cell the
        numbering does not hold (:class:`~sgplan.execution.graph.OutsideNumbering`) numbers the cells anew,
        with every part rebuilt."""
        try:
            self.graph, moved = remasked(self.graph, self.candidates, change)
        except OutsideNumbering:
            self.candidates = candidate_graph(grid, building)
            self.graph = masked_graph(self.candidates, grid.traversable)
            self.fields.forget()
            self.grid, self.labels, self.masks = grid, labels, self.graph.gather(labels)
            self._parts.clear()
            return
        cells = self.candidates.cell_ids(relabelled)
        held = cells >= 0
        cells, positions = cells[held], relabelled[held]
        masks = self.masks.copy()
        masks[cells] = labels.reshape(-1)[positions]
        self.fields.changed(moved, cells, self.masks[cells])
        self.grid, self.labels, self.masks = grid, labels, masks
        for slot in [slot for slot in self._parts if slot[0] in _PER_VERSION]:
            del self._parts[slot]
