"""Doors derived from the rasters: the cells where two rooms touch, and which rooms connect.

Two rooms are connected where a GROUND cell of one is 4-adjacent to a cell of the other (a door
opening). :func:`door_cells` gives, for every ordered pair ``(a, b)`` of touching rooms, the GROUND cells
of ``b`` next to ``a`` -- exactly ``Room.door_cells[b]`` of room ``a`` (see :mod:`sgplan.scene.model`).
"""

from __future__ import annotations

import numpy as np

from sgplan.scene.model import CatCode


def door_cells(room_map: np.ndarray, cat_map: np.ndarray) -> dict[tuple[int, int], np.ndarray]:
    """For every ordered pair ``(a, b)`` of touching rooms (ids > 0): the GROUND cells of ``b`` that are
    4-adjacent to a cell of ``a``, as a sorted ``(n, 2)`` int32 array of ``(row, col)``.

    ``room_map`` and ``cat_map`` are one floor's ``(rows, cols)`` rasters.
    """
    pairs: dict[tuple[int, int], list[np.ndarray]] = {}
    for axis in (0, 1):
        for flip in (False, True):
            a = room_map[:-1, :] if axis == 0 else room_map[:, :-1]
            b = room_map[1:, :] if axis == 0 else room_map[:, 1:]
            b_cat = cat_map[1:, :] if axis == 0 else cat_map[:, 1:]
            offset = (1, 0) if axis == 0 else (0, 1)
            if flip:
                a, b = b, a
                b_cat = cat_map[:-1, :] if axis == 0 else cat_map[:, :-1]
                offset = (0, 0)
            hit = (a > 0) & (b > 0) & (a != b) & (b_cat == CatCode.GROUND)
            rows, cols = np.nonzero(hit)
            for key in set(zip(a[rows, cols].tolist(), b[rows, cols].tolist())):
                sel = (a[rows, cols] == key[0]) & (b[rows, cols] == key[1])
                cells = np.stack([rows[sel] + offset[0], cols[sel] + offset[1]], axis=1)
                pairs.setdefault(key, []).append(cells)
    return {key: np.unique(np.concatenate(parts), axis=0).astype(np.int32) for key, parts in pairs.items()}


def connections(doors: dict[tuple[int, int], np.ndarray]) -> dict[int, set[int]]:
    """Room id -> ids of the rooms it shares a door with (symmetric), from :func:`door_cells` results."""
    linked: dict[int, set[int]] = {}
    for a, b in doors:
        linked.setdefault(a, set()).add(b)
        linked.setdefault(b, set()).add(a)
    return linked
