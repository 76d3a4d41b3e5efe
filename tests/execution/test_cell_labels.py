"""A run's cell labels (bitmasks, compact ids kept for the run, label boundaries) updated at the changed
cells equal those computed afresh on the changed building."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from sgplan.execution.cell_labels import CellLabels
from sgplan.execution.graph import candidate_graph, masked_graph, remasked
from sgplan.execution.world import SceneState
from sgplan.planning.domain import compact_labels
from sgplan.planning.ltl_heuristic import label_boundary
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import Proposition
from tests.execution.buildings import house
from tests.execution.test_fields import label_raster
from tests.execution.test_world import random_changes

PROPS = [Proposition("reach", 10), Proposition("enter", 6), Proposition("reach", 13),
         Proposition("reach", 11)]


@given(st.integers(0, 2**32 - 1), st.sampled_from([0.0, 0.15]))
def test_cell_labels_follow_any_sequence_of_changes(seed, radius):
    rng = np.random.default_rng(seed)
    state = SceneState.of(house(robot_radius_m=radius))
    grid = build_occupancy_grid(state.building, radius)
    candidates = candidate_graph(grid, state.building)
    graph = masked_graph(candidates, grid.traversable)
    labels = label_raster(state.building, PROPS, 0.3)
    kept = CellLabels(candidates, graph, labels)
    for now, _, _, change in random_changes(rng, state, grid, 10):
        graph, moved = remasked(graph, candidates, change)
        new_labels = label_raster(now.building, PROPS, 0.3)
        relabelled = np.flatnonzero(new_labels != labels)
        cells = candidates.cell_ids(relabelled)
        cells, positions = cells[cells >= 0], relabelled[cells >= 0]
        ids_before = kept.cell_label.copy()
        kept.update(graph, moved, cells, new_labels.reshape(-1)[positions])
        labels = new_labels
        masks = candidates.gather(labels)
        assert np.array_equal(kept.masks, masks)
        assert np.array_equal(kept.label_masks[kept.cell_label], masks)
        untouched = np.setdiff1d(np.arange(candidates.num_cells), cells)
        assert np.array_equal(kept.cell_label[untouched], ids_before[untouched])  # ids stay the run's
        _, fresh_ids = compact_labels(masks, int(masks.max()) + 1)
        assert np.array_equal(kept.boundary, label_boundary(graph, fresh_ids))
