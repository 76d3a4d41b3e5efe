"""A run's replans equal a fresh plan of the changed building from the same (cell, automaton state) --
in a new Session and by the independent exact solver -- for every kind of change and for sequences of
them; and the run's statuses, events, amendments and saving."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import sgplan
from sgplan.errors import MissionError, PlanningError, SceneError, SgplanError
from sgplan.execution.changes import (
    AddObject,
    Area,
    Block,
    CloseDoor,
    MoveObject,
    NewSceneGraph,
    OpenDoor,
    RemoveObject,
    Unblock,
)
from sgplan.execution.run import Run
from tests.execution.buildings import house
from tests.execution.test_world import _random_change
from tests.planning.oracle import optimal_cost

MISSION = 'F("reach(object_10)" & F "enter(room_9)") & G !"enter(room_6)"'
"""The sink, then the office upstairs, never through the bedroom (tests.execution.buildings.house)."""


def _fresh_cost(run: Run) -> float:
    """The optimum of a fresh plan of the run's building from the robot's cell and state (a new Session),
    checked against the oracle on the same grid and labels."""
    oracle = optimal_cost(run.grid, run.labels.raster, run.mission.automaton, run.position,
                          start_state=run.state)
    session = sgplan.Session(run.building)
    try:
        fresh = session.plan(run.mission, run.position, options=run.options, start_state=run.state).cost_m
    except PlanningError:
        fresh = math.inf
    except MissionError:  # the mission names an object the changes removed: a Session refuses it
        return oracle
    assert fresh == pytest.approx(oracle, abs=1e-6)
    return oracle


def _check(run: Run) -> None:
    plan = run.plan
    expected = _fresh_cost(run)
    if math.isinf(expected):
        assert plan is None and run.status == "impossible" and run.why
    else:
        assert plan is not None and plan.verified
        assert run.remaining_cost_m == pytest.approx(expected, abs=1e-6)
        rest = run.remaining_path
        assert tuple(rest[0, :3]) == run.position and rest[0, 3] == run.state


@pytest.fixture(scope="module")
def building():
    return house()


@pytest.fixture(scope="module")
def mission(building):
    return sgplan.mission_from_formula(MISSION, building)


CHANGES = {
    "close_door": [CloseDoor(("kitchen", "corridor on floor 0"))],
    "open_door": [CloseDoor(("kitchen", "corridor on floor 0")), OpenDoor(("corridor on floor 0", "room_5"))],
    "block": [Block(Area(0, box_m=(0.0, 3.6, 0.8, 3.9)), "trolley")],
    "unblock": [Block(Area(0, box_m=(0.0, 3.6, 0.8, 3.9)), "trolley"), Unblock(name="trolley")],
    "move_object": [MoveObject("sink", (2.0, 2.5))],
    "add_object": [AddObject("crate", (0.7, 2.0), 0, (1.2, 0.4))],
    "remove_object": [RemoveObject("plant")],
}


@pytest.mark.parametrize("setup", ["A*", "ALL", "NO-LLM"])
@pytest.mark.parametrize("kind", list(CHANGES))
def test_a_replan_after_each_kind_of_change_equals_a_fresh_plan(building, mission, kind, setup):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup=setup)
    _check(run)
    run.observe(run.plan.path[:6, :3], metric=False)
    for change in CHANGES[kind]:
        run.change([change])
        _check(run)


def test_a_newer_scene_graph_replans_like_a_fresh_plan(building, mission, tmp_path):
    from sgplan.execution.world import SceneState
    from sgplan.scene.native import write_native_scene

    newer, _ = SceneState.of(building).apply(MoveObject("sink", (2.0, 2.5)))
    write_native_scene(newer.building, tmp_path / "newer")
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    assert run.plan is not None
    report = run.change([NewSceneGraph(str(tmp_path / "newer"))])
    assert "moved the sink (object_10" in report.describe()
    _check(run)


@settings(max_examples=15)
@given(st.integers(0, 2**32 - 1), st.sampled_from(["A*", "NO-LLM"]))
def test_sequences_of_changes_while_driving_replan_exactly(building, mission, seed, setup):
    rng = np.random.default_rng(seed)
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup=setup)
    for _ in range(6):
        rest = run.remaining_path
        if run.status != "in-progress" or rest is None:
            break
        run.observe(rest[: int(rng.integers(1, max(2, len(rest))))][:, :3], metric=False)
        try:
            run.change([_random_change(rng, run.scene)])
        except SceneError:
            continue
        _check(run)


def test_a_cut_off_goal_is_impossible_with_why_and_a_reopened_door_makes_it_plannable(building, mission):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    events = []
    run.subscribe(events.append)
    run.change([CloseDoor(("office", "corridor on floor 1"))])
    assert run.plan is None and run.status == "impossible"
    assert "the office (room_9, floor 1) can no longer be reached from the robot's position" in run.why
    assert "since: closed the door between the office (room_9, floor 1)" in run.why
    assert events[-1].kind == "impossible"
    run.change([OpenDoor(("office", "corridor on floor 1"))])
    assert run.plan is not None and run.status == "in-progress"
    assert events[-1].kind == "replanned" and events[-1].details["plannable_again"]


def test_forbidden_rooms_on_the_only_way_are_named(building, mission):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    run.change([CloseDoor(("kitchen", "corridor on floor 0"))])  # the kitchen only through the bedroom
    assert run.plan is None and run.status == "impossible"
    assert "bedroom" in run.why


def test_progress_done_and_the_plan_kept_while_followed(building, mission):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    kinds = []
    run.subscribe(lambda event: kinds.append(event.kind))
    plan = run.plan
    run.observe(plan.path[: len(plan.path) // 2, :3], metric=False)
    assert run.plan is plan  # followed: no replan
    run.observe(plan.path[len(plan.path) // 2 :, :3], metric=False)
    assert run.status == "done" and run.plan is None and kinds.count("progress") >= 1 and kinds[-1] == "done"


def test_a_block_away_from_the_plan_keeps_it_and_one_on_it_does_not(building, mission):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    plan = run.plan
    report = run.change([Block(Area(1, box_m=(3.0, 0.3, 3.8, 1.0)))])  # an office corner
    assert report.plan_kept and run.plan is plan
    row, col, floor = (int(v) for v in plan.path[len(plan.path) // 3, :3])
    x, y, _ = run.grid.cell_xyz(floor, (row, col))
    report = run.change([Block(Area(floor, box_m=(x - 0.05, y - 0.05, x + 0.05, y + 0.05)))])
    assert not report.plan_kept and run.plan is not plan


def test_a_violated_mission_stays_violated(building, mission):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    bedroom_id = building.room(uuid=6).id
    bedroom = np.argwhere(run.grid.traversable[0] & (run.grid.room_map[0] == bedroom_id))[0]
    status = run.observe((int(bedroom[0]), int(bedroom[1]), 0), metric=False)
    assert status.verdict == "violated" and run.status == "violated" and run.plan is None
    assert "bedroom" in run.history[-1].message


def test_changes_apply_all_or_none_and_name_the_bad_one(building, mission):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    with pytest.raises(SceneError, match=r"change 2: close door: .* is closed already"):
        run.change([CloseDoor(("kitchen", "corridor on floor 0")),
                    CloseDoor(("corridor on floor 0", "kitchen"))])
    assert run.changes == [] and run.scene.blocks == ()
    x, y, _ = run.grid.cell_xyz(0, run.position[:2])
    with pytest.raises(SceneError, match="obstacle on the robot's cell"):
        run.change([Block(Area(0, box_m=(x - 0.2, y - 0.2, x + 0.2, y + 0.2)))])
    with pytest.raises(SceneError, match=r"change 1: unknown kind 'paint'"):
        run.change([{"kind": "paint"}])


def test_amendments_join_the_rest_or_are_refused_naming_the_conflict(building, mission):
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    run.observe(run.plan.path[:4, :3], metric=False)
    before = run.remaining_cost_m
    accepted = run.amend("from now on, also avoid the kitchen")
    assert not accepted.accepted and "kitchen" in accepted.reason  # the sink is in the kitchen
    assert run.remaining_cost_m == pytest.approx(before)
    assert run.history[-1].kind == "refused"
    amended = run.amend('G !"reach(object_12)"')  # and never reach the plant
    assert amended.accepted and "plant" in amended.said_back
    _check(run)
    assert run.remaining_cost_m >= before - 1e-9


def test_an_amendment_whose_joined_automaton_is_too_large_is_refused_before_it_is_built():
    from sgplan.execution.amend import combine
    from sgplan.mission import compile_mission

    rooms = [f'"enter(room_{i})"' for i in range(20)]
    mission = compile_mission(f"F({rooms[0]} & F {rooms[1]}) & G !({' | '.join(rooms[2:12])})")
    amendment = compile_mission(f"F({rooms[12]} & F {rooms[13]}) & G !({' | '.join(rooms[14:])})")
    with pytest.raises(MissionError, match=r"more than the 8,000,000 an automaton may hold; amend with"):
        combine(mission, 0, amendment, {}, None)


@pytest.mark.parametrize("changes", [
    [CloseDoor(("kitchen", "corridor on floor 0"))],
    [Block(Area(0, box_m=(0.2, 1.0, 1.2, 1.4)), "trolley")],
    [MoveObject("sink", (2.0, 2.5))],
], ids=["close_door", "block", "move_object"])
def test_what_is_left_after_a_change_is_what_a_fresh_monitor_says(building, mission, changes):
    """The words of what is left after a change equal those of a monitor made afresh on the changed
    scene (the run rebases its monitor and keeps the formula's progressions)."""
    from sgplan.execution.monitor import Monitor

    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    run.observe(run.plan.path[:4, :3], metric=False)
    said = run.left()
    run.change(changes)
    fresh = Monitor(run.building, run.mission, run.grid, run.labels.raster, state=run.state)
    assert run.left() == fresh.words.residual(run.state).text() == said


def test_a_run_survives_saving_and_loading(building, mission):
    session = sgplan.Session(building)
    run = sgplan.Run(session, mission, building.initial_cells[0], setup="A*")
    run.observe(run.plan.path[:5, :3], metric=False)
    run.change([MoveObject("sink", (2.0, 2.5)), Block(Area(0, box_m=(0.0, 4.0, 0.7, 4.3)), "cart")])
    run.amend('G !"reach(object_12)"')
    saved = json.loads(json.dumps(run.to_dict()))
    assert saved == run.to_dict()
    restored = Run.from_dict(saved, session)
    assert (restored.position, restored.state, restored.status) == (run.position, run.state, run.status)
    assert restored.plan.cost_m == pytest.approx(run.plan.cost_m, abs=1e-9)
    assert restored.to_dict() | {"history": []} == saved | {"history": []}
    with pytest.raises(SgplanError, match="not a saved run"):
        Run.from_dict({"format": "other"}, session)


def test_a_newer_scene_graph_that_opens_a_wall_renumbers_and_replans_exactly(building, mission, tmp_path):
    from dataclasses import replace

    from sgplan.scene.native import write_native_scene

    floors = list(building.floors)
    cat = floors[0].cat_map.copy()
    cat[14:16, 30:34] = 0  # a gap in the wall between the corridor and the bedroom (x 1.4-1.6 m, y 3-3.4 m)
    floors[0] = replace(floors[0], cat_map=cat)
    write_native_scene(replace(building, floors=floors), tmp_path / "newer")
    run = sgplan.Run(sgplan.Session(building), mission, building.initial_cells[0], setup="A*")
    assert run.plan is not None
    run.change([NewSceneGraph(str(tmp_path / "newer"))])
    _check(run)


@pytest.mark.parametrize("setup", ["A*", "ALL"])
def test_a_plan_resumes_from_any_row_of_its_path(building, mission, setup):
    from sgplan.outputs.waypoints import leg_costs

    session = sgplan.Session(building)
    full = session.plan(mission, building.initial_cells[0], setup=setup)
    costs = np.concatenate([[0.0], np.cumsum(leg_costs(full.path, full.grid))])
    for k in (1, len(full.path) // 3, len(full.path) - 2):
        row, col, floor, q = (int(v) for v in full.path[k])
        rest = session.plan(mission, (row, col, floor), setup=setup, start_state=q)
        assert rest.cost_m == pytest.approx(full.cost_m - costs[k], abs=1e-6) and rest.verified
        assert rest.path[0, 3] == q and not [e for e in rest.events if e.kind == "state" and e.index == 0]


def test_an_amendment_joins_a_mission_folder_with_its_own_proposition_names(building, mission, tmp_path):
    from sgplan.mission import save_mission_folder

    save_mission_folder(mission, tmp_path / "m", building=building)
    folder = sgplan.load_mission(tmp_path / "m")
    assert set(folder.automaton.aps) <= {"p1", "p2", "p3"}
    run = sgplan.Run(sgplan.Session(building), folder, building.initial_cells[0], setup="A*")
    run.observe(run.plan.path[:3, :3], metric=False)
    amended = run.amend('G !"reach(object_12)"')
    assert amended.accepted, amended.reason
    assert "reach(object_12)" in run.mission.automaton.aps and "enter(room_9)" in run.mission.automaton.aps
    _check(run)
