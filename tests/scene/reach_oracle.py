"""The ``visible`` reach model by brute force, sharing no code with :mod:`sgplan.scene.reach` or its
kernels: every floor cell against every object cell, and the cells a segment crosses found by clipping the
segment to each cell's open square with exact fractions (not by walking grid lines, nor by separating
axes). Slow: for the tests' small buildings only.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from sgplan.scene.model import CatCode, Floor, SceneObject


def _open_interval(start: int, delta: int, lo: int, hi: int) -> tuple[Fraction, Fraction] | None:
    """The times ``t`` (any real) with ``lo < start + t * delta < hi``, as an open interval; ``None`` if
    empty. An unbounded side is returned as +-2 (the segment only lives on ``[0, 1]``)."""
    if delta == 0:
        return (Fraction(-2), Fraction(2)) if lo < start < hi else None
    a, b = Fraction(lo - start, delta), Fraction(hi - start, delta)
    return (min(a, b), max(a, b))


def crosses(p: tuple[int, int], q: tuple[int, int], cell: tuple[int, int]) -> bool:
    """Whether the closed segment between the centres of cells ``p`` and ``q`` meets the open square of
    ``cell`` (unit cells: cell ``(r, c)`` is ``(r, r + 1) x (c, c + 1)``, doubled here to stay integral)."""
    p0 = (2 * p[0] + 1, 2 * p[1] + 1)
    d = (2 * (q[0] - p[0]), 2 * (q[1] - p[1]))
    rows = _open_interval(p0[0], d[0], 2 * cell[0], 2 * cell[0] + 2)
    cols = _open_interval(p0[1], d[1], 2 * cell[1], 2 * cell[1] + 2)
    if rows is None or cols is None:
        return False
    lo, hi = max(rows[0], cols[0]), min(rows[1], cols[1])
    # Open intervals meet in an open interval; it must meet the closed [0, 1].
    return lo < hi and lo < 1 and hi > 0


def crossed_cells(p: tuple[int, int], q: tuple[int, int]) -> list[tuple[int, int]]:
    """Every cell the segment between the centres of ``p`` and ``q`` crosses (within their bounding box,
    where the segment lies)."""
    return [
        (r, c)
        for r in range(min(p[0], q[0]), max(p[0], q[0]) + 1)
        for c in range(min(p[1], q[1]), max(p[1], q[1]) + 1)
        if crosses(p, q, (r, c))
    ]


def visible_reach(floor: Floor, obj: SceneObject, radius_m: float) -> np.ndarray:
    """``(rows, cols)`` bool: the object's cells, and the floor cells within ``radius_m`` (float64
    ``sqrt((dr * res_r) ** 2 + (dc * res_c) ** 2) <= radius_m``) of an object cell whose segment crosses
    only floor cells, object cells and non-floor cells of the object's room."""
    cat, room = floor.cat_map, floor.room_map
    target = cat == obj.id
    see_through = (cat == CatCode.GROUND) | target | (room == obj.room_id)
    res_r, res_c = floor.resolution_m
    out = target.copy()
    targets = [tuple(t) for t in np.argwhere(target).tolist()]
    for p in map(tuple, np.argwhere(cat == CatCode.GROUND).tolist()):
        for t in targets:
            if np.sqrt(((t[0] - p[0]) * res_r) ** 2 + ((t[1] - p[1]) * res_c) ** 2) > radius_m:
                continue
            if all(see_through[cell] for cell in crossed_cells(p, t)):
                out[p] = True
                break
    return out
