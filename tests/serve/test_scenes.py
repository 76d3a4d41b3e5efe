"""Served scenes: one warm session per plan worker, each lent to one plan at a time."""

from __future__ import annotations

import pytest

import sgplan
from sgplan.serve.config import ServeError
from sgplan.serve.scenes import SceneHost, SceneRegistry


def test_sessions_are_lent_one_plan_at_a_time() -> None:
    host = SceneHost(sgplan.load_scene("demo"), planners=2)
    with host.planner() as first, host.planner() as second:
        assert first is not second and host.session in (first, second)
        with pytest.raises(TimeoutError), host.planner(wait_s=0.01):
            pass
    with host.planner(wait_s=0.01) as again:  # given back
        assert again in (first, second)
    with host.planner() as one:
        pass
    for _ in range(3):  # one plan at a time: always the session used last, whose planner parts are warm
        with host.planner() as next_one:
            assert next_one is one
    assert host.sessions[0] is host.session and len(set(map(id, host.sessions))) == 2


def test_a_building_is_served_once() -> None:
    building = sgplan.load_scene("demo")
    with pytest.raises(ServeError, match="two scenes are called 'demo-house'"):
        SceneRegistry([SceneHost(building), SceneHost(building)])


def test_every_planner_session_is_warm_from_the_start() -> None:
    host = SceneRegistry.load(["demo"], planners=2)["demo"]
    assert [session.builds["grid"] for session in host.sessions] == [1, 1]
