"""Compiled kernels of the ``visible`` reach model (:mod:`sgplan.scene.reach`): which cells of a window see
a cell of a target (an object's footprint) within a radius along a straight line that crosses no opaque
cell. See that module for the rule; the tests hold an independent brute-force version of it.

Segments join cell centres. In doubled integer coordinates cell ``(r, c)`` is the open square
``(2r, 2r + 2) x (2c, 2c + 2)`` and its centre ``(2r + 1, 2c + 1)``; a segment *crosses* a cell when it
meets that open square. A segment through a cell corner therefore crosses the diagonal cell only, not the
two cells beside the corner: the planner's own diagonal step.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def next_crossed(r: int, c: int, m: int, n: int, dr: int, dc: int, sr: int, sc: int
                 ) -> tuple[int, int, int, int]:
    """One step of the walk of the cells a segment between two cell centres crosses: from cell ``(r, c)``,
    with ``m`` / ``n`` the row / column lines crossed so far plus one, the next cell and counts. The
    segment spans ``dr`` rows and ``dc`` columns (absolute) in directions ``sr`` / ``sc`` (+1 or -1); the
    walk steps while ``m <= dr or n <= dc``. For sight here and for the simplified waypoints
    (:mod:`sgplan.outputs._segments`).

    Exact integer arithmetic: from a centre the segment meets its ``m``-th row line at
    ``t = (2m - 1) / (2 dr)`` and its ``n``-th column line at ``t = (2n - 1) / (2 dc)``; the times are
    compared by cross-multiplying (a missing axis never comes first). Both at once is a cell corner: the
    segment touches the two cells beside it in one point only and goes on in the diagonal cell.
    """
    row_time = (2 * m - 1) * dc if m <= dr else -1  # both times scaled by 2 * dr * dc
    col_time = (2 * n - 1) * dr if n <= dc else -1
    if col_time < 0 or (row_time >= 0 and row_time <= col_time):
        r, m = r + sr, m + 1
    if row_time < 0 or (col_time >= 0 and col_time <= row_time):
        c, n = c + sc, n + 1
    return r, c, m, n


@njit(cache=True)
def first_opaque(opaque: np.ndarray, r: int, c: int, r1: int, c1: int) -> int:
    """The flat index (``row * cols + col``) of the first opaque cell that the segment from the centre of
    ``(r, c)`` to the centre of ``(r1, c1)`` crosses, both end cells included; -1 if there is none. The
    crossed cells are walked in order (:func:`next_crossed`)."""
    cols = opaque.shape[1]
    if opaque[r, c]:
        return r * cols + c
    dr, dc = abs(r1 - r), abs(c1 - c)
    sr = 1 if r1 > r else -1
    sc = 1 if c1 > c else -1
    m = n = 1
    while m <= dr or n <= dc:
        r, c, m, n = next_crossed(r, c, m, n, dr, dc, sr, sc)
        if opaque[r, c]:
            return r * cols + c
    return -1


@njit(cache=True)
def meets_box(r: int, c: int, r1: int, c1: int, box: np.ndarray) -> bool:
    """Whether the segment between the centres of cells ``(r, c)`` and ``(r1, c1)`` meets the open
    rectangle covering cells ``box = (row0, col0, row1, col1)`` (inclusive).

    Separating axes, exactly in doubled integer coordinates: the rows, the columns and the segment's
    normal (the rectangle's corners strictly on both sides of the segment's line). For a rectangle of
    opaque cells this is "crosses one of them": the segment ends at cell centres, so it cannot meet the
    rectangle only on the edges between its cells.
    """
    p_r, p_c, q_r, q_c = 2 * r + 1, 2 * c + 1, 2 * r1 + 1, 2 * c1 + 1
    lo_r, hi_r, lo_c, hi_c = 2 * box[0], 2 * box[2] + 2, 2 * box[1], 2 * box[3] + 2
    if min(p_r, q_r) >= hi_r or max(p_r, q_r) <= lo_r or min(p_c, q_c) >= hi_c or max(p_c, q_c) <= lo_c:
        return False
    d_r, d_c = q_r - p_r, q_c - p_c
    if d_r == 0 and d_c == 0:
        return True  # a point inside the rectangle's row and column spans
    below = above = False
    for corner_r in (lo_r, hi_r):
        for corner_c in (lo_c, hi_c):
            side = d_r * (corner_c - p_c) - d_c * (corner_r - p_r)
            below = below or side < 0
            above = above or side > 0
    return below and above


@njit(cache=True)
def _opaque_counts(opaque: np.ndarray) -> np.ndarray:
    """``(rows + 1, cols + 1)`` int32 summed-area table of ``opaque``."""
    rows, cols = opaque.shape
    counts = np.zeros((rows + 1, cols + 1), dtype=np.int32)
    for i in range(rows):
        run = 0
        for j in range(cols):
            run += opaque[i, j]
            counts[i + 1, j + 1] = counts[i, j + 1] + run
    return counts


@njit(cache=True)
def _opaque_in(counts: np.ndarray, r0: int, c0: int, r1: int, c1: int) -> int:
    """Opaque cells in rows ``r0..r1`` and columns ``c0..c1`` (inclusive, any order)."""
    lo_r, hi_r = min(r0, r1), max(r0, r1) + 1
    lo_c, hi_c = min(c0, c1), max(c0, c1) + 1
    return counts[hi_r, hi_c] - counts[lo_r, hi_c] - counts[hi_r, lo_c] + counts[lo_r, lo_c]


@njit(cache=True)
def _grow_box(opaque: np.ndarray, counts: np.ndarray, cell: int, box: np.ndarray) -> None:
    """Write into ``box`` a large rectangle of opaque cells around the opaque ``cell`` (flat index): its
    row run widened to whole rows above and below, or its column run to whole columns, the larger one.
    A wall is long and thick, so one rectangle shadows what many single cells would."""
    rows, cols = opaque.shape
    r, c = cell // cols, cell % cols
    c0, c1 = c, c
    while c0 > 0 and opaque[r, c0 - 1]:
        c0 -= 1
    while c1 < cols - 1 and opaque[r, c1 + 1]:
        c1 += 1
    r0, r1 = r, r
    while r0 > 0 and _opaque_in(counts, r0 - 1, c0, r0 - 1, c1) == c1 - c0 + 1:
        r0 -= 1
    while r1 < rows - 1 and _opaque_in(counts, r1 + 1, c0, r1 + 1, c1) == c1 - c0 + 1:
        r1 += 1
    box[0], box[1], box[2], box[3] = r0, c0, r1, c1
    r0, r1 = r, r
    while r0 > 0 and opaque[r0 - 1, c]:
        r0 -= 1
    while r1 < rows - 1 and opaque[r1 + 1, c]:
        r1 += 1
    c0, c1 = c, c
    while c0 > 0 and _opaque_in(counts, r0, c0 - 1, r1, c0 - 1) == r1 - r0 + 1:
        c0 -= 1
    while c1 < cols - 1 and _opaque_in(counts, r0, c1 + 1, r1, c1 + 1) == r1 - r0 + 1:
        c1 += 1
    if (r1 - r0 + 1) * (c1 - c0 + 1) > (box[2] - box[0] + 1) * (box[3] - box[1] + 1):
        box[0], box[1], box[2], box[3] = r0, c0, r1, c1


_BAND = 8
"""Rows of target runs summed up in one band: a band's bounding rectangle is tested for shadow first."""


@njit(cache=True)
def _target_runs(target: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The target's cells as row runs and bands of :data:`_BAND` rows:
    ``(row_ptr, run_c0, run_c1, bands, extent)``.

    The runs of row ``i`` are ``row_ptr[i]:row_ptr[i + 1]`` (inclusive column ranges, left to right);
    ``bands[k] = (first row, last row, first column, last column)`` of the target cells in rows
    ``k * _BAND .. (k + 1) * _BAND - 1``, first row -1 when there are none; ``extent`` the same of all the
    target's cells.
    """
    rows, cols = target.shape
    row_ptr = np.zeros(rows + 1, dtype=np.int64)
    most = rows * ((cols + 1) // 2)  # runs are a cell apart at least
    c0 = np.empty(most, dtype=np.int64)
    c1 = np.empty(most, dtype=np.int64)
    bands = np.full(((rows + _BAND - 1) // _BAND, 4), -1, dtype=np.int64)
    k = 0
    for i in range(rows):
        j = 0
        while j < cols:
            if target[i, j]:
                c0[k] = j
                while j + 1 < cols and target[i, j + 1]:
                    j += 1
                c1[k] = j
                k += 1
            j += 1
        row_ptr[i + 1] = k
        if k > row_ptr[i]:
            band = bands[i // _BAND]
            if band[0] < 0:
                band[0], band[2], band[3] = i, c0[row_ptr[i]], c1[k - 1]
            band[1] = i
            band[2] = min(band[2], c0[row_ptr[i]])
            band[3] = max(band[3], c1[k - 1])
    used = bands[bands[:, 0] >= 0]
    extent = np.array([used[:, 0].min(), used[:, 2].min(), used[:, 1].max(), used[:, 3].max()])
    return row_ptr, c0[:k], c1[:k], bands, extent


_CACHE = 8
"""Rectangles of opaque cells remembered while deciding viewers (most recently useful first)."""


@njit(cache=True)
def _shadowed(r: int, c: int, a0: int, b0: int, a1: int, b1: int, boxes: np.ndarray, count: int) -> bool:
    """Whether one remembered rectangle blocks the segments from ``(r, c)`` to every cell centre in rows
    ``a0..a1`` and columns ``b0..b1``, moving it to the front when it does. The points whose segment from
    ``(r, c)`` meets a convex set (its shadow) form a convex region, so a rectangle that blocks the four
    corners blocks all of them."""
    for k in range(count):
        box = boxes[k]
        if (meets_box(r, c, a0, b0, box) and meets_box(r, c, a1, b1, box)
                and meets_box(r, c, a0, b1, box) and meets_box(r, c, a1, b0, box)):
            for i in range(4):
                boxes[0, i], boxes[k, i] = boxes[k, i], boxes[0, i]
            return True
    return False


@njit(cache=True)
def _sees_in_row(opaque: np.ndarray, counts: np.ndarray, row_ptr: np.ndarray, run_c0: np.ndarray,
                 run_c1: np.ndarray, r: int, c: int, a: int, w: int, boxes: np.ndarray,
                 memory: np.ndarray) -> bool:
    """Whether ``(r, c)`` sees a target cell of row ``a`` within ``w`` columns; see :func:`_sees`. A run's
    cells are tried from the one nearest the viewer's column outwards: the likeliest in sight."""
    for k in range(row_ptr[a], row_ptr[a + 1]):
        lo, hi = max(run_c0[k], c - w), min(run_c1[k], c + w)
        if lo > hi:
            continue
        near = min(max(c, lo), hi)
        if _opaque_in(counts, r, c, a, near) == 0:  # nothing opaque in the box spanned: clear
            memory[0], memory[1] = a, near
            return True
        if _shadowed(r, c, a, lo, a, hi, boxes, memory[2]):
            continue
        for d in range(hi - lo + 1):  # near, then both sides of it, one column further each time
            for side in range(2 if d else 1):
                b = near + d if side == 0 else near - d
                if b < lo or b > hi or _shadowed(r, c, a, b, a, b, boxes, memory[2]):
                    continue
                blocker = first_opaque(opaque, r, c, a, b)
                if blocker < 0:
                    memory[0], memory[1] = a, b
                    return True
                slot = min(memory[2], _CACHE - 1)  # a full memory forgets its last rectangle
                _grow_box(opaque, counts, blocker, boxes[slot])
                for i in range(4):
                    boxes[0, i], boxes[slot, i] = boxes[slot, i], boxes[0, i]
                memory[2] = min(memory[2] + 1, _CACHE)
    return False


@njit(cache=True)
def _sees(opaque: np.ndarray, counts: np.ndarray,
          runs: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray],
          widest: np.ndarray, r: int, c: int, boxes: np.ndarray, memory: np.ndarray) -> bool:
    """Whether cell ``(r, c)`` sees a target cell within the radius (``widest``: per row offset, the widest
    column offset within it, -1 for none), once the target cell the previous viewer saw
    (``memory[:2]``, updated to the one found) is out of reach or sight.

    What earlier viewers learnt comes first: the first ``memory[2]`` rectangles of opaque cells of
    ``boxes`` (a rectangle of opaque cells blocks what it blocks, whoever looks); one that shadows the
    target's whole bounding box settles a viewer behind a wall at once. Then the bands of target rows,
    nearest first: a band in the shadow of one rectangle is passed over whole.
    """
    row_ptr, run_c0, run_c1, bands, extent = runs
    reach = widest.shape[0] - 1
    if _shadowed(r, c, extent[0], extent[1], extent[2], extent[3], boxes, memory[2]):
        return False
    home = r // _BAND
    for step in range(2 * bands.shape[0]):  # bands home, home + 1, home - 1, ...: nearest first
        k = home + (step + 1) // 2 if step % 2 else home - step // 2
        if k < 0 or k >= bands.shape[0] or bands[k, 0] < 0:
            continue
        a0, a1 = max(bands[k, 0], r - reach), min(bands[k, 1], r + reach)
        if a0 > a1 or _shadowed(r, c, a0, bands[k, 2], a1, bands[k, 3], boxes, memory[2]):
            continue
        for a in range(a0, a1 + 1):
            if widest[abs(a - r)] >= 0 and _sees_in_row(opaque, counts, row_ptr, run_c0, run_c1, r, c, a,
                                                         widest[abs(a - r)], boxes, memory):
                return True
    return False


@njit(cache=True)
def visible_cells(
    opaque: np.ndarray, target: np.ndarray, viewers: np.ndarray, widest: np.ndarray
) -> np.ndarray:
    """``(rows, cols)`` bool: the ``viewers`` cells that see a ``target`` cell within the radius.

    Parameters
    ----------
    opaque, target, viewers:
        ``(rows, cols)`` bool rasters of one window: the cells a segment may not cross, the target's cells
        (never opaque), the cells to decide (the others come out False).
    widest:
        ``widest[k]`` is the largest column offset within the radius at row offset ``k`` (``-1``: none at
        that row offset; every column offset up to ``widest[k]`` is within it).

    A viewer sees the target when, for some target cell within the radius, the segment between the two
    centres crosses no opaque cell (end cells included).
    """
    rows, cols = opaque.shape
    out = np.zeros((rows, cols), dtype=np.bool_)
    if not target.any():
        return out
    counts = _opaque_counts(opaque)
    runs = _target_runs(target)
    boxes = np.zeros((_CACHE, 4), dtype=np.int64)
    memory = np.array([-1, -1, 0], dtype=np.int64)
    reach = widest.shape[0] - 1
    for r in range(rows):
        for c in range(cols):
            if not viewers[r, c]:
                continue
            # Most viewers see the target cell their neighbour saw, often with nothing opaque in the box
            # between them: settled here, without a call.
            a, b = memory[0], memory[1]
            if (a >= 0 and abs(a - r) <= reach and widest[abs(a - r)] >= abs(b - c)
                    and (_opaque_in(counts, r, c, a, b) == 0 or first_opaque(opaque, r, c, a, b) < 0)):
                out[r, c] = True
            else:
                out[r, c] = _sees(opaque, counts, runs, widest, r, c, boxes, memory)
    return out
