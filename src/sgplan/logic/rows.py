"""Distinct rows of a 2-D integer array, fast for wide rows."""

from __future__ import annotations

import numpy as np


def unique_rows(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(first, inverse)``: the index of one row of each distinct kind, and each row's kind.

    ``rows[first[inverse]]`` equals ``rows`` row by row. Kinds are numbered in the byte order of
    their rows (a fixed but not a numeric order). Each row is compared as one opaque byte string:
    ``np.unique(axis=0)`` builds a structured dtype with one field per column, whose cost grows with
    the row width (``2**len(aps)`` labels for an automaton table).
    """
    if rows.shape[1] == 0:  # every row is the empty row
        return np.zeros(min(1, rows.shape[0]), np.int64), np.zeros(rows.shape[0], np.int64)
    packed = np.ascontiguousarray(rows)
    as_bytes = packed.view(np.dtype((np.void, packed.dtype.itemsize * packed.shape[1]))).ravel()
    _, first, inverse = np.unique(as_bytes, return_index=True, return_inverse=True)
    return first, inverse.ravel().astype(np.int64)
