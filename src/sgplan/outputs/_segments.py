"""Compiled kernels of :mod:`sgplan.outputs.waypoints`: the cells a straight segment crosses, and the path
simplification that tests thousands of candidate segments per path (numpy's per-call overhead on short
segments made it the slowest part of the outputs in Python). See that module for the contracts.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from sgplan.scene._sight import next_crossed


@njit(cache=True)
def walk(r: int, c: int, r1: int, c1: int, out: np.ndarray) -> int:
    """Write the cells whose interior the segment from the centre of cell ``(r, c)`` to the centre of
    ``(r1, c1)`` meets into ``out[:k]`` (``(k, 2)`` int64 rows, in order, both ends included); returns
    ``k``. ``out`` holds at least ``|r1 - r| + |c1 - c| + 1`` rows.

    The steps come from :func:`sgplan.scene._sight.next_crossed` (exact integer arithmetic), the rule the
    reach model's line of sight follows too: where the segment passes through a cell corner it
    touches the two cells beside it in one point only and goes on into the diagonal cell, exactly like
    the planner's own diagonal step.
    """
    dr, dc = abs(r1 - r), abs(c1 - c)
    sr = 1 if r1 > r else -1
    sc = 1 if c1 > c else -1
    out[0, 0], out[0, 1] = r, c
    k = 1
    m = n = 1  # the next row / column line to cross
    while m <= dr or n <= dc:
        r, c, m, n = next_crossed(r, c, m, n, dr, dc, sr, sc)
        out[k, 0], out[k, 1] = r, c
        k += 1
    return k


@njit(cache=True)
def _segment_ok(rows: np.ndarray, i: int, j: int, traversable: np.ndarray, labels: np.ndarray,
                table: np.ndarray, buffer: np.ndarray) -> bool:
    """Whether the straight segment from row ``i`` to row ``j`` (one floor, rows ``i+1 .. j-1`` in row
    ``i``'s state) crosses only traversable cells whose labels are self-loops of that state."""
    floor, q = rows[i, 2], rows[i, 3]
    count = walk(rows[i, 0], rows[i, 1], rows[j, 0], rows[j, 1], buffer)
    num_rows, num_cols = traversable.shape[1], traversable.shape[2]
    for k in range(1, count - 1):
        r, c = buffer[k, 0], buffer[k, 1]
        if r < 0 or c < 0 or r >= num_rows or c >= num_cols or not traversable[floor, r, c]:
            return False
        if table[q, labels[floor, r, c]] != q:
            return False
    return True


@njit(cache=True)
def simplify(rows: np.ndarray, traversable: np.ndarray, labels: np.ndarray, table: np.ndarray) -> np.ndarray:
    """Indices of the rows of the ``(n, 4)`` path ``rows`` to keep (n > 2): from each kept row, the farthest
    row of the same floor and automaton state that a valid segment reaches (the next row always is: it is
    the planner's own move)."""
    n = len(rows)
    # Room for the longest segment between any two rows (sized from the path itself, so that a path
    # reaching outside the grid cannot overrun it: its cells are refused, not read).
    extent = rows[:, 0].max() - rows[:, 0].min() + rows[:, 1].max() - rows[:, 1].min()
    buffer = np.empty((extent + 1, 2), dtype=np.int64)
    keep = np.empty(n, dtype=np.int64)
    keep[0] = 0
    kept = 1
    i = 0
    while i < n - 1:
        floor, q = rows[i, 2], rows[i, 3]
        j = i + 1
        # Visibility along a path is not monotone (a wall may hide a stretch that a later row sees past),
        # so every row up to the next change of floor or state is tried, not only until the first miss.
        t = i + 2
        while t < n and rows[t, 2] == floor and rows[t - 1, 2] == floor and rows[t - 1, 3] == q:
            if _segment_ok(rows, i, t, traversable, labels, table, buffer):
                j = t
            t += 1
        keep[kept] = j
        kept += 1
        i = j
    return keep[:kept]
