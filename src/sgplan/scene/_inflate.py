"""The compiled kernel of obstacle inflation (:func:`sgplan.scene.footprint.inflate`), in its own module
so that importing the scene model does not load numba."""

import numpy as np
from numba import njit


@njit(cache=True)
def inflate_runs(obstacles, d_rows, firsts, lasts, out):
    """:func:`sgplan.scene.footprint.inflate` on arrays: kernel row ``i`` covers columns
    ``firsts[i] .. lasts[i]`` of row offset ``d_rows[i]``; ``out`` gets the inflated mask."""
    rows, cols = obstacles.shape
    table = np.zeros((rows + 1, cols + 1), dtype=np.int32)  # table[r, c] = obstacles in [0, r) x [0, c)
    for r in range(rows):
        run = 0
        for c in range(cols):
            run += obstacles[r, c]
            table[r + 1, c + 1] = table[r, c + 1] + run
    r_lo, r_hi = d_rows.min(), d_rows.max()
    c_lo, c_hi = firsts.min(), lasts.max()
    for r in range(rows):
        r0, r1 = max(r + r_lo, 0), min(r + r_hi, rows - 1)
        for c in range(cols):
            c0, c1 = max(c + c_lo, 0), min(c + c_hi, cols - 1)
            hit = False
            if r0 <= r1 and c0 <= c1 and (
                table[r1 + 1, c1 + 1] - table[r0, c1 + 1] - table[r1 + 1, c0] + table[r0, c0] > 0
            ):
                for i in range(d_rows.shape[0]):
                    rr = r + d_rows[i]
                    a, b = max(c + firsts[i], 0), min(c + lasts[i], cols - 1)
                    if 0 <= rr < rows and a <= b and (
                        table[rr + 1, b + 1] - table[rr, b + 1] - table[rr + 1, a] + table[rr, a] > 0
                    ):
                        hit = True
                        break
            out[r, c] = hit
