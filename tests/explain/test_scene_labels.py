"""Which labels occur where: the linear count agrees with sorting, for any values and masks; the labels a
scene realizes, read sparsely from the propositions' cells, are those of the whole raster."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import sgplan
from sgplan.errors import MissionError, SceneError
from sgplan.explain.scene_labels import in_room_cells, occurring_labels, realizable_labels
from sgplan.radii import resolve_radii
from sgplan.scene.labels import Proposition, label_raster, proposition_cells


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


def _by_raster(props: list, building, radius: float) -> np.ndarray:
    """The labels of every in-room cell of the whole raster (the former way)."""
    return occurring_labels(label_raster(building, props, radius), in_room_cells(building), 1 << len(props))


@pytest.mark.parametrize("names", [
    ["enter(room_4)", "enter(room_11)"], ["enter(room_5)", "enter(room_5)"], [],
    ["reach(object_28)", "enter(room_5)", "reach(object_29)", "reach(object_30)"],
])
def test_realizable_labels_read_sparsely_match_the_raster_on_the_demo(names: list[str]) -> None:
    building = sgplan.load_scene("demo")
    props = [Proposition.parse(name) for name in names]
    for radius in (0.3, 0.6, 2.5):
        got = realizable_labels(props, building, radius)
        assert got.tolist() == _by_raster(props, building, radius).tolist()
        session = sgplan.Session(building)
        shared = realizable_labels(props, building, radius, cells=session.proposition_cells)
        assert shared.tolist() == got.tolist() and session.builds["label_mask"] == len(set(props))
        for prop in props:
            assert session.proposition_cells(prop, radius) is session.proposition_cells(prop, radius)
            assert session.proposition_cells(prop, radius).tolist() == \
                proposition_cells(building, prop, radius).tolist()
        assert session.builds["label_mask"] == len(set(props))  # kept, not built again


@pytest.mark.gibson
def test_realizable_labels_read_sparsely_match_the_raster_on_gibson_missions(gibson_root: Path) -> None:
    for scene, mission in (("Allensville", "2"), ("Benevolence", "4"), ("Collierville", "5")):
        building = sgplan.load_scene(gibson_root / scene)
        loaded = sgplan.load_mission(gibson_root / scene / "missions" / mission, profile="authors")
        props = [loaded.propositions[p] for p in loaded.automaton.aps]
        radius = resolve_radii(building).reach_m
        assert realizable_labels(props, building).tolist() == _by_raster(props, building, radius).tolist()


def test_unknown_entities_and_too_many_propositions_are_refused() -> None:
    building = sgplan.load_scene("demo")
    with pytest.raises(SceneError, match="room_999"):
        realizable_labels([Proposition.parse("enter(room_999)")], building)
    with pytest.raises(MissionError, match="at most 32"):
        realizable_labels([Proposition.parse("enter(room_4)")] * 33, building)
