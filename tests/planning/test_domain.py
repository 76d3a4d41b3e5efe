"""The planning domain: start validation, infeasibility reasons, cell graph, composite actions."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.planning import PlanningProblem
from sgplan.planning._search import ACT_MAP, successors
from sgplan.planning.amra import path_cost
from sgplan.planning.domain import MAP_FLOOR_DOWN, MAP_FLOOR_UP, MAP_OBJECT, domain_of
from sgplan.scene.grid import StairsLink
from sgplan.scene.model import CatCode
from tests.scene.distances import grid_distances

from .instances import RES, automaton, marks, open_building, open_grid, random_problem


def _problem(start, formula="F p0", floors=1, stairs=(), grid=None, building=None, **kw) -> PlanningProblem:
    building = building or open_building(floors)
    grid = grid or open_grid(building, stairs)
    labels = marks(grid.shape, {0: [(2, 10, 0)], 1: [(0, 0, 0)]})
    return PlanningProblem(building, grid, labels, automaton(formula, ("p0", "p1")), start, **kw)


def _status(problem: PlanningProblem) -> PlanningError:
    with pytest.raises(PlanningError) as info:
        domain_of(problem)
    return info.value


def test_start_outside_grid() -> None:
    error = _status(_problem((9, 0, 0)))
    assert error.status == "invalid-start" and "outside the grid" in str(error)


def test_start_in_inflated_region_names_clearance() -> None:
    building = open_building()
    building.floors[0].cat_map[0, 5] = CatCode.WALL
    grid = open_grid(building)
    grid = type(grid)(**{**grid.__dict__, "robot_radius_m": 0.25})
    grid.traversable[0, 0:3, 3:8] = False  # the wall at (0, 5) inflated by 0.25 m
    error = _status(_problem((1, 5, 0), grid=grid, building=building))
    assert error.status == "invalid-start"
    assert "0.100 m away" in str(error) and "robot radius 0.25 m" in str(error)
    error = _status(_problem((0, 5, 0), grid=grid, building=building))
    assert "not free ground (wall)" in str(error)


def test_start_label_leading_to_sink_names_propositions() -> None:
    error = _status(_problem((0, 0, 0), formula="G !p1 & F p0", ap_descriptions={"p1": "enter(room_7)"}))
    assert error.status == "invalid-start" and "p1 (enter(room_7))" in str(error)
    assert domain_of(_problem((0, 0, 0), formula="G !p1 & F p0", profile="authors")).q_start == 0


def test_unreachable_proposition_is_infeasible() -> None:
    building = open_building(2)
    problem = PlanningProblem(
        building,
        open_grid(building),
        marks((2, 5, 12), {0: [(2, 10, 1)]}),
        automaton("F p0", ("p0",)),
        (2, 0, 0),
    )
    error = _status(problem)
    assert error.status == "infeasible" and "p0 never holds on a cell reachable" in str(error)


def test_bad_inputs() -> None:
    with pytest.raises(PlanningError, match="profile"):
        _problem((2, 0, 0), profile="strict")
    building = open_building()
    with pytest.raises(PlanningError, match="shape"):
        PlanningProblem(
            building,
            open_grid(building),
            np.zeros((1, 2, 2), np.uint32),
            automaton("F p0", ("p0",)),
            (0, 0, 0),
        )
    labels = np.full((1, 5, 12), 4, np.uint32)
    error = _status(
        PlanningProblem(building, open_grid(building), labels, automaton("F p0", ("p0",)), (0, 0, 0))
    )
    assert "bitmask 4" in str(error)


def test_cell_graph_distances_match_scene_dijkstra() -> None:
    problem = random_problem(23)
    graph = domain_of(problem).graph
    source = domain_of(problem).start_cell
    ours = graph.distances(np.array([source]))
    theirs = grid_distances(problem.grid, [problem.start])
    floor, row, col = graph.cell_floor, graph.cell_row, graph.cell_col
    assert np.allclose(ours, theirs[floor, row, col], rtol=0, atol=1e-9, equal_nan=False)


def test_floor_actions_take_the_stairs() -> None:
    link = StairsLink(lower_floor=0, lower_cell=(2, 6), upper_cell=(2, 6), cost_m=4.0)
    problem = _problem((2, 0, 0), floors=2, stairs=(link,))
    domain = domain_of(problem)
    kinds = {m.kind for m in domain.maps}
    assert {MAP_FLOOR_UP, MAP_FLOOR_DOWN} <= kinds
    edges = _edges(domain, domain.start_cell, domain.q_start, level=4)
    ((end, _, cost, code),) = edges
    assert domain.graph.cell_floor[end] == 1 and cost == pytest.approx(6 * RES + 4.0)
    cells = domain.action_cells(code - ACT_MAP, domain.start_cell, end)
    assert len(cells) == 7 and domain.graph.cell_floor[cells[-1]] == 1


def _edges(domain, cell, q, level=0, max_level=4):
    n_buf = 64
    out = (np.empty(n_buf, np.int64), np.empty(n_buf, np.int64), np.empty(n_buf), np.empty(n_buf, np.int32))
    n = successors(
        domain.kgraph, domain.kactions, domain.kmaps, domain.klogic, cell, q, level, max_level, *out
    )
    return [(int(out[0][i]), int(out[1][i]), float(out[2][i]), int(out[3][i])) for i in range(n)]


@settings(max_examples=20, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_composite_actions_are_exact_move_sequences(seed: int) -> None:
    """Every composite action replays as legal moves whose cost is the action's cost, the automaton run
    over them gives the action's q, and (when not cut short by acceptance) it is a shortest path: over the
    floor for floor actions, over the cells of the action's room (and its sources) for the others."""
    problem = random_problem(seed, guidance="none")
    try:
        domain = domain_of(problem)
    except PlanningError:
        return
    rng = np.random.default_rng(seed)
    graph = domain.graph
    for cell in rng.integers(graph.num_cells, size=30):
        q = int(rng.integers(domain.num_states))
        for end, nq, cost, code in _edges(domain, int(cell), q):
            if code < ACT_MAP:
                continue
            k = code - ACT_MAP
            cells = np.array([cell, *domain.action_cells(k, int(cell), end)])
            assert path_cost(domain, cells) == pytest.approx(cost, abs=1e-9)
            steps = np.abs(np.diff(np.stack([graph.cell_row[cells], graph.cell_col[cells]]), axis=1)).max(
                axis=0
            )
            same_floor = np.diff(graph.cell_floor[cells]) == 0
            assert np.all(steps[same_floor] == 1)
            run = q
            for c in cells[1:]:
                run = int(domain.trans[run, domain.cell_label[c]])
            assert run == nq
            if not domain.accepting[nq] and domain.maps[k].kind not in (MAP_FLOOR_UP, MAP_FLOOR_DOWN):
                sources = domain.kactions.map_src[
                    domain.kactions.map_src_ptr[k] : domain.kactions.map_src_ptr[k + 1]
                ]
                assert cost == pytest.approx(
                    _confined_distance(problem.grid, domain, k, sources, int(cell)), abs=1e-9
                )


def _confined_distance(grid, domain, k: int, sources: np.ndarray, cell: int) -> float:
    """Metres from ``cell`` to the nearest of ``sources`` over the cells of action ``k``'s room and the
    sources (the whole grid when the action has no room), by the independent grid Dijkstra."""
    graph = domain.graph
    room = int(domain.kactions.map_stop_room[k])
    keep = domain.kgraph.cell_room == room if room >= 0 else np.ones(graph.num_cells, dtype=bool)
    keep[sources] = True
    traversable = np.zeros(graph.shape, dtype=bool)
    traversable[graph.cell_floor[keep], graph.cell_row[keep], graph.cell_col[keep]] = True
    where = [(int(graph.cell_row[s]), int(graph.cell_col[s]), int(graph.cell_floor[s])) for s in sources]
    dist = grid_distances(dataclasses.replace(grid, traversable=traversable), where)
    return float(dist[graph.cell_floor[cell], graph.cell_row[cell], graph.cell_col[cell]])


@settings(max_examples=10, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_level_one_domain_skips_the_action_tables_and_adds_them_later(seed: int) -> None:
    """A domain for max level 1 (the A* setup) has no composite action families but the same occupancy
    successors; asking it for level 4 afterwards gives the families and successors of a full domain."""
    lean, full = random_problem(seed, guidance="none"), random_problem(seed, guidance="none")
    try:
        domain = domain_of(lean, 1)
    except PlanningError:
        return
    assert domain.max_level == 1 and domain.maps == [] and domain.kmaps.dist.size == 0
    assert not domain.kgraph.in_object_region.any()
    reference = domain_of(full)
    rng = np.random.default_rng(seed)
    cells = rng.integers(domain.graph.num_cells, size=20)
    for cell in cells:
        q = int(rng.integers(domain.num_states))
        assert _edges(domain, int(cell), q, max_level=1) == _edges(reference, int(cell), q, max_level=1)
    assert domain_of(lean, 4) is domain and domain.max_level == 4
    assert domain.maps == reference.maps
    assert np.array_equal(domain.kgraph.cell_room, reference.kgraph.cell_room)
    for cell in cells:
        q = int(rng.integers(domain.num_states))
        assert _edges(domain, int(cell), q) == _edges(reference, int(cell), q)


@settings(max_examples=5, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_the_a_star_setup_plans_on_a_level_one_domain_and_no_llm_upgrades_it(seed: int) -> None:
    """plan() builds the domain its setup needs: A* (occupancy moves only) without composite action
    tables; a later NO-LLM plan on the same problem adds them, and both reach the same optimum."""
    from sgplan.planning import plan

    problem, full = random_problem(seed, guidance="none"), random_problem(seed, guidance="none")
    try:
        a_star = plan(problem, "A*")
    except PlanningError:
        return
    assert domain_of(problem, 1).max_level == 1 and domain_of(problem, 1).maps == []
    no_llm = plan(problem, "NO-LLM")
    assert domain_of(problem, 1).max_level == 4 and domain_of(problem, 1).maps == domain_of(full).maps
    assert a_star.status == no_llm.status
    if a_star.status == "optimal":
        assert a_star.cost_m == pytest.approx(no_llm.cost_m, abs=1e-9)


@pytest.mark.parametrize("model", ["box", "visible"])
def test_object_level_regions_are_the_reach_labels_in_the_room(model: str) -> None:
    """One source of truth: an object action's target cells are the cells of the object's ``reach`` label
    (problem's radius and reach model) inside its room and on the grid."""
    from sgplan.scene.demo import demo_building
    from sgplan.scene.grid import build_occupancy_grid
    from sgplan.scene.labels import Proposition, proposition_cells

    building = demo_building()
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    labels = np.zeros(grid.shape, dtype=np.uint8)
    labels[building.initial_cells[1][2], building.initial_cells[1][0], building.initial_cells[1][1]] = 1
    problem = PlanningProblem(building, grid, labels, automaton("F p0", ("p0",)), building.initial_cells[0],
                              reach_radius_m=0.6, reach_model=model)
    domain = domain_of(problem)
    graph, ptr, sources = domain.graph, domain.kactions.map_src_ptr, domain.kactions.map_src
    objects = [(m, action) for m, action in enumerate(domain.maps) if action.kind == MAP_OBJECT]
    assert len(objects) == sum(1 for _ in building.objects())
    room_of_cell = graph.gather(grid.room_map)
    for m, action in objects:
        obj = building.object(uuid=action.entity)
        cells = graph.cell_ids(proposition_cells(building, Proposition("reach", obj.uuid), 0.6, model))
        cells = cells[cells >= 0]
        expected = np.sort(cells[room_of_cell[cells] == obj.room_id])
        np.testing.assert_array_equal(np.sort(sources[ptr[m]:ptr[m + 1]]), expected)
        assert domain.kgraph.in_object_region[expected].all()
