"""Binary dilations of small 2-D masks in plain numpy: the reach regions of objects.

scipy.ndimage would do both, but importing it costs every plan time and memory; these masks are an
object's bounding box grown by the reach radius (a few thousand cells), where numpy is as fast.
"""

from __future__ import annotations

import numpy as np


def _runs_any(mask: np.ndarray, before: int, after: int, axis: int) -> np.ndarray:
    """``out[i] = any(mask[i - before .. i + after])`` along ``axis`` (cells beyond the mask are False)."""
    moved = np.moveaxis(mask, axis, -1)
    n = moved.shape[-1]
    counts = np.zeros((*moved.shape[:-1], n + 1), dtype=np.int32)
    np.cumsum(moved, axis=-1, dtype=np.int32, out=counts[..., 1:])
    idx = np.arange(n)
    hi = np.minimum(idx + after + 1, n)
    lo = np.clip(idx - before, 0, n)
    out = counts[..., hi] > counts[..., lo]
    return np.moveaxis(out, -1, axis)


def box_dilate(mask: np.ndarray, half: tuple[int, int]) -> np.ndarray:
    """Cells whose window of ``2 * half + 1`` rows x columns (centred) holds a True cell of ``mask``.

    Equals ``scipy.ndimage.maximum_filter(mask, size=2 * half + 1, mode="constant", cval=0)``; bool.
    """
    rows = _runs_any(np.asarray(mask, dtype=bool), half[0], half[0], axis=0)
    return _runs_any(rows, half[1], half[1], axis=1)


def radius_widths(
    resolution_m: tuple[float, float], radius_m: float, max_rows: int, max_cols: int
) -> np.ndarray:
    """``widest[k]`` for row offsets ``k = 0 .. min(int(radius_m / res_r) + 1, max_rows)``: the largest
    column offset (at most ``min(int(radius_m / res_c) + 1, max_cols)``) whose cell centre lies within
    ``radius_m`` metres of the centre at offset ``(0, 0)``, or -1 when not even column offset 0 does;
    int64. Every column offset up to ``widest[k]`` lies within the radius too.

    "Within" is ``sqrt((dr * res_r) ** 2 + (dc * res_c) ** 2) <= radius_m`` in float64: the one test of
    :func:`within_distance` and of the ``visible`` reach model (:mod:`sgplan.scene.reach`).
    """
    res_r, res_c = float(resolution_m[0]), float(resolution_m[1])
    reach_r = min(int(radius_m / res_r) + 1, max_rows)
    reach_c = np.arange(min(int(radius_m / res_c) + 1, max_cols) + 1)
    offsets = np.arange(reach_r + 1)
    inside = np.sqrt((offsets[:, None] * res_r) ** 2 + (reach_c[None, :] * res_c) ** 2) <= radius_m
    # The distance grows with the column offset, so "inside" is a prefix of each row.
    widest = np.where(inside[:, 0], inside.shape[1] - 1 - np.argmax(inside[:, ::-1], axis=1), -1)
    return widest.astype(np.int64)


def within_distance(footprint: np.ndarray, resolution_m: tuple[float, float], radius_m: float) -> np.ndarray:
    """Cells whose centre lies within ``radius_m`` metres (Euclidean, cell centres, ``resolution_m`` =
    metres per row and per column) of a True cell of ``footprint``; bool, same shape.

    Equals ``scipy.ndimage.distance_transform_edt(~footprint, sampling=resolution_m) <= radius_m`` when
    ``footprint`` has a True cell (the distance is computed the same way, :func:`radius_widths`).
    Separable: the column distance to the nearest True cell of each row first, then one integer test per
    row offset within the radius, on the rows holding True cells only.
    """
    footprint = np.asarray(footprint, dtype=bool)
    rows, cols = footprint.shape
    out = np.zeros(footprint.shape, dtype=bool)
    used = np.flatnonzero(footprint.any(axis=1))
    if used.size == 0:
        return out
    first, last = int(used[0]), int(used[-1]) + 1
    col = np.arange(cols)
    big = 2 * cols + 1  # "no True cell in this row": farther than any kernel half-width
    part = footprint[first:last]
    left = np.maximum.accumulate(np.where(part, col, -big), axis=1)
    right = np.minimum.accumulate(np.where(part, col, big)[:, ::-1], axis=1)[:, ::-1]
    dc = np.minimum(col - left, right - col)  # columns to the nearest True cell of the row
    widest = radius_widths(resolution_m, radius_m, rows, cols)
    for offset, k in enumerate(widest.tolist()):
        if k < 0:
            continue
        for dr in {offset, -offset}:
            lo, hi = max(first - dr, 0), min(last - dr, rows)  # rows i whose row i + dr holds True cells
            if lo < hi:
                out[lo:hi] |= dc[lo + dr - first:hi + dr - first] <= k
    return out
