"""Sets of integers (cell numbers, raster positions) as ascending numpy arrays, by sorting.

``np.unique`` of the NumPy this project runs on hashes integer arrays before sorting them, which on the
tens of thousands of cells a scene change touches costs far more than a sort
(benchmarks/results/comment_measurements.md); these helpers sort.
"""

from __future__ import annotations

import numpy as np


def unique_sorted(values: np.ndarray) -> np.ndarray:
    """The distinct values of ``values``, ascending (as ``np.unique``, by one sort)."""
    ordered = np.sort(np.asarray(values).reshape(-1))
    if ordered.size < 2:
        return ordered
    keep = np.empty(ordered.size, dtype=bool)
    keep[0] = True
    np.not_equal(ordered[1:], ordered[:-1], out=keep[1:])
    return ordered[keep]


def members(values: np.ndarray, of: np.ndarray) -> np.ndarray:
    """Bool per value of ``values``: whether it is in ``of`` (ascending, distinct), by binary search."""
    values = np.asarray(values)
    if of.size == 0:
        return np.zeros(values.shape, dtype=bool)
    at = np.minimum(np.searchsorted(of, values), of.size - 1)
    return of[at] == values
