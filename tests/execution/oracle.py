"""Test oracle of the runtime monitor: the cells a robot passed between its poses and the automaton stepped
over them one by one, in plain Python (:func:`sgplan.outputs.waypoints.crossed_cells` and
:meth:`sgplan.logic.automaton.Automaton.run`, both tested on their own), independent of the monitor's
compiled kernel and its batching."""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.outputs.waypoints import crossed_cells
from sgplan.scene.grid import OccupancyGrid

Cell = tuple[int, int, int]


def _on_one_floor(a: Cell, b: Cell) -> list[Cell]:
    """The cells read going from ``a`` to ``b`` on one floor, ``a`` excluded."""
    if a == b:
        return []
    if max(abs(a[0] - b[0]), abs(a[1] - b[1])) <= 1:
        return [b]
    return [(int(r), int(c), a[2]) for r, c in crossed_cells(a[:2], b[:2])[1:]]


def cells_read(poses: Sequence[Cell], grid: OccupancyGrid) -> list[list[Cell]]:
    """Per pose, the cells read when it is reached (the first pose: itself); stairs portal to portal."""
    links = {link.lower_floor: link for link in grid.stairs}
    out: list[list[Cell]] = [[tuple(poses[0])]]
    for a, b in itertools.pairwise(poses):
        here, cells = tuple(a), []
        while here[2] != b[2]:
            up = b[2] > here[2]
            link = links[here[2] if up else here[2] - 1]
            lower, upper = (*link.lower_cell, link.lower_floor), (*link.upper_cell, link.upper_floor)
            leave, arrive = (lower, upper) if up else (upper, lower)
            cells += _on_one_floor(here, leave) + [arrive]
            here = arrive
        out.append(cells + _on_one_floor(here, tuple(b)))
    return out


def states_after_poses(poses: Sequence[Cell], grid: OccupancyGrid, labels: np.ndarray, automaton: Automaton,
                       profile: str = "ltlf") -> tuple[list[int], list[int]]:
    """The automaton state after each pose, and the states after every cell read (in order)."""
    per_pose = cells_read(poses, grid)
    if profile == "authors":
        per_pose[0] = []  # the start cell's label is not read
    word = [int(labels[f, r, c]) for cells in per_pose for r, c, f in cells]
    states = automaton.run(word).tolist()
    ends = np.cumsum([len(cells) for cells in per_pose])
    return [states[int(end)] for end in ends], states[1:]
