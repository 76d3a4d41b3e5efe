"""Binary min-heaps on plain arrays, shared by the numba-compiled searches (grid Dijkstra, AMRA*).

An entry is ``(key, tie, value)``: entries are ordered by ``key`` ascending and, on equal keys, by
``tie`` DESCENDING (the searches pass ``g`` as tie, so among equal ``f`` the deeper state comes first,
which shortens weighted searches without touching their bounds). Heaps are lazy: callers push a new
entry when a value improves and skip stale entries when they pop; nothing is ever removed or re-keyed
in place. Capacity is the caller's business (``heap_grow``), so the hot push stays branch-free.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def _before(key_a, tie_a, key_b, tie_b):
    return key_a < key_b or (key_a == key_b and tie_a > tie_b)


@njit(cache=True, inline="always")
def heap_push_at(keys, ties, values, base, size, key, tie, value):
    """Insert one entry into the heap stored at ``keys[base : base + size]`` (and likewise ``ties``,
    ``values``), which must have room for ``size + 1`` entries. Returns the new size. Several heaps can
    share one flat array this way, each at its own ``base``."""
    i = size
    while i > 0:
        parent = (i - 1) >> 1
        if not _before(key, tie, keys[base + parent], ties[base + parent]):
            break
        keys[base + i] = keys[base + parent]
        ties[base + i] = ties[base + parent]
        values[base + i] = values[base + parent]
        i = parent
    keys[base + i] = key
    ties[base + i] = tie
    values[base + i] = value
    return size + 1


@njit(cache=True, inline="always")
def heap_pop_at(keys, ties, values, base, size):
    """Remove the top entry (read it from index ``base`` first) of the heap at ``base``. Returns the new
    size."""
    size -= 1
    if size <= 0:
        return 0
    key, tie, value = keys[base + size], ties[base + size], values[base + size]
    i = 0
    while True:
        child = 2 * i + 1
        if child >= size:
            break
        if child + 1 < size and _before(
            keys[base + child + 1], ties[base + child + 1], keys[base + child], ties[base + child]
        ):
            child += 1
        if not _before(keys[base + child], ties[base + child], key, tie):
            break
        keys[base + i] = keys[base + child]
        ties[base + i] = ties[base + child]
        values[base + i] = values[base + child]
        i = child
    keys[base + i] = key
    ties[base + i] = tie
    values[base + i] = value
    return size


@njit(cache=True, inline="always")
def heap_push(keys, ties, values, size, key, tie, value):
    """Insert one entry; the arrays must have room for ``size + 1`` entries. Returns the new size."""
    return heap_push_at(keys, ties, values, 0, size, key, tie, value)


@njit(cache=True, inline="always")
def heap_pop(keys, ties, values, size):
    """Remove the top entry (read it from index 0 first). Returns the new size."""
    return heap_pop_at(keys, ties, values, 0, size)


@njit(cache=True)
def heap_grow(keys, ties, values, size):
    """Copies of the three arrays with twice the capacity (the first ``size`` entries kept)."""
    cap = max(2 * keys.shape[0], 16)
    new_keys = np.empty(cap, dtype=keys.dtype)
    new_ties = np.empty(cap, dtype=ties.dtype)
    new_values = np.empty(cap, dtype=values.dtype)
    # An element loop, not slice assignment: slices pull in numba's shape-error machinery (~2 s of JIT).
    for i in range(size):
        new_keys[i] = keys[i]
        new_ties[i] = ties[i]
        new_values[i] = values[i]
    return new_keys, new_ties, new_values
