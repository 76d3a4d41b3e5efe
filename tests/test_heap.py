"""The array heaps shared by the compiled searches, against Python's heapq (several heaps in one array)."""

from __future__ import annotations

import heapq

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.heap import heap_pop_at, heap_push_at

_OPS = st.lists(
    st.tuples(st.integers(0, 2), st.booleans(), st.integers(0, 20), st.integers(0, 5)), max_size=200
)


@settings(max_examples=60, deadline=None)
@given(_OPS)
def test_heaps_at_offsets_match_heapq(ops: list[tuple[int, bool, int, int]]) -> None:
    """Three heaps at offsets 0, cap, 2*cap of one flat array: each pops what heapq pops (key ascending,
    then tie descending), and none disturbs the others."""
    cap = 256
    keys, ties, values = np.zeros(3 * cap), np.zeros(3 * cap), np.zeros(3 * cap, dtype=np.int64)
    sizes = [0, 0, 0]
    mirror: list[list[tuple[float, float, int]]] = [[], [], []]
    for n, (which, push, key, tie) in enumerate(ops):
        base = which * cap
        if push:
            sizes[which] = heap_push_at(keys, ties, values, base, sizes[which], float(key), float(tie), n)
            heapq.heappush(mirror[which], (float(key), -float(tie), n))
        elif sizes[which]:
            want_key, want_neg_tie, _ = heapq.heappop(mirror[which])
            assert (keys[base], ties[base]) == (want_key, -want_neg_tie)
            sizes[which] = heap_pop_at(keys, ties, values, base, sizes[which])
        assert sizes[which] == len(mirror[which])
