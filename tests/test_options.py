"""The planning options as one value (sgplan.PlanOptions): stated once, validated once, serialisable, and
taken as a value or as keywords by the API, the CLI and the benchmark worker."""

from __future__ import annotations

import argparse
import inspect
import json

import numpy as np
import pytest

import sgplan
from sgplan.cli import _build_parser
from sgplan.commands.common import plan_options
from sgplan.errors import PlanningError
from sgplan.options import PlanOptions
from sgplan.planning.termination import AnyOf, ExpansionLimit, TimeLimit

FORMULA = 'F("enter(room_4)" & F "enter(room_11)")'


@pytest.fixture(scope="module")
def demo() -> sgplan.api.Building:
    return sgplan.load_scene("demo")


@pytest.fixture(scope="module")
def mission(demo) -> sgplan.api.Mission:
    return sgplan.mission_from_formula(FORMULA, demo)


def test_the_defaults_are_those_of_the_api() -> None:
    assert PlanOptions() == PlanOptions(setup="ALL", profile="ltlf", robot_radius_m=None, reach_radius_m=None,
                                        reach_model=None, time_limit_s=None, max_expansions=None,
                                        verify=True, prebuild_actions=False)
    assert PlanOptions.names() == ("setup", "profile", "robot_radius_m", "reach_radius_m", "reach_model",
                                   "time_limit_s", "max_expansions", "verify", "prebuild_actions")


def test_names_are_normalised_and_numbers_become_plain() -> None:
    options = PlanOptions(setup="no_llm", profile="AUTHORS", robot_radius_m=np.float32(0.25),
                          reach_radius_m=1, time_limit_s=np.int64(3), max_expansions=np.int64(10))
    assert (options.setup, options.profile) == ("NO-LLM", "authors")
    assert PlanOptions(setup="a_star").setup == "A*"
    assert options.robot_radius_m == 0.25 and type(options.robot_radius_m) is float
    assert type(options.reach_radius_m) is float and type(options.time_limit_s) is float
    assert options.max_expansions == 10 and type(options.max_expansions) is int


def test_the_reach_model_is_the_profiles_unless_chosen() -> None:
    assert PlanOptions().reach_model is None and PlanOptions().effective_reach_model == "visible"
    assert PlanOptions(profile="authors").effective_reach_model == "box"
    chosen = PlanOptions(profile="authors", reach_model=" Visible ")
    assert chosen.reach_model == "visible" and chosen.effective_reach_model == "visible"
    assert chosen.replace(reach_model=None).effective_reach_model == "box"
    assert PlanOptions(reach_model="BOX").to_dict()["reach_model"] == "box"


@pytest.mark.parametrize(("given", "message"), [
    ({"setup": "FAST"}, "unknown setup 'FAST'; use one of ALL, NO-LLM, A*"),
    ({"setup": 3}, "setup must be a name"),
    ({"profile": "strict"}, "unknown semantics profile 'strict'; use one of ltlf, authors"),
    ({"robot_radius_m": -0.1}, "robot_radius_m must be a number of metres >= 0 and <= 2"),
    ({"robot_radius_m": 5.0}, "robot_radius_m must be a number of metres >= 0 and <= 2"),
    ({"reach_radius_m": 0.0}, "reach_radius_m must be a number of metres > 0 and <= 100"),
    ({"reach_radius_m": float("nan")}, "reach_radius_m must be"),
    ({"reach_radius_m": "0.5"}, "reach_radius_m must be"),
    ({"time_limit_s": 0}, "time_limit_s must be a number of seconds > 0"),
    ({"time_limit_s": float("inf")}, "time_limit_s must be"),
    ({"max_expansions": -1}, "max_expansions must be a whole number >= 0"),
    ({"max_expansions": 2.5}, "max_expansions must be a whole number"),
    ({"max_expansions": True}, "max_expansions must be a whole number"),
    ({"verify": "yes"}, "verify must be True or False, got 'yes'"),
    ({"prebuild_actions": 1}, "prebuild_actions must be True or False"),
    ({"reach_model": "sphere"}, "unknown reach model 'sphere'; use one of box, visible"),
])
def test_a_bad_value_is_refused_naming_the_option_and_what_is_allowed(given: dict, message: str) -> None:
    with pytest.raises(PlanningError) as error:
        PlanOptions(**given)
    assert message in str(error.value) and "\n" not in str(error.value)
    assert error.value.status == "error"


def test_the_options_round_trip_through_json() -> None:
    options = PlanOptions(setup="ROOM", profile="authors", robot_radius_m=0.2, reach_radius_m=0.9,
                          time_limit_s=2.5, max_expansions=1000, verify=False, prebuild_actions=True)
    record = json.loads(json.dumps(options.to_dict()))
    assert PlanOptions.from_dict(record) == options
    assert PlanOptions.from_dict({}) == PlanOptions() and PlanOptions.from_dict({"setup": "A*"}).setup == "A*"
    assert list(PlanOptions().to_dict()) == list(PlanOptions.names())


def test_reading_a_stored_dict_refuses_what_is_no_option() -> None:
    with pytest.raises(PlanningError, match="unknown planning option colour; the options are setup, profile"):
        PlanOptions.from_dict({"setup": "ALL", "colour": "red"})
    with pytest.raises(PlanningError, match="must be a mapping"):
        PlanOptions.from_dict(["ALL"])  # type: ignore[arg-type]
    with pytest.raises(PlanningError, match="unknown setup"):
        PlanOptions.from_dict({"setup": "nope"})


def test_replace_validates_again_and_keeps_the_rest() -> None:
    options = PlanOptions(setup="NO-LLM", time_limit_s=4.0)
    assert options.replace(max_expansions=7) == PlanOptions(setup="NO-LLM", time_limit_s=4.0,
                                                            max_expansions=7)
    with pytest.raises(PlanningError, match="robot_radius_m"):
        options.replace(robot_radius_m=-1.0)
    with pytest.raises(TypeError, match="unknown planning option setups; the options are setup, profile"):
        options.replace(setups="ALL")


def test_the_budgets_make_the_search_termination() -> None:
    assert PlanOptions().termination() is None
    assert PlanOptions(time_limit_s=2.0).termination() == TimeLimit(2.0)
    assert PlanOptions(max_expansions=5).termination() == ExpansionLimit(5)
    assert PlanOptions(time_limit_s=2.0, max_expansions=5).termination() == AnyOf((TimeLimit(2.0),
                                                                                  ExpansionLimit(5)))


def test_plan_and_session_state_no_option_of_their_own() -> None:
    """The options are the value's fields alone: neither signature lists one (they come as **keywords)."""
    for function in (sgplan.plan, sgplan.Session.plan):
        parameters = inspect.signature(function).parameters
        assert not set(parameters) & set(PlanOptions.names())
        assert "options" in parameters and any(p.kind is p.VAR_KEYWORD for p in parameters.values())


def test_todays_keywords_plan_as_the_options_value_does(demo, mission) -> None:
    by_keywords = sgplan.plan(demo, mission, 1, setup="no-llm", profile="authors", reach_radius_m=0.7,
                              prebuild_actions=True, verify=True)
    options = PlanOptions(setup="NO-LLM", profile="authors", reach_radius_m=0.7, prebuild_actions=True)
    by_value = sgplan.plan(demo, mission, 1, options=options)
    assert by_keywords.status == by_value.status == "optimal"
    assert (by_keywords.setup, by_keywords.profile) == ("NO-LLM", "authors")
    assert by_keywords.radii.reach_m == 0.7 and by_keywords.radii.reach_from == "given"
    assert by_keywords.cost_m == by_value.cost_m and np.array_equal(by_keywords.path, by_value.path)
    session = sgplan.Session(demo)
    assert session.plan(mission, 1, options=options).cost_m == by_value.cost_m


def test_keywords_replace_the_fields_of_a_given_value(demo, mission) -> None:
    options = PlanOptions(setup="NO-LLM", max_expansions=1)
    cut = sgplan.plan(demo, mission, 0, options=options)
    whole = sgplan.plan(demo, mission, 0, options=options, max_expansions=None)
    assert cut.status == "timeout" and whole.status == "optimal" and whole.setup == "NO-LLM"


def test_an_unknown_keyword_is_a_type_error_naming_the_options(demo, mission) -> None:
    expected = "unknown planning option time_limit; the options are setup, profile, robot_radius_m"
    with pytest.raises(TypeError, match=expected):
        sgplan.plan(demo, mission, 0, time_limit=5)
    with pytest.raises(TypeError, match="unknown planning options robot_radius, setups"):
        sgplan.Session(demo).plan(mission, 0, setups="ALL", robot_radius=0.1)


def test_a_bad_option_fails_before_any_work(demo, mission) -> None:
    session = sgplan.Session(demo)
    with pytest.raises(PlanningError, match="unknown setup 'FAST'"):
        session.plan(mission, 0, setup="FAST")
    assert not session.builds  # no grid, no labels


def test_the_cli_builds_the_options_from_its_arguments() -> None:
    args = _build_parser().parse_args([
        "plan", "--scene", "demo", "--formula", FORMULA, "--setup", "no_llm", "--profile", "AUTHORS",
        "--robot-radius", "0.1", "--reach-radius", "0.8", "--reach-model", "Visible", "--time-limit", "3",
        "--max-expansions", "99", "--verify",
    ])
    assert plan_options(args) == PlanOptions(setup="NO-LLM", profile="authors", robot_radius_m=0.1,
                                             reach_radius_m=0.8, reach_model="visible", time_limit_s=3.0,
                                             max_expansions=99)
    plain = _build_parser().parse_args(["plan", "--scene", "demo", "--formula", FORMULA])
    assert plan_options(plain) == PlanOptions() and plan_options(plain, setup="A*").setup == "A*"
    assert plan_options(argparse.Namespace(profile="authors", scene="demo")) == PlanOptions(profile="authors")


def test_the_cli_says_a_bad_setup_in_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    from sgplan.cli import main

    assert main(["plan", "--scene", "demo", "--formula", FORMULA, "--setup", "FAST"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1] == "sgplan: error: unknown setup 'FAST'; use one of ALL, NO-LLM, A*, OCC, OBJ, ROOM, FLR"
