"""An independent checker of planned paths.

It shares no code with the search: given a path of cells with the automaton state after each cell, it
checks that consecutive cells are joined by legal moves (an 8-connected step on one floor, or the stairs
between two portals), that every cell may be entered, that the automaton states follow from the cell
labels under the chosen semantics profile, and that the path ends in an accepting state; and it
recomputes the path's cost in metres.

Its independence is deliberate, and so are the near-copies it keeps: it takes only the profiles' names
from the planner (:data:`~sgplan.planning.setups.PROFILES`), restates what each profile means (``ltlf``
reads the start cell's label, ``authors`` does not) and checks a profile with its own ``ValueError``
rather than :func:`~sgplan.planning.setups.check_profile`, so that a mistake in the planner's semantics
cannot also pass the check.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.planning.setups import PROFILES
from sgplan.scene.grid import OccupancyGrid


@dataclass(frozen=True)
class PathCheck:
    """Outcome of :func:`check_path`.

    ``cost_m`` is the recomputed cost (sum of step and stairs costs, metres; ``inf`` when a move is
    illegal). ``problems`` lists what is wrong, the first few of each kind, empty iff ``valid``.
    """

    valid: bool
    cost_m: float
    problems: tuple[str, ...]


def check_path(
    path: np.ndarray,
    grid: OccupancyGrid,
    labels: np.ndarray,
    automaton: Automaton,
    profile: str = "ltlf",
    start_state: int | None = None,
) -> PathCheck:
    """Check a path against the grid, the labels and the automaton.

    Parameters
    ----------
    path:
        ``(n, 4)`` integer array of ``[row, col, floor, q]`` rows, one per visited cell, start first;
        ``q`` is the automaton state after the cell's label was read (for the start cell under the
        ``authors`` profile, which does not read it: the initial state).
    grid:
        the occupancy grid the path must stay in.
    labels:
        ``(floors, rows, cols)`` label bitmasks in the automaton's proposition order.
    automaton:
        the mission automaton.
    profile:
        ``"ltlf"`` (start label read) or ``"authors"`` (start label not read).
    start_state:
        a path that resumes a mission: the automaton state at its first cell, that cell's label already
        read (``profile`` then plays no part); ``None``: from the initial state, as ``profile`` says.

    Returns
    -------
    PathCheck
    """
    if profile not in PROFILES:
        raise ValueError(f"unknown profile {profile!r}; expected one of {PROFILES}")
    path = np.asarray(path, dtype=np.int64)
    if path.ndim != 2 or path.shape[1] != 4 or len(path) == 0:
        return PathCheck(False, float("inf"), ("path must be a non-empty (n, 4) array [row, col, floor, q]",))
    problems: list[str] = []
    rows, cols, floors, states = path[:, 0], path[:, 1], path[:, 2], path[:, 3]

    f_max, r_max, c_max = grid.shape
    inside = (rows >= 0) & (rows < r_max) & (cols >= 0) & (cols < c_max) & (floors >= 0) & (floors < f_max)
    if not inside.all():
        k = int(np.flatnonzero(~inside)[0])
        return PathCheck(False, float("inf"), (f"cell {k} {tuple(path[k, :3])} lies outside the grid",))
    blocked = np.flatnonzero(~grid.traversable[floors, rows, cols])
    problems += [f"cell {k} {tuple(path[k, :3])} is not traversable" for k in blocked[:3]]

    cost_m, move_problems = _moves_cost(path, grid)
    problems += move_problems

    expected = _expected_states(labels[floors, rows, cols], automaton, profile, start_state)
    wrong = np.flatnonzero(expected != states)
    problems += [
        f"cell {k} {tuple(path[k, :3])} has state {states[k]}, the automaton gives {expected[k]}"
        for k in wrong[:3]
    ]
    if not automaton.accepting[expected[-1]]:
        problems.append(f"the path ends in state {expected[-1]}, which is not accepting")
    return PathCheck(not problems, cost_m if not move_problems else float("inf"), tuple(problems))


def _moves_cost(path: np.ndarray, grid: OccupancyGrid) -> tuple[float, list[str]]:
    """Total cost of the moves between consecutive cells and the illegal ones (first few)."""
    res_x, res_y = grid.resolution_m
    step = np.diff(path[:, :3], axis=0)
    same_floor = step[:, 2] == 0
    d_row, d_col = np.abs(step[:, 0]), np.abs(step[:, 1])
    grid_step = same_floor & (np.maximum(d_row, d_col) == 1)
    step_cost = np.hypot(d_row * res_x, d_col * res_y)

    stairs: dict[tuple[tuple[int, ...], tuple[int, ...]], float] = {}
    for link in grid.stairs:
        lower = (link.lower_cell[0], link.lower_cell[1], link.lower_floor)
        upper = (link.upper_cell[0], link.upper_cell[1], link.upper_floor)
        stairs[(lower, upper)] = stairs[(upper, lower)] = link.cost_m

    total = float(step_cost[grid_step].sum())
    problems: list[str] = []
    for k in np.flatnonzero(~grid_step):
        a, b = tuple(int(v) for v in path[k, :3]), tuple(int(v) for v in path[k + 1, :3])
        if (a, b) in stairs:
            total += stairs[(a, b)]
        elif len(problems) < 3:
            problems.append(f"no legal move from cell {k} {a} to cell {k + 1} {b}")
        else:
            break
    return total, problems


def _expected_states(path_labels: np.ndarray, automaton: Automaton, profile: str,
                     start_state: int | None) -> np.ndarray:
    """Automaton state after each cell of the path, from the labels alone."""
    q = automaton.initial if start_state is None else int(start_state)
    expected = np.empty(len(path_labels), dtype=np.int64)
    for k, label in enumerate(path_labels):
        if k > 0 or (profile == "ltlf" and start_state is None):
            q = int(automaton.table[q, int(label)])
        expected[k] = q
    return expected
