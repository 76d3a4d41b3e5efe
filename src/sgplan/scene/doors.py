"""Door cells and room connections derived from a floor's rasters (one rule for every scene builder).

Two rooms are connected where a GROUND cell of one is 4-adjacent to a cell of the other: the opening
between them. The procedural generator and the importers both derive ``Room.door_cells`` and the
connections this way, so connections always agree with what the occupancy grid lets a robot cross.
"""

from __future__ import annotations

import numpy as np

from sgplan.scene.model import CatCode


def door_cells(room_map: np.ndarray, cat_map: np.ndarray) -> dict[tuple[int, int], np.ndarray]:
    """For every ordered pair ``(a, b)`` of touching rooms: the GROUND cells of ``b`` 4-adjacent to ``a``.

    ``room_map`` / ``cat_map`` are one floor's decoded rasters ``(rows, cols)``; the values are
    ``(n, 2)`` int32 arrays of ``(row, col)``, sorted and without repeats.
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


def connections(doors: list[dict[tuple[int, int], np.ndarray]]) -> dict[int, set[int]]:
    """Room id -> ids of the rooms it shares a door cell with, over the door maps of all floors."""
    connected: dict[int, set[int]] = {}
    for floor_doors in doors:
        for a, b in floor_doors:
            connected.setdefault(a, set()).add(b)
            connected.setdefault(b, set()).add(a)
    return connected
