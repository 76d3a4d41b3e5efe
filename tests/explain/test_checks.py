"""Scene-aware checks before planning, on the demo building (one room at a time; the sink object_21 is
in the bathroom room_5; the corridor room_2 holds start 0; the bedroom room_11 is upstairs, reached only
by the staircase room_8)."""

from __future__ import annotations

import pytest

from sgplan.assembly import make_problem
from sgplan.errors import PlanningError, UnsatisfiableMissionError
from sgplan.explain.checks import check_mission_in_scene
from sgplan.mission import compile_mission
from sgplan.planning.amra import plan
from sgplan.scene.demo import demo_building

BUILDING = demo_building()
START = BUILDING.initial_cells[0]


def _check(formula: str, start: tuple[int, int, int] | None = START,  # type: ignore[no-untyped-def]
           reach_model: str | None = None):
    return check_mission_in_scene(compile_mission(formula), BUILDING, start, reach_model=reach_model)


def _kinds(check) -> list[str]:  # type: ignore[no-untyped-def]
    return [f.kind for f in check.findings]


def test_contradiction_is_unsatisfiable_from_any_start_and_names_the_conflict() -> None:
    check = _check('F "enter(room_4)" & G !"enter(room_4)" & F "enter(room_11)"')
    assert _kinds(check) == ["unsatisfiable"]
    message = check.findings[0].message
    assert "from any start" in message
    assert "Go to the kitchen (room_4, floor 0). Never enter the kitchen (room_4, floor 0)." in message
    assert "room_11" not in message  # only the parts in conflict are named
    with pytest.raises(UnsatisfiableMissionError) as error:
        check.raise_errors()
    assert error.value.status == "unsatisfiable" and error.value.exit_code == 4


def test_object_reached_from_a_room_it_is_not_in() -> None:
    # The bathroom sink is in sight through the door from a corner of the kitchen: possible, but said.
    check = _check('F("enter(room_4)" & "reach(object_21)")')
    assert _kinds(check) == ["object-outside-room"]
    assert ("is not in the kitchen (room_4, floor 0): it is reached from there only through a door, in sight "
            "of it") in check.findings[0].message
    # The authors' window also crosses the wall beside it.
    check = _check('F("enter(room_4)" & "reach(object_21)")', reach_model="box")
    assert "it is reached from there only through a wall" in check.findings[0].message
    # The upstairs sink (object_41) is out of reach from the kitchen: nothing satisfies the mission.
    check = _check('F("enter(room_4)" & "reach(object_41)")')
    assert _kinds(check) == ["unsatisfiable", "impossible-part"]
    assert "no place in this scene is in the kitchen" in check.findings[1].message
    assert "this part cannot hold in this scene: Reach the sink (object_41" in check.findings[0].message


def test_a_local_avoidance_the_scene_makes_vacuous_is_a_warning() -> None:
    check = _check('F("enter(room_11)" & !"enter(room_4)")')
    assert _kinds(check) == ["vacuous"]
    assert "'not in the kitchen (room_4, floor 0)' changes nothing" in check.findings[0].message
    check.raise_errors()  # a warning only


def test_avoiding_a_place_the_robot_can_never_be_at_is_said_shortly() -> None:
    """'Stay on this floor' lists every room of the other floors, some of which the robot may not fit
    into: the warning says so, not every other room of the list."""
    # With a reach radius barely above the robot's, no free cell is within reach of the microwave.
    mission = compile_mission('F("enter(room_11)" & !"reach(object_18)" & !"enter(room_4)")')
    check = check_mission_in_scene(mission, BUILDING, START, reach_radius_m=0.16)
    messages = [f.message for f in check.findings]
    microwave = "the microwave (object_18, in the kitchen room_4, floor 0)"
    assert messages[0] == (f"'not within reach of {microwave}' changes nothing: no place of this scene the "
                           f"robot can be at is within reach of {microwave}")
    assert _kinds(check) == ["vacuous", "vacuous"]


def test_start_inside_a_forbidden_room_is_unsatisfiable_from_this_start_only() -> None:
    check = _check('F "enter(room_11)" & G !"enter(room_2)"')
    assert _kinds(check) == ["unsatisfiable-from-start"]
    with pytest.raises(PlanningError) as error:
        check.raise_errors()
    assert error.value.status == "invalid-start" and error.value.exit_code == 2
    assert _check('F "enter(room_11)" & G !"enter(room_2)"', start=None).findings == ()


def test_goal_reachable_only_through_a_forbidden_room_names_it() -> None:
    check = _check('F "enter(room_11)" & G !"enter(room_8)"')
    assert _kinds(check) == ["blocked-by-forbidden"]
    message = check.findings[0].message
    assert "the bedroom (room_11, floor 1)" in message and "the staircase (room_8, floor 0)" in message
    with pytest.raises(PlanningError) as error:
        check.raise_errors()
    assert error.value.status == "infeasible"


def test_blocked_agrees_with_the_planner() -> None:
    mission = compile_mission('F "enter(room_11)" & G !"enter(room_8)"')
    prepared = make_problem(BUILDING, mission, START)
    with pytest.raises(PlanningError) as error:
        plan(prepared.problem, "NO-LLM")
    assert error.value.status == "infeasible"


def test_already_satisfied_at_the_start_is_said() -> None:
    check = _check('F "enter(room_2)"')
    assert _kinds(check) == ["satisfied-at-start"] and "0 m" in check.findings[0].message
    check.raise_errors()


def test_a_plain_mission_has_no_findings() -> None:
    check = _check('F("enter(room_5)" & F "enter(room_11)") & G !"enter(room_6)"')
    assert check.findings == () and check.to_dict() == []
