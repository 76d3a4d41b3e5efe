"""``sgplan monitor`` end to end: a plan's waypoints judged done, a prefix in progress, another mission
violated, bad files and poses as one-line errors, recorded columns that differ as warnings."""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

import pytest

from sgplan.cli import main
from sgplan.commands.monitor import IN_PROGRESS_EXIT, VIOLATED_EXIT

FORMULA = 'F("enter(room_5)" & F "enter(room_11)") & G !"enter(room_6)"'
NO_STAIRS = 'F "enter(room_11)" & G !"enter(room_8)"'


@lru_cache(maxsize=2)
def _waypoints(folder: str, dense: bool) -> Path:
    target = Path(folder) / ("dense.csv" if dense else "simplified.csv")
    argv = ["plan", "--scene", "demo", "--formula", FORMULA, "--setup", "A*", "--waypoints", str(target),
            "-q"]
    assert main([*argv, "--dense"] if dense else argv) == 0
    return target


@pytest.fixture(scope="module")
def plan_files(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    folder = str(tmp_path_factory.mktemp("plan"))
    return _waypoints(folder, dense=False), _waypoints(folder, dense=True)


def monitor(capsys: pytest.CaptureFixture[str], trajectory: Path, *extra: str, formula: str = FORMULA
            ) -> tuple[int, str, str]:
    code = main(["monitor", "--scene", "demo", "--formula", formula, "--trajectory", str(trajectory), *extra])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_a_plans_waypoints_are_done(plan_files, capsys):
    for trajectory in plan_files:
        code, out, err = monitor(capsys, trajectory)  # their own segments: no distance is a gap
        assert code == 0, err
        assert "The mission, as it will be planned:" in out  # said back first
        assert ("verdict: done: the mission is satisfied; if the robot goes on: never enter the living room "
                "(room_6, floor 0)") in out
        assert "warning" not in err


def test_a_prefix_is_in_progress_and_says_what_is_left(plan_files, capsys, tmp_path):
    part = tmp_path / "part.csv"
    part.write_text("".join(plan_files[1].read_text().splitlines(keepends=True)[:20]))
    code, out, _ = monitor(capsys, part)
    assert code == IN_PROGRESS_EXIT == 5
    assert ("verdict: in progress: left: go to the bathroom (room_5, floor 0), then go to the bedroom "
            "(room_11, floor 1); never enter the living room (room_6, floor 0)") in out
    assert "trajectory " in out and "19 poses" in out


def test_another_mission_is_violated_by_the_step_named(plan_files, capsys):
    code, out, err = monitor(capsys, plan_files[1], formula=NO_STAIRS)
    assert code == VIOLATED_EXIT == 6
    verdict = next(line for line in out.splitlines() if line.startswith("verdict:"))
    assert verdict.startswith("verdict: violated at pose ") and "(line " in verdict
    assert verdict.endswith("entered the staircase (room_8, floor 0), which the mission forbids: never enter "
                            "the staircase (room_8, floor 0)")
    assert "q is 1, but the monitor computes 0" in err  # the file's states are another mission's


def test_the_json_record(plan_files, capsys, tmp_path):
    code, out, _ = monitor(capsys, plan_files[0], "--json", "-")
    record = json.loads(out)
    assert code == 0 and record["verdict"] == "done" and record["accepting"]
    assert record["scene"] == "demo-house" and record["profile"] == "ltlf"
    assert len(record["states"]) == record["poses"] and record["recorded_mismatches"] == []
    assert record["explanation"]["text"].startswith("The mission, as it will be planned:")
    assert record["issues"] == []  # sgplan's own waypoints: their segments are the path's
    plain = tmp_path / "plain.csv"  # the same poses with no sgplan header: far apart, so gaps
    plain.write_text("".join(",".join(row.split(",")[1:3] + [row.split(",")[4]]) + "\n"
                             for row in plan_files[0].read_text().splitlines()[1:]))
    record = json.loads(monitor(capsys, plain, "--json", "-")[1])
    assert {issue["kind"] for issue in record["issues"]} == {"gap"} and record["verdict"] == "done"
    target = tmp_path / "m.json"
    assert monitor(capsys, plan_files[0], "--json", str(target))[0] == 0
    assert json.loads(target.read_text())["verdict"] == "done"


def test_a_mission_folder_and_the_authors_profile(plan_files, capsys, tmp_path):
    import sgplan
    from sgplan.mission import save_mission_folder

    building = sgplan.load_scene("demo")
    mission = sgplan.mission_from_formula(FORMULA, building)
    folder = save_mission_folder(mission, tmp_path / "m", building=building)
    for profile in ("ltlf", "authors"):
        code = main(["monitor", "--scene", "demo", "--mission-dir", str(folder), "--trajectory",
                     str(plan_files[1]), "--profile", profile])
        assert code == 0, capsys.readouterr().err


@pytest.mark.parametrize(("text", "fragment"), [
    ("x_m,y_m,floor\n0,0,0\n1000,0,0\n", "bad.csv: pose 1 (line 3): (x 1000 m, y 0 m, floor 0) lies off"),
    ("x_m,y_m,floor\n0,0,7\n", "bad.csv: pose 0 (line 2): (x 0 m, y 0 m, floor 7) is on no floor"),
    ("x_m,y_m\n0,0\n", "bad.csv: line 1: the header has no floor column"),
])
def test_bad_trajectories_exit_2_with_one_line(capsys, tmp_path, text, fragment):
    bad = tmp_path / "bad.csv"
    bad.write_text(text)
    code, _, err = monitor(capsys, bad)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("sgplan: error: ")
    assert fragment in lines[0] and "Traceback" not in err


def test_a_mission_in_words(plan_files, capsys):
    code = main(["monitor", "--scene", "demo", "--text", "Go to the home office.", "--trajectory",
                 str(plan_files[1])])
    out = capsys.readouterr().out
    assert code == IN_PROGRESS_EXIT
    assert "verdict: in progress: left: go to the home office (room_12, floor 1)" in out
