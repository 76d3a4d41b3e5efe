"""Choosing the reach model (sgplan.scene.reach) through the API, a session, the CLI and the records: the
demo's chair case under both models, each plan's cost equal to the independent exact solver's."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import sgplan
from sgplan.cli import main
from sgplan.commands.demo import DEMO_MISSION
from sgplan.scene.labels import Proposition, proposition_cells
from tests.planning.oracle import optimal_cost

CHAIR = "reach(object_29)"
"""The dining chair the demo mission's optimal path sits on."""


@pytest.fixture(scope="module")
def demo() -> sgplan.api.Building:
    return sgplan.load_scene("demo")


@pytest.fixture(scope="module")
def demo_mission(demo: sgplan.api.Building) -> sgplan.Mission:
    return sgplan.mission_from_text(DEMO_MISSION, demo)


def _chair_distance_m(building: sgplan.api.Building, result: sgplan.PlanResult) -> float:
    """Metres from where the path first reaches the chair to the nearest chair cell."""
    event = next(e for e in result.events if e.proposition == CHAIR)
    footprint = np.argwhere(building.floors[event.floor].cat_map == building.object(uuid=29).id)
    res = np.asarray(building.resolution_m)
    return float(np.sqrt((((footprint - [event.row, event.col]) * res) ** 2).sum(axis=1)).min())


@pytest.mark.parametrize(("model", "chosen"), [("box", "box"), ("visible", "visible"), (None, "visible")])
def test_the_demo_chair_is_sat_on_within_reach_and_the_cost_is_the_exact_optimum(
    demo: sgplan.api.Building, demo_mission: sgplan.Mission, model: str | None, chosen: str
) -> None:
    """The box window "reached" the chair from the dining room's doorway, 0.78 m away with a 0.6 m reach;
    the visible model sits within 0.6 m, a little further on (a longer optimum)."""
    result = sgplan.plan(demo, demo_mission, 0, reach_model=model)
    assert result.status == "optimal" and result.verified and result.reach_model == chosen
    assert result.to_dict()["reach_model"] == chosen
    assert result.cost_m == pytest.approx(
        optimal_cost(result.grid, result.labels, demo_mission.automaton, result.start, "ltlf"), abs=1e-9)
    distance = _chair_distance_m(demo, result)
    if chosen == "box":
        assert distance > 0.75 and result.cost_m == pytest.approx(24.3061, abs=1e-4)
    else:
        assert distance <= 0.6 and result.cost_m == pytest.approx(24.6890, abs=1e-4)


def test_the_profile_chooses_the_model_unless_one_is_given(demo: sgplan.api.Building) -> None:
    mission = sgplan.mission_from_formula(f'F "{CHAIR}"', demo)
    assert sgplan.plan(demo, mission, 0, profile="authors").reach_model == "box"
    assert sgplan.plan(demo, mission, 0, profile="authors", reach_model="visible").reach_model == "visible"


def test_a_session_keeps_the_cells_of_each_model_apart(demo: sgplan.api.Building) -> None:
    session = sgplan.Session(demo)
    mission = sgplan.mission_from_formula(f'F "{CHAIR}"', demo)
    box = session.plan(mission, 0, reach_model="box")
    visible = session.plan(mission, 0, reach_model="visible")
    again = session.plan(mission, 0, reach_model="box")
    assert box.cost_m == again.cost_m and visible.cost_m > box.cost_m
    prop = Proposition("reach", 29)
    for model in ("box", "visible"):
        assert np.array_equal(session.proposition_cells(prop, 0.6, model),
                              proposition_cells(demo, prop, 0.6, model))
    assert session.builds["label_mask"] == 2  # the chair under each model, once
    assert np.array_equal(np.flatnonzero(visible.labels), proposition_cells(demo, prop, 0.6, "visible"))


def test_plan_reach_model_on_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    runs = {}
    for model in ("box", "visible"):
        out = tmp_path / f"{model}.json"
        assert main(["plan", "--scene", "demo", "--formula", f'F "{CHAIR}"', "--reach-model", model.upper(),
                     "--setup", "NO-LLM", "--json", str(out)]) == 0
        runs[model] = json.loads(out.read_text())
    assert runs["box"]["reach_model"] == "box" and runs["visible"]["reach_model"] == "visible"
    assert runs["box"]["cost_m"] < runs["visible"]["cost_m"]
    with pytest.raises(SystemExit) as stop:
        main(["plan", "--scene", "demo", "--formula", f'F "{CHAIR}"', "--reach-model", "sphere"])
    assert stop.value.code == 2
    assert "invalid choice: 'sphere' (choose from 'box', 'visible')" in capsys.readouterr().err


def test_the_monitor_reads_the_mission_under_the_plans_reach_model(demo: sgplan.api.Building) -> None:
    from sgplan.execution.monitor import Monitor

    session = sgplan.Session(demo)
    mission = sgplan.mission_from_formula(f'F "{CHAIR}"', demo)
    for profile, model, expected in (("ltlf", None, "visible"), ("authors", None, "box"),
                                     ("authors", "visible", "visible")):
        monitor = Monitor.in_session(session, mission, profile=profile, reach_model=model)
        assert np.array_equal(monitor.labels, session.labels(mission, None, expected))
    plan = session.plan(mission, 0, reach_model="box")
    monitor = Monitor.in_session(session, mission, reach_model="box")
    assert monitor.observe_cells(plan.path[:, :3]).accepting


@pytest.mark.parametrize("model", ["box", "visible"])
def test_a_run_relabels_an_object_when_an_obstacle_appears_in_its_reach(demo: sgplan.api.Building,
                                                                         model: str) -> None:
    """A block beside the chair moves no object, yet under ``visible`` the chair is no longer reached from
    the blocked floor: the run's labels stay those of its changed building, under either model."""
    from sgplan.execution.changes import Area, Block

    mission = sgplan.mission_from_formula(f'F "{CHAIR}"', demo)
    run = sgplan.Run(sgplan.Session(demo), mission, 0, reach_model=model)
    chair = demo.object(uuid=29)
    floor = demo.floors[demo.room(uuid=chair.room_uuid).floor]
    x, y = floor.cell_to_xy((chair.grid_max[0] + 4, (chair.grid_min[1] + chair.grid_max[1]) // 2))
    before = run.labels.raster.copy()
    run.change([Block(Area(floor.index, box_m=(x - 0.1, y - 0.1, x + 0.1, y + 0.1)))])
    fresh = sgplan.Session(run.building).labels(run.mission, None, model)
    assert np.array_equal(run.labels.raster, fresh)
    assert np.array_equal(run.labels.raster, before) == (model == "box")
