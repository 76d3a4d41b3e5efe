"""Compiled kernels of :mod:`sgplan.outputs.waypoints`: the cells a straight segment crosses, and the greedy
path simplification that tests thousands of candidate segments per path (in Python that was 0.06-0.1 s of
every plan, mostly numpy's per-call overhead on short segments). See that module for the contracts.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def walk(r: int, c: int, r1: int, c1: int, out: np.ndarray) -> int:
    """Write the cells crossed from cell ``(r, c)`` to ``(r1, c1)`` into ``out[:k]`` (``(k, 2)`` int64 rows,
    both ends included, corner touches as both side cells then the diagonal one); returns ``k``.
    ``out`` holds at least ``2 * (|r1 - r| + |c1 - c|) + 1`` rows.

    Exact integer arithmetic: from a cell centre the segment crosses its ``m``-th row line at
    ``t = (2m - 1) / (2 |d_row|)`` and its ``n``-th column line at ``t = (2n - 1) / (2 |d_col|)``;
    both at once is a corner. The times are compared by cross-multiplying (a missing axis never comes first).
    """
    dr, dc = abs(r1 - r), abs(c1 - c)
    sr = 1 if r1 > r else -1
    sc = 1 if c1 > c else -1
    out[0, 0], out[0, 1] = r, c
    k = 1
    m = n = 1  # the next row / column line to cross
    while m <= dr or n <= dc:
        row_first = n > dc or (m <= dr and (2 * m - 1) * dc < (2 * n - 1) * dr)
        col_first = m > dr or (n <= dc and (2 * n - 1) * dr < (2 * m - 1) * dc)
        if row_first:
            r += sr
            m += 1
        elif col_first:
            c += sc
            n += 1
        else:  # a corner: both side cells, then the diagonal one
            out[k, 0], out[k, 1] = r + sr, c
            out[k + 1, 0], out[k + 1, 1] = r, c + sc
            k += 2
            r, c = r + sr, c + sc
            m, n = m + 1, n + 1
        out[k, 0], out[k, 1] = r, c
        k += 1
    return k


@njit(cache=True)
def _segment_ok(rows: np.ndarray, i: int, j: int, traversable: np.ndarray, labels: np.ndarray,
                table: np.ndarray, buffer: np.ndarray) -> bool:
    """Whether the straight segment from row ``i`` to row ``j`` may replace rows ``i+1 .. j-1``: one floor,
    no automaton move inside, every crossed cell traversable and a self-loop of the state."""
    floor, q = rows[i, 2], rows[i, 3]
    for k in range(i + 1, j + 1):
        if rows[k, 2] != floor:
            return False
    for k in range(i + 1, j):
        if rows[k, 3] != q:  # the automaton moves inside: keep that cell
            return False
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
    """Indices of the rows of the ``(n, 4)`` path ``rows`` to keep (n > 2): greedy, from each kept row the
    segment is extended row by row while it stays valid (the planner's own move always is)."""
    n = len(rows)
    # Room for the longest segment between any two rows (sized from the path itself, so that a path
    # reaching outside the grid cannot overrun it: its cells are refused, not read).
    extent = rows[:, 0].max() - rows[:, 0].min() + rows[:, 1].max() - rows[:, 1].min()
    buffer = np.empty((2 * extent + 1, 2), dtype=np.int64)
    keep = np.empty(n, dtype=np.int64)
    keep[0] = 0
    kept = 1
    i = 0
    while i < n - 1:
        j = i + 1
        while j + 1 < n and _segment_ok(rows, i, j + 1, traversable, labels, table, buffer):
            j += 1
        keep[kept] = j
        kept += 1
        i = j
    return keep[:kept]
