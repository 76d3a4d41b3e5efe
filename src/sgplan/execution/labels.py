"""A run's label raster, kept up to date as objects move: only the propositions of the objects a change
touched are recomputed.

A proposition of an object that is no longer in the building holds nowhere (its raster bit is clear
everywhere): a mission that still needs it becomes impossible, which the run reports, rather than an
error in the middle of a run.
"""

from __future__ import annotations

from collections.abc import Callable, Collection

import numpy as np

from sgplan.intsets import members, unique_sorted
from sgplan.scene.labels import Proposition, proposition_cells, raster_from_cells
from sgplan.scene.model import Building


class RunLabels:
    """The label raster of ``propositions`` (in bit order) over a run's building, with each proposition's
    cells (flat raster positions) kept.

    Parameters
    ----------
    building:
        the building the run starts on.
    propositions:
        the mission's propositions in label-bit order.
    reach_radius_m:
        the reach radius of ``reach`` propositions without their own (metres).
    cells:
        ``cells(prop, reach_radius_m)``: where ``prop`` holds in ``building`` (e.g. a session's
        :meth:`~sgplan.Session.proposition_cells`, kept between missions); default: computed here.
    """

    def __init__(self, building: Building, propositions: list[Proposition], reach_radius_m: float,
                 cells: Callable[[Proposition, float], np.ndarray] | None = None) -> None:
        self.propositions = list(propositions)
        self.reach_radius_m = float(reach_radius_m)
        self.shape = (building.num_floors, *building.grid_shape)
        find = cells or (lambda prop, reach: proposition_cells(building, prop, reach))
        self._cells = [self._where(building, prop, find) for prop in self.propositions]
        self.raster = raster_from_cells(self.shape, self._cells)

    def _where(self, building: Building, prop: Proposition,
               find: Callable[[Proposition, float], np.ndarray]) -> np.ndarray:
        if prop.kind == "reach" and not building.has_object(prop.uuid):
            return np.zeros(0, dtype=np.int64)
        return find(prop, self.reach_radius_m)

    def update(self, building: Building, objects: Collection[int]) -> np.ndarray:
        """The raster after the objects ``objects`` (uuids) moved, appeared or vanished in ``building``;
        returns the flat positions whose label changed (ascending). Costs the touched propositions' cells
        and, if any changed, a copy of the raster (the old one may still be read: a plan made with it)."""
        changed = []
        raster = self.raster.copy()
        flat = raster.reshape(-1)
        for i, prop in enumerate(self.propositions):
            if prop.kind != "reach" or prop.uuid not in objects:
                continue
            new = self._where(building, prop, lambda p, r: proposition_cells(building, p, r))
            bit = raster.dtype.type(1 << i)
            flat[self._cells[i]] &= ~bit
            flat[new] |= bit
            changed += [self._cells[i][~members(self._cells[i], new)], new[~members(new, self._cells[i])]]
            self._cells[i] = new
        positions = unique_sorted(np.concatenate(changed)) if changed else np.zeros(0, dtype=np.int64)
        if positions.size:
            self.raster = raster
        return positions.astype(np.int64)

