"""A run's label raster, kept up to date as the building changes: only the propositions a change can
touch are recomputed -- those of the objects it moved, added or removed, and, under the ``visible`` reach
model, those of every object whose reach window holds a cell whose category changed (a new obstacle may
hide the object, a cleared one show it).

A proposition of an object that is no longer in the building holds nowhere (its raster bit is clear
everywhere): a mission that still needs it becomes impossible, which the run reports, rather than an
error in the middle of a run.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping

import numpy as np

from sgplan.intsets import members, unique_sorted
from sgplan.scene.labels import Proposition, proposition_cells, raster_from_cells
from sgplan.scene.model import Building
from sgplan.scene.reach import sight_may_change


class RunLabels:
    """The label raster of ``propositions`` (in bit order) over a run's building, with each proposition's
    cells (flat raster positions) kept.

    Parameters
    ----------
    building:
        the building the run starts on.
    propositions:
        the mission's propositions in label-bit order.
    reach_radius_m, reach_model:
        the reach radius of ``reach`` propositions without their own (metres) and the reach model
        (:mod:`sgplan.scene.reach`).
    cells:
        ``cells(prop, reach_radius_m, reach_model)``: where ``prop`` holds in ``building`` (e.g. a
        session's :meth:`~sgplan.Session.proposition_cells`, kept between missions); default: computed
        here.
    """

    def __init__(self, building: Building, propositions: list[Proposition], reach_radius_m: float,
                 reach_model: str,
                 cells: Callable[[Proposition, float, str], np.ndarray] | None = None) -> None:
        self.propositions = list(propositions)
        self.reach_radius_m = float(reach_radius_m)
        self.reach_model = reach_model
        self.shape = (building.num_floors, *building.grid_shape)
        find = cells or (lambda prop, reach, model: proposition_cells(building, prop, reach, model))
        self._cells = [self._where(building, prop, find) for prop in self.propositions]
        self.raster = raster_from_cells(self.shape, self._cells)

    def _where(self, building: Building, prop: Proposition,
               find: Callable[[Proposition, float, str], np.ndarray]) -> np.ndarray:
        if prop.kind == "reach" and not building.has_object(prop.uuid):
            return np.zeros(0, dtype=np.int64)
        return find(prop, self.reach_radius_m, self.reach_model)

    def _touched(self, building: Building, prop: Proposition, objects: Collection[int],
                 changed: Mapping[int, np.ndarray]) -> bool:
        """Whether a change can have moved where the ``reach`` proposition ``prop`` holds: its object
        changed, or (``visible``) a cell within its object's reach window changed category."""
        if prop.uuid in objects:
            return True
        if not building.has_object(prop.uuid):
            return False
        return sight_may_change(building, building.object(uuid=prop.uuid), changed,
                                prop.reach_radius_m or self.reach_radius_m, self.reach_model)

    def update(self, building: Building, objects: Collection[int],
               changed: Mapping[int, np.ndarray] | None = None) -> np.ndarray:
        """The raster after the objects ``objects`` (uuids) moved, appeared or vanished in ``building`` and
        the cells ``changed`` (floor -> flat positions) changed category; returns the flat positions whose
        label changed (ascending). Costs the touched propositions' cells and, if any changed, a copy of
        the raster (the old one may still be read: a plan made with it)."""
        changed_cells = changed or {}
        touched = []
        raster = self.raster.copy()
        flat = raster.reshape(-1)
        for i, prop in enumerate(self.propositions):
            if prop.kind != "reach" or not self._touched(building, prop, objects, changed_cells):
                continue
            new = self._where(building, prop,
                              lambda p, r, m: proposition_cells(building, p, r, m))
            bit = raster.dtype.type(1 << i)
            flat[self._cells[i]] &= ~bit
            flat[new] |= bit
            touched += [self._cells[i][~members(self._cells[i], new)], new[~members(new, self._cells[i])]]
            self._cells[i] = new
        positions = unique_sorted(np.concatenate(touched)) if touched else np.zeros(0, dtype=np.int64)
        if positions.size:
            self.raster = raster
        return positions.astype(np.int64)

