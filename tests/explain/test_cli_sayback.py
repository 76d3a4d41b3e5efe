"""The commands say back what they will plan: explanation printed once and recorded, --confirm,
scene checks with their own exit code, mission folders refused on another scene."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from sgplan.cli import main
from sgplan.commands.sayback import check_before_planning, say_back
from sgplan.errors import ConfirmationError
from sgplan.mission import compile_mission, save_mission_folder
from sgplan.scene.demo import demo_building

GOAL = 'F("enter(room_5)" & F "enter(room_11)") & G !"enter(room_6)"'
EXPLAINED = "Go to the bathroom (room_5, floor 0), then go to the bedroom (room_11, floor 1)."


def test_plan_prints_and_records_the_explanation_once(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "r.json"
    assert main(["plan", "--scene", "demo", "--formula", GOAL, "--setup", "NO-LLM", "--json", str(out)]) == 0
    printed = capsys.readouterr().out
    assert printed.count(EXPLAINED) == 1 and "Never enter the living room (room_6, floor 0)." in printed
    assert printed.index(EXPLAINED) < printed.index("optimal: cost")
    record = json.loads(out.read_text())
    assert EXPLAINED in record["explanation"]["text"] and record["explanation"]["method"] == "patterns"
    assert record["scene_check"] == []


def test_plan_finds_where_each_proposition_holds_once_for_the_explanation_and_the_plan(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import numpy as np

    import sgplan.explain.scene_labels
    import sgplan.scene.labels as labels
    from sgplan.scene.model import Building

    built: list[str] = []
    real = labels.proposition_cells

    def counted(building: Building, prop: labels.Proposition, reach_radius_m: float | None = None,
                reach_model: str = "visible") -> np.ndarray:
        built.append(prop.name)
        return real(building, prop, reach_radius_m, reach_model)

    for module in (labels, sgplan.explain.scene_labels):  # wherever it is called from
        monkeypatch.setattr(module, "proposition_cells", counted)
    out = tmp_path / "r.json"
    assert main(["plan", "--scene", "demo", "--formula", GOAL, "--setup", "NO-LLM", "--json", str(out)]) == 0
    assert sorted(built) == ["enter(room_11)", "enter(room_5)", "enter(room_6)"]  # each once, not twice
    record = json.loads(out.read_text())
    assert EXPLAINED in record["explanation"]["text"] and record["status"] == "optimal"
    capsys.readouterr()


def test_contradiction_exits_3_with_its_own_status(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "r.json"
    argv = [
        "plan", "--scene", "demo", "--formula", 'F "enter(room_4)" & G !"enter(room_4)"', "--json", str(out),
    ]
    assert main(argv) == 4
    err = capsys.readouterr().err
    assert "from any start" in err and "Go to the kitchen (room_4, floor 0). Never enter the kitchen" in err
    assert "start elsewhere" not in err
    assert json.loads(out.read_text())["status"] == "unsatisfiable"


def test_confirm_without_a_terminal_errors_instead_of_blocking(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "--scene", "demo", "--formula", GOAL, "--confirm"]) == 2
    captured = capsys.readouterr()
    assert EXPLAINED in captured.out and "no terminal to ask on" in captured.err


def test_confirm_asks_and_stops_unless_yes() -> None:
    mission, building = compile_mission(GOAL), demo_building()
    asked: list[str] = []
    say_back(mission, building, confirm=True, ask=lambda q: asked.append(q) or "yes")
    assert asked == ["Plan this mission? [y/N] "]
    for answer in ("", "n", "nope"):
        with pytest.raises(ConfirmationError, match="not confirmed"):
            say_back(mission, building, confirm=True, ask=lambda q, a=answer: a)


def test_translate_prints_the_explanation_and_writes_scene_record(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "m"
    text = "Visit the bathroom on floor 0, then the dining room. Always avoid the kitchen."
    assert main(["translate", "--scene", "demo", "--text", text, "--out", str(out)]) == 0
    assert "Go to the bathroom (room_5, floor 0), then go to the dining room (room_7, floor 0)." in (
        capsys.readouterr().out)
    events = json.loads((out / "llm_record.json").read_text())["events"]
    assert [e["method"] for e in events if e["kind"] == "explained"] == ["patterns"]
    scene = yaml.safe_load((out / "scene.yaml").read_text())
    assert scene["scene"] == "demo-house" and scene["entities"]["room_4"] == {
        "category": "kitchen",
        "floor": 0,
    }


def _folder_for_another_scene(tmp_path: Path) -> Path:
    folder = save_mission_folder(compile_mission(GOAL), tmp_path / "m", building=demo_building())
    record = yaml.safe_load((folder / "scene.yaml").read_text())
    record.update(scene="elsewhere", graph_sha256="0" * 64)
    record["entities"]["room_5"] = {"category": "kitchen", "floor": 1}
    (folder / "scene.yaml").write_text(yaml.safe_dump(record))
    return folder


def test_mission_folder_of_another_scene_is_refused_unless_forced(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    folder = _folder_for_another_scene(tmp_path)
    argv = ["plan", "--scene", "demo", "--mission-dir", str(folder), "--setup", "NO-LLM"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "made for scene 'elsewhere', not 'demo-house'" in err
    assert "room_5 was a kitchen on floor 1, but in 'demo-house' it is a bathroom on floor 0" in err
    assert "--force" in err
    assert main([*argv, "--force"]) == 0
    assert "planning anyway (--force)" in capsys.readouterr().err


def test_own_mission_folder_plans(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = save_mission_folder(compile_mission(GOAL), tmp_path / "m", building=demo_building())
    assert main(["plan", "--scene", "demo", "--mission-dir", str(folder), "--setup", "NO-LLM"]) == 0
    assert EXPLAINED in capsys.readouterr().out


def test_translate_warns_when_the_mission_cannot_be_planned(capsys: pytest.CaptureFixture[str]) -> None:
    # What `translate` runs after writing the folder: the scene checks without a start, never raising.
    mission = compile_mission('F "enter(room_4)" & G !"enter(room_4)"')
    check = check_before_planning(mission, demo_building(), stop=False)
    assert [f.kind for f in check.findings] == ["unsatisfiable"]
    assert "warning: it cannot be planned: no path in scene 'demo-house'" in capsys.readouterr().err
