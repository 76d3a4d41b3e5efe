"""The robot's connected component followed across scene changes (competing floods where cells left the
graph, a flood from the cells that joined it) equals a flood fill of the changed graph."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from sgplan.execution.changes import CloseDoor, OpenDoor
from sgplan.execution.component import Component
from sgplan.execution.graph import candidate_graph, in_graph, masked_graph, remasked
from sgplan.execution.regrid import regrid
from sgplan.execution.world import SceneState
from sgplan.scene.grid import build_occupancy_grid
from tests.execution.buildings import house
from tests.execution.test_world import random_changes


def _setup(radius):
    state = SceneState.of(house(robot_radius_m=radius))
    grid = build_occupancy_grid(state.building, radius)
    candidates = candidate_graph(grid, state.building)
    return state, grid, candidates, masked_graph(candidates, grid.traversable)


def _cell(graph, x_m, y_m, floor):
    row, col = int(x_m / 0.1), int(y_m / 0.1)
    return graph.cell_id(row, col, floor)


@given(st.integers(0, 2**32 - 1), st.sampled_from([0.0, 0.15]))
def test_the_component_follows_any_sequence_of_changes(seed, radius):
    rng = np.random.default_rng(seed)
    state, grid, candidates, graph = _setup(radius)
    component = Component()
    anchor = int(rng.choice(np.flatnonzero(in_graph(graph))))
    component.of(graph, anchor)
    expected_floods = 1
    for _, _, _, change in random_changes(rng, state, grid, 10):
        graph, moved = remasked(graph, candidates, change)
        component.update(graph, moved, anchor)
        if not in_graph(graph)[anchor]:  # the robot stood where an obstacle is now: another robot
            anchor = int(rng.choice(np.flatnonzero(in_graph(graph))))
            expected_floods += 1
        assert np.array_equal(component.of(graph, anchor), graph.reachable(anchor))
    assert component.floods == expected_floods


def test_a_closed_door_splits_the_component_on_the_robots_side_and_an_open_one_joins_it():
    state, grid, candidates, graph = _setup(0.0)
    component = Component()
    for inside in (True, False):  # the robot in the kitchen, then in the corridor
        anchor = _cell(graph, 3.0, 1.5, 0) if inside else _cell(graph, 0.7, 0.7, 0)
        kitchen = _cell(graph, 3.0, 1.5, 0)
        component.of(graph, anchor)
        floods = component.floods
        for change in (CloseDoor(("kitchen", "corridor on floor 0")), CloseDoor(("kitchen", "bedroom")),
                       OpenDoor(("kitchen", "bedroom")), OpenDoor(("kitchen", "corridor on floor 0"))):
            state, delta = state.apply(change)
            grid, moved_change = regrid(grid, state.building, delta.cells)
            graph, moved = remasked(graph, candidates, moved_change)
            component.update(graph, moved, anchor)
            cells = component.of(graph, anchor)
            assert np.array_equal(cells, graph.reachable(anchor))
            if isinstance(change, CloseDoor) and change.rooms[1] == "bedroom":  # the kitchen is cut off
                share = cells.sum() / in_graph(graph).sum()
                assert cells[kitchen] == inside and share < (0.5 if inside else 1.0)
        assert component.floods == floods and component.updates > 0
