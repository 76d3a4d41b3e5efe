"""``sgplan simulate`` and ``sgplan plan --after`` end to end on the demo building."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from sgplan.cli import main
from sgplan.commands.monitor import VIOLATED_EXIT
from sgplan.execution.run import IMPOSSIBLE_EXIT

MISSION = "Go to the kitchen, then the bedroom with the clock."
FORMULA = 'F("enter(room_4)" & F "enter(room_11)") & G !"enter(room_6)"'
START = ["--start-room", "bathroom on floor 0"]


def _changes(folder: Path, text: str) -> Path:
    path = folder / "changes.yaml"
    path.write_text(text)
    return path


def test_simulate_replans_at_each_change_and_writes_the_log(tmp_path, capsys):
    changes = _changes(tmp_path, "version: 1\nchanges:\n"
                       "  - {kind: close_door, rooms: [kitchen, corridor on floor 0], when: {after_m: 3}}\n"
                       "  - {kind: block, floor: 1, box_m: [0.0, -1.0, 1.0, 0.0], when: {enter: room_9}}\n")
    code = main(["simulate", "--scene", "demo", "--text", MISSION, *START, "--changes", str(changes),
                 "--setup", "A*", "--json", str(tmp_path / "log.json"), "--draw", str(tmp_path / "draw"),
                 "--html", str(tmp_path / "run.html")])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "closed the door between the kitchen (room_4, floor 0) and the corridor (room_2, floor 0)" in out
    assert "replanned in" in out and "done: the mission is satisfied" in out
    log = json.loads((tmp_path / "log.json").read_text())
    assert [m["what"][:6] for m in log["timeline"]][:2] == ["start", "closed"]
    assert log["status"] == "done" and len(log["plans"]) >= 2 and log["run"]["format"] == "sgplan-run"
    assert (tmp_path / "draw" / "run_0.png").stat().st_size > 0 and (tmp_path / "run.html").exists()


def test_simulate_says_why_when_the_rest_becomes_impossible(tmp_path, capsys):
    changes = _changes(tmp_path, "changes:\n  - {kind: close_door, rooms: [bedroom on floor 1, room_9], "
                       "when: {after_m: 2}}\n  - {kind: close_door, rooms: [kitchen, room_2]}\n"
                       "  - {kind: close_door, rooms: [kitchen, room_5]}\n")
    code = main(["simulate", "--scene", "demo", "--formula", FORMULA, *START, "--changes", str(changes),
                 "--setup", "A*"])
    out = capsys.readouterr().out
    assert code == IMPOSSIBLE_EXIT, out
    assert "stopped: the kitchen (room_4, floor 0) can no longer be reached" in out


def test_a_bad_changes_file_is_one_line_naming_the_change(tmp_path, capsys):
    changes = _changes(tmp_path, "changes:\n  - {kind: close_door, rooms: [kitchen]}\n")
    assert main(["simulate", "--scene", "demo", "--formula", FORMULA, "--changes", str(changes)]) == 2
    err = capsys.readouterr().err
    assert f"{changes}: change 1 (close_door): field 'rooms' must name two rooms" in err
    changes = _changes(tmp_path, "changes:\n  - {kind: close_door, rooms: [kitchen, garage]}\n")
    assert main(["simulate", "--scene", "demo", "--formula", FORMULA, "--changes", str(changes)]) == 2
    err = capsys.readouterr().err
    assert "change 1: close door: building 'demo-house' has no room called 'garage'" in err


def test_plan_after_a_trajectory_plans_the_rest_from_its_end(tmp_path, capsys):
    dense = tmp_path / "dense.csv"
    assert main(["plan", "--scene", "demo", "--formula", FORMULA, *START, "--setup", "A*",
                 "--waypoints", str(dense), "--dense", "--json", str(tmp_path / "full.json"), "-q"]) == 0
    full = json.loads((tmp_path / "full.json").read_text())
    lines = dense.read_text().splitlines()
    half = len(lines) // 2
    (tmp_path / "half.csv").write_text("\n".join(lines[: half + 1]) + "\n")
    assert main(["plan", "--scene", "demo", "--formula", FORMULA, "--after", str(tmp_path / "half.csv"),
                 "--setup", "A*", "--json", str(tmp_path / "rest.json"), "-q"]) == 0
    rest = json.loads((tmp_path / "rest.json").read_text())
    driven = full["waypoints"][half - 1]["cost_m"]
    assert rest["cost_m"] == pytest.approx(full["cost_m"] - driven, abs=1e-3)
    assert rest["after"]["verdict"] == "in-progress"


def test_plan_after_a_violating_trajectory_exits_6(tmp_path, capsys):
    trajectory = tmp_path / "living.csv"
    trajectory.write_text("x_m,y_m,floor\n-1.9,3.5,0\n-0.5,3.5,0\n-0.5,1.0,0\n2.0,-2.5,0\n")
    code = main(["plan", "--scene", "demo", "--formula", FORMULA, "--after", str(trajectory),
                 "--setup", "A*"])
    assert code == VIOLATED_EXIT
    assert "the trajectory violated" in capsys.readouterr().err


def test_the_pictures_draw_abandoned_plans_and_changed_cells_where_they_are(tmp_path):
    """In the map-frame picture a cell's data coordinates are (row, col): an abandoned plan is drawn on its
    own cells and a closed door on the door's cells (they were drawn transposed, through walls)."""
    import sgplan
    from sgplan.execution.changes import read_changes
    from sgplan.execution.drawing import simulation_figure
    from sgplan.execution.simulate import simulate

    changes = _changes(tmp_path, "version: 1\nchanges:\n"
                       "  - {kind: close_door, rooms: [kitchen, corridor on floor 0], when: {after_m: 3}}\n")
    building = sgplan.load_scene("demo")
    session = sgplan.Session(building)
    run = sgplan.Run(session, sgplan.mission_from_formula(FORMULA, building), "bathroom on floor 0",
                     setup="A*")
    sim = simulate(run, read_changes(changes))
    assert len(sim.plans) >= 2 and sim.changed.get(0)
    fig = simulation_figure(sim, 0)
    ax = fig.axes[0]
    dashed = [line for line in ax.get_lines() if line.get_linestyle() == "--" and len(line.get_xdata())]
    first = sim.plans[0][sim.plans[0][:, 2] == 0]
    assert dashed and np.array_equal(np.c_[dashed[0].get_xdata(), dashed[0].get_ydata()], first[:, :2])
    door = np.concatenate(sim.changed[0])
    rows, cols = np.divmod(door, building.grid_shape[1])
    (points,) = [c.get_offsets() for c in ax.collections if len(c.get_offsets()) == len(door)]
    assert np.array_equal(np.asarray(points), np.c_[rows, cols])
