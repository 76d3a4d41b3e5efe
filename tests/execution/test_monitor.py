"""The runtime monitor: states and verdicts of driven poses, against the planner's own states and an
independent oracle; the words of what is left and of the step that broke a mission; poses it must report."""

from __future__ import annotations

import dataclasses
from functools import lru_cache

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sgplan.errors import PlanningError, TrajectoryError
from sgplan.execution.monitor import Monitor, MonitorStatus
from sgplan.mission import Mission, compile_mission
from sgplan.outputs.waypoints import crossed_cells, densify, simplify_path
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import Proposition
from sgplan.scene.model import CatCode
from tests.execution.oracle import states_after_poses
from tests.logic.oracle import formulas
from tests.plans import REACH_M, DemoPlan, demo_plan
from tests.scene.small_buildings import random_small_building

BEDROOM_NO_STAIRS = 'F "enter(room_11)" & G !"enter(room_8)"'  # the demo's only staircase is room_8
LEFT_AT_START = (
    "go to the bathroom (room_5, floor 0) while not within reach of the sink (object_21, in the bathroom "
    "room_5, floor 0), then reach the chair (object_28, in the dining room room_7, floor 0) while in the "
    "dining room (room_7, floor 0), then go to the bedroom (room_11, floor 1); never enter the living room "
    "(room_6, floor 0) or the kitchen (room_4, floor 0)"
)


@lru_cache(maxsize=1)
def demo_labels() -> np.ndarray:
    demo = demo_plan()
    return demo.mission.labels(demo.building, REACH_M)


def monitor(mission: Mission | None = None, **options: object) -> Monitor:
    demo = demo_plan()
    mission = mission or demo.mission
    labels = demo_labels() if mission is demo.mission else mission.labels(demo.building, REACH_M)
    return Monitor(demo.building, mission, demo.grid, labels, **options)  # type: ignore[arg-type]


def path() -> np.ndarray:
    result = demo_plan().result
    assert result.path is not None
    return result.path


def centres(demo: DemoPlan, cells: np.ndarray) -> np.ndarray:
    """Metric centres ``(x_m, y_m, floor)`` of ``(n, 3+)`` cells."""
    xy = [demo.grid.cell_xyz(int(f), (int(r), int(c)))[:2] for r, c, f in cells[:, :3]]
    return np.column_stack([np.array(xy), cells[:, 2]])


def test_the_planned_path_read_cell_by_cell_gives_the_planners_states():
    status = monitor().observe_cells(path()[:, :3])
    assert status.states.tolist() == path()[:, 3].tolist()
    assert status.verdict == "done" and status.accepting and status.violation is None
    assert status.cells == len(path()) and status.poses == len(path()) and status.issues == ()
    assert status.length_m == pytest.approx(demo_plan().result.cost_m)
    assert status.cell == tuple(int(v) for v in path()[-1, :3])


def test_simplified_waypoints_read_as_the_robot_drives_them():
    demo = demo_plan()
    keep = simplify_path(path(), demo.grid, demo_labels(), demo.mission.automaton)
    status = monitor().observe_xy(centres(demo, path()[keep]))
    assert status.states.tolist() == path()[keep, 3].tolist()
    # The cells between waypoints are those densify() gives for the same straight segments.
    assert status.cells == len(densify(path(), keep, demo.mission.automaton, demo_labels()))
    assert status.verdict == "done"


def test_batches_and_single_poses_give_the_same_states_and_verdicts():
    whole = monitor().observe_cells(path()[:, :3])
    rng = np.random.default_rng(3)
    cuts = np.sort(rng.choice(np.arange(1, len(path())), size=12, replace=False))
    batched = monitor()
    parts = [batched.observe_cells(part[:, :3]) for part in np.split(path(), cuts)]
    single = monitor()
    ones = [single.observe_cells(tuple(row)) for row in path()[::7, :3].tolist()]
    assert np.concatenate([p.states for p in parts]).tolist() == whole.states.tolist()
    assert np.concatenate([p.lengths_m for p in parts]) == pytest.approx(whole.lengths_m)
    assert _final(parts[-1]) == _final(whole)
    sparse = monitor().observe_cells(path()[::7, :3])
    assert [int(s.states[0]) for s in ones] == sparse.states.tolist() and _final(ones[-1]) == _final(sparse)


def _final(status: MonitorStatus) -> tuple:
    return (status.verdict, status.state, status.cells, status.poses, round(status.length_m, 9),
            status.violation, status.left)


def test_metric_poses_anywhere_in_a_cell_read_that_cell():
    demo = demo_plan()
    offsets = np.random.default_rng(5).uniform(0.01, 0.99, size=(len(path()), 2)) * demo.grid.resolution_m
    lower = centres(demo, path()) - np.array([*demo.grid.resolution_m, 0.0]) / 2
    status = monitor().observe_xy(lower + np.column_stack([offsets, np.zeros(len(path()))]))
    assert status.states.tolist() == path()[:, 3].tolist() and status.issues == ()


def test_in_progress_says_what_is_left():
    demo = demo_plan()
    before = monitor().observe_cells(path()[:5, :3])
    assert before.verdict == "in-progress" and before.left == LEFT_AT_START
    assert before.summary() == f"in progress: left: {LEFT_AT_START}"
    chair = int(np.argmax(path()[:, 3] == 3))  # the chair reached: the bedroom is left
    after = monitor().observe_cells(path()[:chair + 1, :3])
    assert after.left == ("go to the bedroom (room_11, floor 1); never enter the living room (room_6, "
                          "floor 0) or the kitchen (room_4, floor 0)")
    done = monitor().observe_cells(path()[:, :3])
    assert done.summary() == ("done: the mission is satisfied; if the robot goes on: never enter the living "
                              "room (room_6, floor 0) or the kitchen (room_4, floor 0)")
    assert demo.mission.automaton.accepting[done.state]


def test_a_violation_names_the_step_that_broke_the_mission():
    mission = compile_mission(BEDROOM_NO_STAIRS)
    mon = monitor(mission)
    status = mon.observe_cells(path()[:, :3])
    rooms = demo_plan().grid.room_map[path()[:, 2], path()[:, 0], path()[:, 1]]
    first = int(np.argmax(rooms == demo_plan().building.room(uuid=8).id))
    assert status.verdict == "violated" and status.violation is not None
    assert status.violation.pose == first
    assert status.violation.cell == tuple(int(v) for v in path()[first, :3])
    assert status.violation.text == ("entered the staircase (room_8, floor 0), which the mission forbids: "
                                     "never enter the staircase (room_8, floor 0)")
    assert status.summary().startswith(f"violated at pose {first}, x ")
    assert status.left == "" and not mission.automaton.live_states()[status.state]
    again = mon.observe_cells(path()[:3, :3])  # it stays violated, by the same step
    assert again.verdict == "violated" and again.violation == status.violation


def test_a_broken_until_names_its_clause():
    mission = compile_mission('!"enter(room_9)" U "enter(room_4)"')  # the upstairs corridor first
    status = monitor(mission).observe_cells(path()[:, :3])
    assert status.violation is not None and status.violation.text == (
        "entered the corridor (room_9, floor 1), which the mission forbids: go to the kitchen (room_4, "
        "floor 0), without entering the corridor (room_9, floor 1) before that")


def test_the_profiles_differ_on_the_first_pose():
    mission = compile_mission('F "enter(room_11)" & G !"enter(room_2)"')  # the start is in room_2
    start = path()[:1, :3]
    ltlf = monitor(mission).observe_cells(start)
    assert ltlf.verdict == "violated" and ltlf.violation is not None and ltlf.violation.pose == 0
    assert ltlf.violation.text.startswith("started in the corridor (room_2, floor 0), which the mission "
                                          "forbids")
    authors = monitor(mission, profile="authors")
    assert authors.observe_cells(start).verdict == "in-progress"
    second = authors.observe_cells(path()[1:2, :3])
    assert second.verdict == "violated" and second.violation is not None and second.violation.pose == 1


def test_poses_off_the_grid_are_errors_and_nothing_of_the_call_is_read():
    mon = monitor()
    mon.observe_cells(path()[:3, :3])
    rows = demo_plan().grid.shape[1]
    for bad, fragment in [
        ([[0.0, 0.0, 0], [1000.0, 3.0, 0]], "pose 4: (x 1000 m, y 3 m, floor 0) lies off the grid (x from"),
        ([[0.0, 0.0, 5]], "pose 3: (x 0 m, y 0 m, floor 5) is on no floor of the scene (floors 0..1)"),
        ([[np.nan, 0.0, 0]], "pose 3: (x nan m, y 0 m, floor 0) is not a pose"),
        ([[0.0, 0.0, 0.5]], "is not a pose"),
    ]:
        with pytest.raises(TrajectoryError, match=fragment.replace("(", r"\(").replace(")", r"\)")):
            mon.observe_xy(bad)
    with pytest.raises(TrajectoryError, match=f"pose 3: .row {rows}, col 1, floor 0. lies off the"):
        mon.observe_cells([rows, 1, 0])
    with pytest.raises(TrajectoryError, match="is not a pose"):
        mon.observe_cells([1.5, 1, 0])
    assert (mon.poses, mon.state, mon.cell) == (3, int(path()[2, 3]), tuple(int(v) for v in path()[2, :3]))
    assert mon.observe_cells(path()[3:, :3]).states.tolist() == path()[3:, 3].tolist()


def test_poses_in_obstacles_are_reported_where_and_why_and_read_as_they_lie():
    demo = demo_plan()
    wall = np.argwhere((demo.building.floors[0].cat_map == CatCode.WALL) & ~demo.grid.traversable[0])[0]
    near = np.argwhere(demo.grid.traversable[0] & (demo.grid.room_map[0] > 0)
                       & (demo.building.floors[0].cat_map == CatCode.GROUND))
    free = near[0]
    margin = np.argwhere(~demo.grid.traversable[0] & (demo.grid.room_map[0] > 0)
                         & (demo.building.floors[0].cat_map == CatCode.GROUND))[0]
    poses = np.array([[*free, 0], [*wall, 0], [*wall, 0], [*margin, 0]])
    status = monitor().observe_cells(poses)
    kinds = [(i.kind, i.first_pose, i.last_pose) for i in status.issues]
    assert ("obstacle", 1, 2) in kinds and ("obstacle", 3, 3) in kinds
    wall_issue = next(i for i in status.issues if i.kind == "obstacle" and i.first_pose == 1)
    assert wall_issue.message.startswith("pose 1 to pose 2 lie in a wall (the first at x ")
    assert "read as it lies, not moved" in wall_issue.message
    margin_issue = next(i for i in status.issues if i.kind == "obstacle" and i.first_pose == 3)
    assert "within 0.15 m (the robot radius) of an obstacle" in margin_issue.message
    assert status.cell == (int(margin[0]), int(margin[1]), 0)  # not snapped


def test_gaps_and_lines_through_obstacles_are_reported():
    demo = demo_plan()
    keep = simplify_path(path(), demo.grid, demo_labels(), demo.mission.automaton)
    gaps = monitor(max_gap_m=1.0).observe_cells(path()[keep, :3])
    steps = np.hypot(*(np.diff(path()[keep, :2], axis=0) * demo.grid.resolution_m).T)
    flagged = {p for i in gaps.issues if i.kind == "gap" for p in range(i.first_pose, i.last_pose + 1)}
    assert flagged == {int(k) + 1 for k in np.flatnonzero(steps > 1.0)} and flagged
    assert not monitor(max_gap_m=100.0).observe_cells(path()[keep, :3]).issues
    assert not any(i.kind == "crosses-obstacle" for i in gaps.issues)  # simplified segments stay free
    a, b = _cells_seen_through_a_wall(demo)
    crossing = monitor().observe_cells([[*a, 0], [*b, 0]])
    assert [i.kind for i in crossing.issues if i.kind != "gap"] == ["crosses-obstacle"]
    assert crossing.issues[-1].message.startswith("the straight line to pose 1 from the pose before crosses")


def _cells_seen_through_a_wall(demo: DemoPlan) -> tuple[tuple[int, int], tuple[int, int]]:
    """Two free cells of floor 0 (in two rooms) whose straight line crosses cells the robot cannot enter."""
    free = demo.grid.traversable[0]
    inside = [np.argwhere(free & (demo.grid.room_map[0] == room.id))
              for room in demo.building.floors[0].rooms.values()]
    middles = [tuple(int(v) for v in cells[len(cells) // 2]) for cells in inside if len(cells)]
    for a in middles:
        for b in middles:
            if not free[tuple(crossed_cells(a, b).T)].all():
                return a, b
    raise AssertionError("no two rooms of the demo are separated by a wall")


def test_floors_without_stairs_between_them_are_an_error():
    demo = demo_plan()
    grid = dataclasses.replace(demo.grid, stairs=())
    mon = Monitor(demo.building, demo.mission, grid, demo_labels())
    on_two_floors = path()[[0, -1], :3]
    with pytest.raises(TrajectoryError, match="pose 0 on floor 0 and pose 1 on floor 1: no stairs join "
                                              "floors 0 and 1 in this scene"):
        mon.observe_cells(on_two_floors)


def test_a_resumed_monitor_continues_the_run():
    half = len(path()) // 2
    whole = monitor().observe_cells(path()[:, :3])
    resumed = monitor(state=int(path()[half, 3]), at=tuple(int(v) for v in path()[half, :3]))
    rest = resumed.observe_cells(path()[half + 1:, :3])
    assert rest.states.tolist() == whole.states[half + 1:].tolist() and rest.verdict == whole.verdict
    mon = monitor()
    mon.observe_cells(path()[:half, :3])
    moved = mon.rebased(demo_plan().grid, demo_labels())
    assert moved.observe_cells(path()[half:, :3]).states.tolist() == whole.states[half:].tolist()
    with pytest.raises(PlanningError, match="automaton state 99 does not exist"):
        monitor(state=99)


def test_an_empty_batch_reads_nothing():
    mon = monitor()
    mon.observe_cells(path()[:4, :3])
    status = mon.observe_xy(np.zeros((0, 3)))
    assert status.poses == 4 and status.states.size == 0 and status.state == int(path()[3, 3])


@given(seed=st.integers(0, 2**32 - 1), formula=formulas(("p0", "p1", "p2"), max_leaves=6),
       profile=st.sampled_from(["ltlf", "authors"]))
def test_states_equal_the_automaton_stepped_over_every_cell_passed(seed, formula, profile):
    """Random buildings, missions, trajectories (neighbour steps, long jumps, repeats, floor changes) and
    batches: the monitor's state after each pose is the automaton run over the label of every cell passed,
    and its verdict and violation follow from those states."""
    rng = np.random.default_rng(seed)
    building = random_small_building(rng)
    grid = build_occupancy_grid(building, 0.0)
    mission = compile_mission(formula, _random_meanings(building, rng))
    labels = mission.labels(building, 0.5)
    poses = _random_poses(grid, rng)
    mon = Monitor(building, mission, grid, labels, profile=profile)
    cuts = np.sort(rng.choice(np.arange(1, len(poses)), size=min(3, len(poses) - 1), replace=False))
    statuses = [mon.observe_cells(part) for part in np.split(poses, cuts)]
    expected, per_cell = states_after_poses([tuple(p) for p in poses.tolist()], grid, labels,
                                            mission.automaton, profile)
    assert np.concatenate([s.states for s in statuses]).tolist() == expected
    automaton = mission.automaton
    realizable = np.zeros(automaton.num_labels, bool)
    realizable[np.unique(labels[grid.traversable])] = True
    dead = ~automaton.live_states(realizable)
    final = statuses[-1]
    assert final.verdict == ("violated" if dead[expected[-1]] else
                             "done" if automaton.accepting[expected[-1]] else "in-progress")
    assert final.cells == len(per_cell)
    before = [automaton.initial, *per_cell[:-1]]
    first_dead = next((k for k, (p, q) in enumerate(zip(before, per_cell)) if dead[q] and not dead[p]), None)
    assert (final.violation is None) == (first_dead is None)
    if final.violation is not None:
        assert int(final.violation.to_state) == per_cell[first_dead]


def _random_meanings(building, rng: np.random.Generator) -> dict[str, Proposition]:
    rooms = [Proposition("enter", room.uuid) for room in building.rooms()]
    objects = [Proposition("reach", obj.uuid) for obj in building.objects()]
    pool = rooms + objects
    return {f"p{k}": pool[int(i)] for k, i in enumerate(rng.choice(len(pool), size=3, replace=len(pool) < 3))}


def _random_poses(grid, rng: np.random.Generator) -> np.ndarray:
    free = np.argwhere(grid.traversable)  # (floor, row, col)
    poses = [free[rng.integers(len(free))]]
    for _ in range(int(rng.integers(1, 25))):
        move = rng.random()
        f, r, c = poses[-1]
        if move < 0.5:  # a neighbour step (maybe into an obstacle: read as it lies)
            dr, dc = rng.integers(-1, 2, size=2)
            step = (f, min(max(r + dr, 0), grid.shape[1] - 1), min(max(c + dc, 0), grid.shape[2] - 1))
            poses.append(np.array(step))
        elif move < 0.6:
            poses.append(poses[-1])  # standing still
        else:  # a jump anywhere free, maybe on another floor
            poses.append(free[rng.integers(len(free))])
    return np.array([[r, c, f] for f, r, c in poses], dtype=np.int64)


def test_a_monitor_resumed_past_saving_is_violated_without_naming_a_step():
    mission = compile_mission(BEDROOM_NO_STAIRS)
    broken = monitor(mission).observe_cells(path()[:, :3])
    resumed = monitor(mission, state=broken.state, at=tuple(int(v) for v in path()[-1, :3]))
    status = resumed.observe_cells(path()[-3:, :3])
    assert status.verdict == "violated" and status.violation is None
    assert status.summary() == (f"violated: the mission cannot be completed from automaton state "
                                f"{broken.state}, as already when the monitor started")


def test_a_mission_without_a_formula_is_said_back_from_its_automaton():
    demo = demo_plan()
    bare = dataclasses.replace(demo.mission, formula=None)
    status = monitor(bare).observe_cells(path()[:5, :3])
    assert status.verdict == "in-progress"
    assert status.left.startswith("as read from its automaton:\nIt mentions ")
    assert "the bedroom (room_11, floor 1)" in status.left


def test_done_with_nothing_left_to_keep():
    status = monitor(compile_mission('F "enter(room_11)"')).observe_cells(path()[:, :3])
    assert status.verdict == "done" and status.left == ""
    assert status.summary() == "done: the mission is satisfied"
