"""One cell numbering across changes (masked graphs) and the distance fields repaired after each change
(kept as the columns of one matrix, laid out anew as the labels asked for change): both against what a
fresh build of the changed building computes."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from sgplan.errors import SceneError
from sgplan.execution.fields import FieldStore
from sgplan.execution.graph import candidate_graph, in_graph, masked_graph, remasked
from sgplan.execution.regrid import regrid
from sgplan.execution.world import SceneState
from sgplan.planning.cells import build_cell_graph
from sgplan.planning.ltl_heuristic import finest_unit, unit_field
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import Proposition, proposition_cells, raster_from_cells
from tests.execution.buildings import house
from tests.execution.test_world import _random_change


def label_raster(building, props, reach):
    """The label raster, a proposition of a removed object holding nowhere."""
    def cells(prop):
        gone = prop.kind == "reach" and not building.has_object(prop.uuid)
        return np.zeros(0, np.int64) if gone else proposition_cells(building, prop, reach)
    return raster_from_cells((building.num_floors, *building.grid_shape), [cells(p) for p in props])


def _fresh_field(grid, labels, mask, unit):
    """The field of a fresh cell graph of ``grid``, as a raster (-1 off the graph)."""
    graph = build_cell_graph(grid)
    masks = graph.gather(labels)
    field = unit_field(graph, np.flatnonzero(masks == mask), unit)
    raster = np.full(grid.traversable.size, -1, dtype=np.int64)
    raster[graph.positions()] = field
    return raster


def _lipschitz(graph, field, unit):
    """Whether no move changes ``field`` by more than its cost in units (over the graph's cells)."""
    from sgplan.planning.ltl_heuristic import unit_costs

    steps, _ = unit_costs(graph, unit)
    cells = np.flatnonzero(in_graph(graph))
    value = field.astype(np.float64)
    value[field == np.iinfo(np.uint32).max] = np.inf
    near = graph.neighbours(cells)
    for k in range(8):
        ok = near[:, k] >= 0
        a, b = value[cells[ok]], value[near[ok, k]]
        finite = np.isfinite(a) | np.isfinite(b)
        if (np.abs(a[finite] - b[finite]) > steps[k]).any():
            return False
    return True


@given(st.integers(0, 2**32 - 1), st.sampled_from([0.0, 0.15]), st.sampled_from([1.0, 0.01]), st.booleans())
def test_repaired_fields_equal_fields_of_a_fresh_graph(seed, radius, fraction, bound):
    """With room to repair, every field equals a fresh one; with little, a field is recomputed, or (when
    the store may ``bound``) a field that is not exact any more is a lower bound, 1-Lipschitz over the
    moves (what h_LTL needs)."""
    rng = np.random.default_rng(seed)
    state = SceneState.of(house(robot_radius_m=radius))
    props = [Proposition("reach", 10), Proposition("enter", 6), Proposition("reach", 13)]
    grid = build_occupancy_grid(state.building, radius)
    candidates = candidate_graph(grid, state.building)
    graph = masked_graph(candidates, grid.traversable)
    labels = label_raster(state.building, props, 0.3)
    unit = finest_unit(candidates)
    store = FieldStore(invalidate_fraction=fraction, lower_fraction=1.0, bound=bound)
    wanted = [1, 2, 4, 0]
    store.fields(graph, graph.gather(labels), wanted, unit)
    changed_any = False
    for _ in range(8):
        try:
            new, delta = state.apply(_random_change(rng, state))
        except SceneError:
            continue
        grid, change = regrid(grid, new.building, delta.cells)
        graph, moved = remasked(graph, candidates, change)
        new_labels = label_raster(new.building, props, 0.3)
        old_masks = graph.gather(labels)
        relabelled = np.flatnonzero(graph.gather(new_labels) != old_masks)
        store.changed(moved, relabelled, old_masks[relabelled])
        changed_any |= bool(moved.size or relabelled.size)
        state, labels = new, new_labels
        assert np.array_equal(in_graph(graph), grid.traversable.reshape(-1)[graph.positions()])
        masks = graph.gather(labels)
        chosen = [int(m) for m in rng.permutation(wanted)[: int(rng.integers(1, 5))]]
        matrix = store.fields(graph, masks, chosen, unit)
        for mask, field in zip(chosen, matrix.T):
            on_graph = np.full(grid.traversable.size, -1, dtype=np.int64)
            on_graph[graph.positions()[in_graph(graph)]] = field[in_graph(graph)]
            fresh = _fresh_field(grid, labels, mask, unit)
            if store.exact[mask]:
                assert np.array_equal(on_graph, fresh)
            else:
                assert (on_graph <= fresh).all() and _lipschitz(graph, field, unit)
                assert (on_graph[fresh == 0] == 0).all()
    assert store.counts["computed"] >= len(wanted)
    repaired = store.counts["repaired"] + store.counts["bounded"]
    assert repaired > 0 or not changed_any or (fraction < 1 and not bound)
    assert (fraction < 1 and bound) or store.counts["bounded"] == 0
    assert bound or all(store.exact.values())
