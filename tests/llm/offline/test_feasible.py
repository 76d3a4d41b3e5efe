"""The offline translator refuses a mission no walk through the scene's rooms can do, naming the parts that
clash (:mod:`sgplan.llm.offline.meaning.feasible`), and the planner agrees that no path exists."""

from __future__ import annotations

import pytest

import sgplan
from sgplan.errors import MissionError, PlanningError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.meaning.feasible import check_can_be_done
from sgplan.logic import parse_infix
from sgplan.scene.model import Building

IMPOSSIBLE = [
    # the fridge is in the kitchen, which is forbidden; the office waits for the fridge
    ('G !"enter(room_4)" & (!"enter(room_12)" U "reach(object_15)") & F "enter(room_12)"',
     ["Never enter the kitchen", "Reach the refrigerator"]),
    # the bedroom with the book opens only onto the upstairs corridor
    ('F "enter(room_13)" & G !"enter(room_9)"', ["Go to the bedroom", "Never enter the corridor"]),
    # the oven downstairs and the laptop upstairs, without the staircase (a start on each floor)
    ('F "reach(object_16)" & F "reach(object_35)" & G !"enter(room_8)"',
     ["Reach the oven", "Reach the laptop", "Never enter the staircase"]),
]
POSSIBLE = [
    'F "enter(room_13)" & G !"enter(room_6)"',
    '(!"enter(room_12)" U "reach(object_15)") & F "enter(room_12)"',
    'F("reach(object_15)" & F("enter(room_14)" & F "reach(object_22)"))',
    'G("enter(room_7)" -> F "enter(room_4)") & F "enter(room_7)"',
]


@pytest.mark.parametrize(("infix", "named"), IMPOSSIBLE)
def test_an_impossible_mission_is_refused_with_the_parts_that_clash(demo: Building, infix: str,
                                                                   named: list[str]) -> None:
    formula = parse_infix(infix)
    with pytest.raises(MissionError) as refusal:
        check_can_be_done(formula, demo, None)
    message = str(refusal.value)
    assert "no way through this scene's rooms and doors" in message
    assert all(part in message for part in named), message
    mission = sgplan.mission_from_formula(formula, demo)
    for start in range(len(demo.initial_cells)):  # the planner, an independent exact search, agrees
        with pytest.raises(PlanningError):
            sgplan.plan(demo, mission, start, setup="NO-LLM")


@pytest.mark.parametrize("infix", POSSIBLE)
def test_a_possible_mission_passes(demo: Building, infix: str) -> None:
    formula = parse_infix(infix)
    check_can_be_done(formula, demo, None)
    result = sgplan.plan(demo, sgplan.mission_from_formula(formula, demo), 0, setup="NO-LLM")
    assert result.path is not None and len(result.path)


def test_the_start_floor_limits_the_starts(demo: Building) -> None:
    """From the upper floor the kitchen needs the staircase; from the ground floor it does not."""
    formula = parse_infix('F "enter(room_4)" & G !"enter(room_8)"')
    check_can_be_done(formula, demo, 0)
    with pytest.raises(MissionError, match="Never enter the staircase"):
        check_can_be_done(formula, demo, 1)


def test_the_translator_refuses_such_a_text(demo: Building) -> None:
    text = "Go to the bedroom with the book, but never enter the upstairs corridor."
    with pytest.raises(MissionError, match="no way through this scene's rooms and doors"):
        PatternTranslator().translate(text, demo)
