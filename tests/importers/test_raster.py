"""Rasterisation helpers: polygon distances (against dense sampling), cells, frames."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import SceneError
from sgplan.importers.raster import GridFrame, capsules_mask, hull_cells, polygon_cells, polygon_distance_m


def square(x: float, y: float, side: float = 1.0) -> np.ndarray:
    return np.array([[x, y], [x + side, y], [x + side, y + side], [x, y + side]])


def sampled_distance(p: np.ndarray, q: np.ndarray, n: int = 200) -> float:
    """Distance between the two boundaries sampled densely (an upper bound, close to the truth)."""

    def boundary(v: np.ndarray) -> np.ndarray:
        t = np.linspace(0, 1, n, endpoint=False)[:, None]
        return np.concatenate([a + t * (b - a) for a, b in zip(v, np.roll(v, -1, axis=0))])

    bp, bq = boundary(p), boundary(q)
    return float(np.sqrt(((bp[:, None] - bq[None]) ** 2).sum(axis=2)).min())


def test_distance_of_apart_overlapping_and_crossing_polygons() -> None:
    assert polygon_distance_m(square(0, 0), square(1.3, 0)) == pytest.approx(0.3)
    assert polygon_distance_m(square(0, 0), square(0.5, 0.5)) == 0.0
    bar = np.array([[0, 0.4], [3, 0.4], [3, 0.6], [0, 0.6]])  # crosses the other bar, no vertex inside
    assert polygon_distance_m(bar, bar[:, ::-1]) == 0.0


@settings(max_examples=25, deadline=None)
@given(st.lists(st.floats(-3, 3), min_size=12, max_size=12))
def test_distance_matches_dense_sampling_for_separated_triangles(values: list[float]) -> None:
    p = np.array(values[:6]).reshape(3, 2)
    q = np.array(values[6:]).reshape(3, 2) + (8.0, 0.0)  # shifted apart: the boundaries are what matters
    exact = polygon_distance_m(p, q)
    assert exact <= sampled_distance(p, q) + 1e-9
    assert exact == pytest.approx(sampled_distance(p, q), abs=0.05)


def test_cells_by_centre_and_a_flat_box_keeps_one_cell() -> None:
    frame = GridFrame((0.0, 0.0), 0.5, (10, 10))
    assert len(polygon_cells(frame, square(0, 0, 2.0))) == 16
    flat = np.array([[1.1, 1.1], [2.2, 1.1], [1.1, 1.1], [2.2, 1.1]])
    assert hull_cells(frame, flat).tolist() == [[3, 2]]  # the cell of the points' mean (1.65, 1.1)
    disc = capsules_mask(frame, np.array([[2.5, 2.5]]), np.array([[2.5, 2.5]]), np.array([1.0]))
    centres = (np.argwhere(np.ones((10, 10))) + 0.5) * 0.5
    assert disc.sum() == int((((centres - 2.5) ** 2).sum(axis=1) <= 1.0).sum())


def test_a_grid_too_large_asks_for_a_coarser_resolution() -> None:
    with pytest.raises(SceneError, match="coarser --resolution"):
        GridFrame.around(np.zeros(2), np.array([1000.0, 1000.0]), 0.05, 0.0)
    with pytest.raises(SceneError, match="positive"):
        GridFrame.around(np.zeros(2), np.ones(2), 0.0, 0.0)
