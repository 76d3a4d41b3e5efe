"""Compiled kernel of :mod:`sgplan.execution.monitor`: run the mission's automaton over every cell a route
passes. See :func:`sgplan.execution.monitor.Monitor` for the route model; the tests check it against
:func:`sgplan.outputs.waypoints.crossed_cells` and :meth:`sgplan.logic.automaton.Automaton.run`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from sgplan.outputs._segments import walk


@njit(cache=True)
def follow(route: np.ndarray, read_first: bool, labels: np.ndarray, traversable: np.ndarray,
           table: np.ndarray, state: int, dead: np.ndarray, states_out: np.ndarray,
           blocked_out: np.ndarray) -> tuple[int, int, int, int, int, int, int, int]:
    """Read the cells from ``route[0]`` to ``route[-1]`` and step the automaton over their labels.

    Parameters
    ----------
    route:
        ``(m, 3)`` int64 ``[row, col, floor]`` rows, all inside the grid. Between two rows on one floor the
        robot passed the straight segment's cells (:func:`sgplan.outputs._segments.walk`: the cells whose
        interior it crosses) -- a single step (8-neighbours) only its end cell, as the planner's move --
        and a repeated cell is not read again; between two floors it took the stairs from one portal
        row to the next.
    read_first:
        whether ``route[0]``'s label is read (the very first cell of a run, under the ``ltlf`` profile);
        otherwise it is the cell the automaton already stands on.
    labels, traversable:
        ``(floors, rows, cols)`` label raster (bit ``i`` = proposition ``i``) and occupancy grid.
    table, state, dead:
        the automaton's ``(states, labels)`` table, the state before ``route[0]``, and ``(states,)``
        bool: the states from which the mission can no longer be completed.
    states_out, blocked_out:
        ``(m,)`` outputs: the state after reaching each row, and whether the segment ending at a row
        crossed a cell the robot may not enter (not counting the rows themselves).

    Returns
    -------
    tuple
        ``(state, cells_read, broken_row, broken_cell_row, broken_cell_col, label_before, label_at,
        state_before)``: the final state, the number of labels read, and where the automaton first went
        from a live state to a ``dead`` one (the route row whose segment did it, the cell, the labels of
        the cell before it -- ``-1`` when it is the first cell read -- and of that cell, the state before
        that cell); ``broken_row`` is ``-1`` when it did not.
    """
    m = route.shape[0]
    extent = 1
    for k in range(1, m):
        extent = max(extent, abs(route[k, 0] - route[k - 1, 0]) + abs(route[k, 1] - route[k - 1, 1]))
    buffer = np.empty((extent + 1, 2), dtype=np.int64)
    q = state
    count = 0
    broken = broken_r = broken_c = before = at = q_before = -1
    previous = labels[route[0, 2], route[0, 0], route[0, 1]]
    if read_first:
        q = table[state, previous]
        count = 1
        if dead[q] and not dead[state]:
            broken, broken_r, broken_c, at, q_before = 0, route[0, 0], route[0, 1], previous, state
    states_out[0] = q
    blocked_out[0] = False
    for k in range(1, m):
        r0, c0, f0 = route[k - 1, 0], route[k - 1, 1], route[k - 1, 2]
        r1, c1, f1 = route[k, 0], route[k, 1], route[k, 2]
        blocked_out[k] = False
        if f0 != f1 or max(abs(r1 - r0), abs(c1 - c0)) <= 1:
            n = 2
            buffer[1, 0], buffer[1, 1] = r1, c1
            if f0 == f1 and r0 == r1 and c0 == c1:
                n = 1  # the same cell again: nothing new read
        else:
            n = walk(r0, c0, r1, c1, buffer)
        for j in range(1, n):  # every cell lies in the box of two cells of the grid: inside it
            r, c = buffer[j, 0], buffer[j, 1]
            if j < n - 1 and not traversable[f1, r, c]:
                blocked_out[k] = True
            label = labels[f1, r, c]
            q_next = table[q, label]
            count += 1
            if broken < 0 and dead[q_next] and not dead[q]:
                broken, broken_r, broken_c, before, at, q_before = k, r, c, previous, label, q
            q = q_next
            previous = label
        states_out[k] = q
    return q, count, broken, broken_r, broken_c, before, at, q_before
