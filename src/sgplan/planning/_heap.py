"""The one priority queue of sgplan's compiled searches (AMRA*, the grid Dijkstra's stairs queue): a lazy
4-ary min-heap on a flat buffer.

An entry is three 8-byte words ``(key, tie, value)``, stored in one int64 buffer ``hi`` that is also read
through its float64 view ``hf`` (the same memory twice: keys and ties as floats, values and whole-entry
copies as integers, bit-exact). Entries are ordered by ``key`` ascending and, on equal keys, by ``tie``
DESCENDING (AMRA* passes ``g``: among equal keys the deeper state comes first, which shortens weighted
searches without touching their bounds). Several heaps can share one buffer, each at its own entry offset
``base``. 4-ary: half the depth of a binary heap, and a node's children share one or two cache lines.

Lazy: callers push a new entry when a value improves and skip stale entries when they pop; nothing is ever
removed or re-keyed in place. Capacity is the caller's business (:func:`grown`), so the hot push stays
branch-free.
"""

from __future__ import annotations

import numpy as np
from numba import njit

HREC = 3
"""Words per entry: key, tie, value."""
ARITY = 4
"""Children per node."""


@njit(cache=True, inline="always")
def _before(key_a, tie_a, key_b, tie_b):
    return key_a < key_b or (key_a == key_b and tie_a > tie_b)


@njit(cache=True, inline="always")
def _move_entry(hi, to, src):
    """Copy the entry at word ``src`` to word ``to`` (through the integer view: bit-exact)."""
    hi[to] = hi[src]
    hi[to + 1] = hi[src + 1]
    hi[to + 2] = hi[src + 2]


@njit(cache=True, inline="always")
def _put_entry(hf, hi, d, key, tie, value):
    """Write the entry ``(key, tie, value)`` at word ``d``."""
    hf[d] = key
    hf[d + 1] = tie
    hi[d + 2] = value


@njit(cache=True, inline="always")
def hpush(hf, hi, base, size, key, tie, value):
    """Insert ``(key, tie, value)`` into the heap of ``size`` entries at entry offset ``base`` (room for one
    more is the caller's business); returns the new size."""
    i = size
    while i > 0:
        parent = (i - 1) // ARITY
        a = (base + parent) * HREC
        if not _before(key, tie, hf[a], hf[a + 1]):
            break
        _move_entry(hi, (base + i) * HREC, a)
        i = parent
    _put_entry(hf, hi, (base + i) * HREC, key, tie, value)
    return size + 1


@njit(cache=True, inline="always")
def hpop(hf, hi, base, size):
    """Remove the top entry (read it at entry ``base`` first: key ``hf[base * HREC]``, value
    ``hi[base * HREC + 2]``); returns the new size."""
    size -= 1
    if size <= 0:
        return 0
    last = (base + size) * HREC
    key, tie, value = hf[last], hf[last + 1], hi[last + 2]
    i = 0
    while True:
        first = ARITY * i + 1
        if first >= size:
            break
        best = first
        b = (base + first) * HREC
        bk, bt = hf[b], hf[b + 1]
        for child in range(first + 1, min(first + ARITY, size)):
            e = (base + child) * HREC
            if _before(hf[e], hf[e + 1], bk, bt):
                best, bk, bt = child, hf[e], hf[e + 1]
        if not _before(bk, bt, key, tie):
            break
        _move_entry(hi, (base + i) * HREC, (base + best) * HREC)
        i = best
    _put_entry(hf, hi, (base + i) * HREC, key, tie, value)
    return size


@njit(cache=True)
def grown(hi, size):
    """A buffer for one heap with twice the capacity of ``hi`` (at least 16 entries), its first ``size``
    entries copied; read it as float64 through ``.view(np.float64)``."""
    capacity = max(2 * (hi.shape[0] // HREC), 16)
    new = np.empty(capacity * HREC, dtype=np.int64)
    # An element loop, not slice assignment: slices pull in numba's shape-error machinery, slow to compile.
    for w in range(size * HREC):
        new[w] = hi[w]
    return new
