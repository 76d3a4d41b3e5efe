"""The CLI: sub-commands run end to end; user errors print one line and exit with code 2."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.cli import main


def test_inspect_demo_prints_summary_and_draws(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", "demo", "--draw", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "building demo-house" in out and "free cells" in out and "stairs floor 0" in out
    assert sorted(p.name for p in tmp_path.glob("*.png")) == ["floor_0.png", "floor_1.png"]


@pytest.mark.gibson
def test_inspect_gibson_scene_by_name(gibson_root: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", "Benevolence", "--data", str(gibson_root), "--no-objects"]) == 0
    out = capsys.readouterr().out
    assert "93,302 free cells" in out and "(69, 741) <-> floor 1 (74, 381)" in out


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["inspect", "/no/such/scene"], "neither an existing path"),
        (["inspect", "Benevolence", "--data", "/no/such/data"], "does not exist"),
    ],
)
def test_user_errors_exit_2_with_one_line(
    argv: list[str], fragment: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) <= 2 and err[0].startswith("sgplan: error:") and fragment in err[0]
    assert "Traceback" not in "\n".join(err)


def test_bad_scene_folder_names_the_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "building.yaml").write_text("floors: {0: {id: 0}}\n")
    assert main(["inspect", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "building.yaml" in err and "Traceback" not in err


def test_demo_runs_end_to_end_offline(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import json

    assert main(["demo", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "offline-pattern" in out and "offline-symbolic" in out and "not LLMs" in out
    record = json.loads((tmp_path / "run.json").read_text())
    assert record["verified"] and record["status"] == "optimal"
    assert {row[2] for row in record["path"]} == {0, 1}  # the mission needs both floors
    assert "G(" in record["mission"]["formula"]  # the "always avoid" part
    assert (tmp_path / "plan_floor_1.png").is_file() and (tmp_path / "mission" / "automaton.aut").is_file()
    written = {p.name for p in tmp_path.iterdir()}
    assert {"plan_floor_0.svg", "automaton.svg", "report.html", "waypoints.csv", "ros_path.yaml"} <= written
    assert record["backends"]["guidance"] == "offline-symbolic (not an LLM)" and record["events"]


DEMO_FORMULA = 'F("enter(room_5)" & F "reach(object_28)") & G !"enter(room_6)"'


def test_plan_formula_on_demo_writes_verified_json(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import json

    out = tmp_path / "r.json"
    assert main(["plan", "--scene", "demo", "--formula", DEMO_FORMULA, "--setup", "NO-LLM", "--verify",
                 "--json", str(out), "--draw", str(tmp_path)]) == 0
    record = json.loads(out.read_text())
    assert record["status"] == "optimal" and record["verified"] and record["cost_m"] > 0
    assert record["iterations"][-1]["w1"] == 1 and len(record["iterations"][-1]["expansions"]) == 1
    assert set(record["timings"]) >= {"prepare_s", "precompute_s", "search_s", "wall_s"}
    assert len(record["path"][0]) == 4 and (tmp_path / "plan_floor_0.png").is_file()


def test_plan_reports_invalid_start_and_infeasible(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import json

    out = tmp_path / "r.json"
    assert (
        main(["plan", "--scene", "demo", "--formula", DEMO_FORMULA, "--start", "0,0,0", "--json", str(out)])
        == 2
    )
    assert json.loads(out.read_text())["status"] == "invalid-start"
    assert "start" in capsys.readouterr().err
    # the bathroom is reachable only through the corridor, which the mission forbids
    blocked = 'F "enter(room_5)" & G !"enter(room_2)"'
    assert (
        main(["plan", "--scene", "demo", "--formula", blocked, "--start-index", "1", "--json", str(out)]) == 2
    )
    assert json.loads(out.read_text())["status"] == "infeasible"


@pytest.mark.gibson
def test_plan_gibson_mission_folder_authors_profile(
    gibson_root: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    folder = gibson_root / "Benevolence" / "missions" / "1"
    assert main(["plan", "--scene", str(gibson_root / "Benevolence"), "--mission-dir", str(folder),
                 "--start-index", "0", "--profile", "authors", "--verify"]) == 0
    assert "cost 18.8181 m" in capsys.readouterr().out  # reference-algorithm.md §11, stay column


@pytest.mark.gibson
def test_a_gibson_mission_folder_not_found_here_points_to_the_data_found(
    gibson_root: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The README's ``../shared/...`` path from a clone that is not beside the data."""
    monkeypatch.setenv("SGPLAN_GIBSON_DIR", str(gibson_root))
    monkeypatch.chdir(tmp_path)
    given = "../shared/datasets/gibson-3dsg/Benevolence/missions/1"
    assert main(["plan", "--scene", "Benevolence", "--mission-dir", given]) == 2
    expected = gibson_root / "Benevolence" / "missions" / "1"
    assert capsys.readouterr().err.strip() == (f"sgplan: error: {given}: mission folder does not exist; the "
                                               f"Gibson data sgplan finds holds it at {expected}")


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (
            ["plan", "--scene", "demo", "--formula", 'F "enter(room_5)"', "--time-limit", "nan"],
            "number of seconds > 0 and <= 1e+06",
        ),
        (
            ["plan", "--scene", "demo", "--formula", 'F "enter(room_5)"', "--max-expansions", "0"],
            "whole number >= 1",
        ),
        (["bench", "--jobs", "-2"], "whole number >= 1"),
        (["bench", "--case-timeout", "inf"], "number of seconds > 0"),
        (["bench", "--case-timeout", "3e6"], "number of seconds > 0 and <= 1e+06"),
        (["bench", "--time-limit", "-1"], "number of seconds > 0"),
        (["demo", "--start-index", "x"], "whole number >= 0"),
        (["inspect", "demo", "--robot-radius", "-0.1"], "radius in metres >= 0 and <= 2"),
        (
            ["plan", "--scene", "demo", "--formula", "x", "--robot-radius", "100"],
            "radius in metres >= 0 and <= 2",
        ),
        (
            ["plan", "--scene", "demo", "--formula", "x", "--reach-radius", "1e308"],
            "radius in metres > 0 and <= 100",
        ),
        (
            ["plan", "--scene", "demo", "--formula", "x", "--reach-radius", "0"],
            "radius in metres > 0 and <= 100",
        ),
        (["guide", "--max-concurrency", "0"], "whole number >= 1"),
        (["guide", "--rpm", "nan"], "finite number > 0"),
    ],
)
def test_bad_numbers_are_refused_by_the_parser(
    argv: list[str], fragment: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    assert fragment in capsys.readouterr().err


@pytest.mark.gibson
def test_plan_text_reads_downstairs_from_the_start_floor(
    gibson_root: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Benevolence has three floors: "downstairs" means something only relative to where the robot starts.
    argv = ["plan", "--scene", "Benevolence", "--data", str(gibson_root), "--text",
            "Go to the bathroom downstairs.", "--setup", "A*"]
    assert main([*argv, "--start-index", "3"]) == 0  # floor 2: the one bathroom below is room_2, floor 0
    assert 'F "enter(room_2)"' in capsys.readouterr().err
    assert main([*argv, "--start-index", "0"]) == 2  # floor 0: nothing is downstairs
    assert "the robot starts on floor 0" in capsys.readouterr().err


def test_start_floor_is_read_without_a_grid() -> None:
    from sgplan.scene.demo import demo_building
    from sgplan.starts import Point, start_floor

    demo = demo_building()
    assert start_floor(demo, None) == demo.initial_cells[0][2]
    assert start_floor(demo, (3, 4, 1)) == 1 and start_floor(demo, Point(1.0, 2.0, 0)) == 0
    assert start_floor(demo, "kitchen") == 0 and start_floor(demo, "bedroom with the teddy bear") is None
    assert start_floor(demo, (3, 4, 7)) is None and start_floor(demo, 99) is None


def test_plan_explains_the_mission_once(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """The explanation said back before planning is the one the result carries: made once per plan."""
    import json

    import sgplan.explain

    calls: list[str] = []
    real = sgplan.explain.explain_mission

    def counted(*args: object, **kwargs: object) -> sgplan.explain.Explanation:
        calls.append("explain")
        return real(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(sgplan.explain, "explain_mission", counted)
    out = tmp_path / "r.json"
    argv = ["plan", "--scene", "demo", "--formula", DEMO_FORMULA, "--setup", "A*", "--json", str(out)]
    assert main(argv) == 0
    record = json.loads(out.read_text())
    assert calls == ["explain"]
    assert record["explanation"]["text"] in capsys.readouterr().out


def test_help_describes_demo_and_lists_every_scene_kind(capsys: pytest.CaptureFixture[str]) -> None:
    for argv in (["demo", "--help"], ["plan", "--help"]):
        with pytest.raises(SystemExit) as stop:
            main(argv)
        assert stop.value.code == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "Run the whole pipeline on the embedded demo building, offline" in out  # demo had none
    assert all(kind in out for kind in (".house", "map.yaml", "Hydra .json", "building.yaml"))


def test_counts_are_said_in_the_right_number(capsys: pytest.CaptureFixture[str]) -> None:
    """An imported scene with one room said "1 rooms"."""
    import sgplan
    from sgplan.scene.summary import summarize, summary_lines

    b = sgplan.BuildingBuilder("one room", size_m=(3.0, 3.0), resolution_m=0.1, robot_radius_m=0.1)
    b.add_floor()
    room = b.add_room(0, "office", box=(0, 0, 3, 3))
    b.add_object(room, "desk", box=(0.3, 0.3, 1.0, 1.0))
    b.add_start(2.0, 2.0, 0)
    text = "\n".join(summary_lines(summarize(b.build())))
    assert "1 floor, 1 room, 1 object" in text and "floor 0 (A): 1 room, 1 object" in text
    assert "1 rooms" not in text and "floor(s)" not in text
    assert main(["plan", "--scene", "demo", "--formula", 'F "enter(room_4)"', "--start-room", "kitchen"]) == 0
    out = capsys.readouterr().out
    assert "over 1 cell, 1 simplified waypoint (setup ALL, 1 iteration)" in out  # satisfied at the start
