"""Which labels occur where: the linear count agrees with sorting, for any values and masks."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from sgplan.explain.scene_labels import occurring_labels


def _by_sorting(labels: np.ndarray, where: np.ndarray, num_labels: int) -> np.ndarray:
    present = np.zeros(num_labels, bool)
    values = np.unique(labels[where])
    present[values[(values >= 0) & (values < num_labels)].astype(np.int64)] = True
    return present


@given(
    hnp.arrays(np.int64, st.tuples(st.integers(1, 3), st.integers(1, 9), st.integers(1, 9)),
               elements=st.sampled_from([-3, 0, 1, 2, 5, 7, 8, 31, 1 << 20])),
    st.integers(0, 2**31 - 1),
    st.sampled_from([1, 2, 8, 32]),
)
def test_occurring_labels_match_a_sort(labels: np.ndarray, seed: int, num_labels: int) -> None:
    where = np.random.default_rng(seed).random(labels.shape) < 0.6
    for values in (labels, np.abs(labels).astype(np.uint32), np.clip(labels, 0, 40).astype(np.uint32)):
        got = occurring_labels(values, where, num_labels)
        assert got.dtype == bool and got.tolist() == _by_sorting(values, where, num_labels).tolist()


def test_nothing_selected_gives_no_label() -> None:
    labels = np.arange(12, dtype=np.uint32).reshape(3, 4)
    assert not occurring_labels(labels, np.zeros((3, 4), bool), 16).any()
