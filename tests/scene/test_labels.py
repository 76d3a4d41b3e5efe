"""Propositions and label rasters (reference-algorithm.md §2.4)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import FormulaError, MissionError, SceneError
from sgplan.scene.demo import demo_building
from sgplan.scene.labels import (
    MAX_PROPOSITIONS,
    Proposition,
    label_raster,
    proposition_cells,
)
from sgplan.scene.model import Building
from sgplan.scene.reach import reach_half_widths
from tests.scene.small_buildings import random_small_building


def test_proposition_names_and_parsing() -> None:
    assert Proposition("enter", 2).name == "enter(room_2)"
    assert str(Proposition("reach", 27)) == "reach(object_27)"
    assert Proposition.parse("reach(object_27)") == Proposition("reach", 27)
    assert Proposition.parse(" enter( room_2 ) ") == Proposition("enter", 2)
    assert Proposition.parse("reach(object_3)", 0.5).reach_radius_m == 0.5
    assert Proposition.parse("enter(room_3)", 0.5).reach_radius_m is None
    for bad in ("enter(object_2)", "reach(room_2)", "visit(room_2)", "enter(room_x)", "p1", ""):
        with pytest.raises(FormulaError):
            Proposition.parse(bad)
    with pytest.raises(FormulaError, match="reach radius"):
        Proposition("reach", 3, -1.0)
    with pytest.raises(FormulaError, match="only applies"):
        Proposition("enter", 3, 1.0)


def _oracle(building: Building, props: list[Proposition], reach_m: float) -> np.ndarray:
    """Direct transcription of §2.4 (the ``box`` reach model): a square window around every object cell
    (loops; tiny grids only)."""
    floors, (rows, cols) = building.num_floors, building.grid_shape
    out = np.zeros((floors, rows, cols), dtype=np.uint32)
    for bit, prop in enumerate(props):
        for floor in building.floors:
            if prop.kind == "enter":
                hit = floor.room_map == building.room(uuid=prop.uuid).id
            else:
                h_r, h_c = reach_half_widths(building.resolution_m, prop.reach_radius_m or reach_m)
                hit = np.zeros((rows, cols), dtype=bool)
                for r, c in np.argwhere(floor.cat_map == building.object(uuid=prop.uuid).id):
                    hit[max(0, r - h_r) : r + h_r + 1, max(0, c - h_c) : c + h_c + 1] = True
            out[floor.index][hit] |= np.uint32(1 << bit)
    return out


@settings(max_examples=40)
@given(seed=st.integers(0, 2**32 - 1), reach=st.floats(0.05, 1.5), own=st.floats(0.1, 1.0))
def test_label_raster_matches_definition(seed: int, reach: float, own: float) -> None:
    building = random_small_building(seed)
    props = [Proposition("enter", r.uuid) for r in building.rooms()]
    objects = list(building.objects())
    props += [Proposition("reach", o.uuid, own if i % 2 else None) for i, o in enumerate(objects)]
    labels = label_raster(building, props, reach, "box")
    smallest = np.uint8 if len(props) <= 8 else np.uint16 if len(props) <= 16 else np.uint32
    assert labels.dtype == smallest and labels.shape == (building.num_floors, *building.grid_shape)
    np.testing.assert_array_equal(labels, _oracle(building, props, reach))
    for bit, prop in enumerate(props[:8]):  # the sparse form Session keeps: the same cells, ascending
        cells = proposition_cells(building, prop, reach, "box")
        np.testing.assert_array_equal(cells, np.flatnonzero(labels.reshape(-1) >> bit & 1))


def test_demo_labels() -> None:
    building = demo_building()
    stairs = building.rooms_named("staircase")[0]
    fridge = building.objects_named("refrigerator")[0]
    labels = label_raster(building, [Proposition("enter", stairs.uuid), Proposition("reach", fridge.uuid)],
                          reach_model="box")
    # The staircase is drawn (and entered) on both floors.
    assert [(labels[f] & 1).any() for f in (0, 1)] == [True, True]
    # The box model's window uses the building's default radius and truncates like the authors' C++:
    # int(0.6 / 0.05) is 11, not 12, in floating point. It sees through walls.
    assert reach_half_widths(building.resolution_m, 0.6) == (11, 11)
    reach = (labels[0] & 2) > 0
    rows, cols = np.nonzero(reach)
    assert rows.max() - rows.min() == fridge.grid_max[0] - fridge.grid_min[0] + 22
    assert cols.max() - cols.min() == fridge.grid_max[1] - fridge.grid_min[1] + 22
    assert not (labels[1] & 2).any()
    assert set(np.unique(building.floors[0].room_map[reach]).tolist()) - {-5} != {fridge.room_id}


def test_label_errors() -> None:
    building = demo_building()
    with pytest.raises(SceneError) as error:
        label_raster(building, [Proposition("enter", 999), Proposition("reach", 2), Proposition("enter", 2)])
    assert "enter(room_999)" in str(error.value) and "reach(object_2)" in str(error.value)
    many = [Proposition("enter", r.uuid) for r in building.rooms()] * 3
    assert len(many) > MAX_PROPOSITIONS
    with pytest.raises(MissionError, match="at most 32"):
        label_raster(building, many)
    building.reach_radius_m = None
    fridge = building.objects_named("refrigerator")[0]
    with pytest.raises(MissionError, match="no reach radius"):
        label_raster(building, [Proposition("reach", fridge.uuid)])
    assert label_raster(building, [Proposition("reach", fridge.uuid, 0.3)]).any()
    assert label_raster(building, [Proposition("enter", r.uuid) for r in building.rooms()][:32]).any()


@pytest.mark.gibson
def test_benevolence_labels(gibson_root: Path) -> None:
    from sgplan.scene.authors import load_authors_scene

    building = load_authors_scene(gibson_root / "Benevolence")
    props = [Proposition("enter", r.uuid) for r in building.rooms()]
    labels = label_raster(building, props)
    for bit, room in enumerate(building.rooms()):
        counts = [int(((labels[f] >> bit) & 1).sum()) for f in range(3)]
        expected = [int((f.room_map == room.id).sum()) for f in building.floors]
        assert counts == expected
        if room.is_staircase:
            assert sum(c > 0 for c in counts) == 2  # drawn on its floor and the one above
