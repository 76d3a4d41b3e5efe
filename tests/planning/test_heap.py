"""The one heap of the compiled searches (planning/_heap.py), against Python's heapq: several heaps at
offsets of one buffer, ties to the larger tie value, values read back bit-exact, growth."""

from __future__ import annotations

import heapq
from collections import Counter

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.planning._heap import HREC, grown, hpop, hpush

_OPS = st.lists(
    st.tuples(st.integers(0, 2), st.booleans(), st.integers(0, 20), st.integers(0, 5)), max_size=200
)


@settings(max_examples=60, deadline=None)
@given(_OPS)
def test_heaps_at_offsets_match_heapq(ops: list[tuple[int, bool, int, int]]) -> None:
    """Three heaps at entry offsets 0, cap, 2*cap of one buffer: each pops what heapq pops (key
    ascending, then tie descending) with a value pushed under that key and tie, and none disturbs the
    others."""
    cap = 256
    hi = np.zeros(3 * cap * HREC, dtype=np.int64)
    hf = hi.view(np.float64)
    sizes = [0, 0, 0]
    mirror: list[list[tuple[float, float]]] = [[], [], []]
    waiting: list[Counter[tuple[float, float, int]]] = [Counter(), Counter(), Counter()]
    for which, push, key, tie in ops:
        base = which * cap
        if push:
            value = 1000 * key + tie
            sizes[which] = hpush(hf, hi, base, sizes[which], float(key), float(tie), value)
            heapq.heappush(mirror[which], (float(key), -float(tie)))
            waiting[which][(float(key), float(tie), value)] += 1
        elif sizes[which]:
            want_key, want_neg_tie = heapq.heappop(mirror[which])
            top = base * HREC
            got = (hf[top], hf[top + 1], int(hi[top + 2]))
            assert got[:2] == (want_key, -want_neg_tie) and waiting[which][got] > 0
            waiting[which][got] -= 1
            sizes[which] = hpop(hf, hi, base, sizes[which])
        assert sizes[which] == len(mirror[which])


def test_values_survive_bit_exact_and_a_grown_heap_keeps_its_entries() -> None:
    hi = np.zeros(4 * HREC, dtype=np.int64)
    hf = hi.view(np.float64)
    big = (1 << 62) + 12345  # a value no float64 holds exactly
    size = 0
    for key in (3.0, 1.0, 2.0):
        size = hpush(hf, hi, 0, size, key, 0.5, big + int(key))
    more = grown(hi, size)
    assert more.shape[0] == 16 * HREC and np.array_equal(more[: size * HREC], hi[: size * HREC])
    more_f = more.view(np.float64)
    for key in (0.5, 4.0, 1.5):
        size = hpush(more_f, more, 0, size, key, 0.5, big + int(key * 10))
    popped = []
    while size:
        popped.append((more_f[0], int(more[2])))
        size = hpop(more_f, more, 0, size)
    assert [k for k, _ in popped] == [0.5, 1.0, 1.5, 2.0, 3.0, 4.0]
    assert dict(popped)[1.0] == big + 1 and dict(popped)[4.0] == big + 40
