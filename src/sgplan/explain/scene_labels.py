"""The label sets a scene can actually produce for a mission's propositions.

A label (bitmask over the automaton's propositions) is *realizable* when some cell carries it: rooms
are exclusive (a cell lies in one room), and an object is reached only from the cells of its reach region
(:func:`sgplan.scene.labels.label_raster`, the one source of truth for labels). Which cells count
is the caller's choice: every cell inside a room (the explanation: independent of the robot's size), or
the free cells of an occupancy grid (the pre-planning checks).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial

import numpy as np

from sgplan.errors import MissionError
from sgplan.scene.labels import MAX_PROPOSITIONS, Proposition, proposition_cells, raster_from_cells
from sgplan.scene.model import Building
from sgplan.scene.reach import DEFAULT_REACH_MODEL


def occurring_labels(labels: np.ndarray, where: np.ndarray, num_labels: int) -> np.ndarray:
    """``(num_labels,)`` bool: the labels of ``labels`` (any shape) that occur where ``where`` is True."""
    values = labels[where]
    if values.size and int(values.min()) >= 0 and int(values.max()) < max(num_labels, 1 << 16):
        # Counting is linear; sorting (np.unique) a scene's million cells is not, and this runs per check.
        return np.bincount(values.astype(np.intp, copy=False), minlength=num_labels)[:num_labels] > 0
    present = np.zeros(num_labels, bool)
    values = np.unique(values)
    present[values[(values >= 0) & (values < num_labels)].astype(np.int64)] = True
    return present


def in_room_cells(building: Building) -> np.ndarray:
    """``(floors, rows, cols)`` bool: the cells that lie inside some room."""
    return np.stack([floor.room_map > 0 for floor in building.floors])


def realizable_labels(propositions: Sequence[Proposition], building: Building,
                      reach_radius_m: float | None = None, *, reach_model: str = DEFAULT_REACH_MODEL,
                      cells: Callable[[Proposition, float, str], np.ndarray] | None = None) -> np.ndarray:
    """``(2**len(propositions),)`` bool: the labels (bit ``i`` = ``propositions[i]``) that some in-room
    cell of ``building`` carries (reach radius: the given one, else the scene's, else the default of
    :mod:`sgplan.radii`; objects reached under ``reach_model``).

    The labels are those of :func:`~sgplan.scene.labels.label_raster`, made from
    ``cells(prop, radius, reach_model)``: the flat cell indices of one proposition, as
    :func:`~sgplan.scene.labels.proposition_cells` (the
    default) gives them, or a :class:`sgplan.Session`'s, which keeps them for the plan that follows
    (finding them is most of the cost).

    Raises
    ------
    SceneError
        a proposition names an entity the building lacks.
    MissionError
        more propositions than a label holds, or a reach proposition without a radius.
    """
    from sgplan.radii import resolve_radii

    if len(propositions) > MAX_PROPOSITIONS:  # as label_raster: a label is at most a uint32 bitmask
        raise MissionError(
            f"{len(propositions)} propositions given; a label holds at most {MAX_PROPOSITIONS}"
        )
    radius = resolve_radii(building).reach_m if reach_radius_m is None else reach_radius_m
    cells_of = cells or partial(proposition_cells, building)
    floors, (rows, cols) = building.num_floors, building.grid_shape
    labels = raster_from_cells((floors * rows * cols,),
                               [cells_of(prop, radius, reach_model) for prop in propositions])
    return occurring_labels(labels, in_room_cells(building).reshape(-1), 1 << len(propositions))
