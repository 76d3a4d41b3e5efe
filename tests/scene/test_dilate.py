"""The numpy dilations of reach regions agree cell for cell with scipy.ndimage (the reference replaced)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import ndimage

from sgplan.scene.dilate import box_dilate, within_distance

_RES = st.sampled_from([0.05, 0.1, 0.0497, 0.03, 0.25, 1.0, 0.009985776293823039, 0.009991059907834101])


@st.composite
def _masks(draw: st.DrawFn) -> np.ndarray:
    rows, cols = draw(st.integers(1, 40)), draw(st.integers(1, 40))
    density = draw(st.sampled_from([0.01, 0.05, 0.3, 0.9]))
    seed = draw(st.integers(0, 2**32 - 1))
    mask = np.random.default_rng(seed).random((rows, cols)) < density
    if not mask.any():
        mask[draw(st.integers(0, rows - 1)), draw(st.integers(0, cols - 1))] = True
    return mask


@settings(max_examples=300, deadline=None)
@given(_masks(), st.integers(1, 6), st.integers(1, 6))
def test_box_dilate_is_ndimage_maximum_filter(mask: np.ndarray, half_rows: int, half_cols: int) -> None:
    size = (2 * half_rows + 1, 2 * half_cols + 1)
    expected = ndimage.maximum_filter(mask.view(np.uint8), size=size, mode="constant", cval=0).view(bool)
    assert np.array_equal(box_dilate(mask, (half_rows, half_cols)), expected)


@settings(max_examples=300, deadline=None)
@given(_masks(), _RES, _RES, st.one_of(st.sampled_from([0.05, 0.1, 0.25, 0.3, 0.6, 0.7, 1.0]),
                                       st.floats(0.01, 2.0)))
def test_within_distance_is_the_edt_threshold(mask: np.ndarray, res_r: float, res_c: float,
                                              radius: float) -> None:
    """Including radii that fall exactly on cell-centre distances (0.6 m at 0.05 m cells)."""
    expected = ndimage.distance_transform_edt(~mask, sampling=(res_r, res_c)) <= radius
    assert np.array_equal(within_distance(mask, (res_r, res_c), radius), expected)


def test_within_distance_of_nothing_is_nothing() -> None:
    assert not within_distance(np.zeros((5, 7), bool), (0.05, 0.05), 0.6).any()
