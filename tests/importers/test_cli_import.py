"""``sgplan import`` end to end: import, inspect --draw, plan a mission in words on the result."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from sgplan.cli import main
from tests.shared_data import scene_example

from .test_mp3d import house_text
from .test_ros import write_map


def test_import_inspect_and_plan_in_words(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    house = tmp_path / "small.house"
    house.write_text(house_text())
    scene = tmp_path / "scene"
    assert main(["import", "mp3d", str(house), "--out", str(scene), "--resolution", "0.1"]) == 0
    assert "2 rooms" in capsys.readouterr().out and (scene / "scene.json").is_file()
    assert main(["inspect", str(scene), "--draw", str(tmp_path / "draw")]) == 0
    assert "bedroom" in capsys.readouterr().out and (tmp_path / "draw" / "floor_0.png").is_file()
    out = tmp_path / "run.json"
    argv = [
        "plan",
        "--scene",
        str(scene),
        "--text",
        "go to the bed, then the kitchen",
        "--verify",
        "--json",
        str(out),
    ]
    assert main(argv) == 0  # no start given: the scene's first start cell
    record = json.loads(out.read_text())
    assert record["verified"] and record["status"] == "optimal"
    assert "verified" in capsys.readouterr().out


def test_the_source_itself_works_as_a_scene(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    house = tmp_path / "small.house"
    house.write_text(house_text())
    assert main(["inspect", str(house), "--no-objects"]) == 0
    assert "kitchen" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["import", "ros", "{map}", "--out", "{out}"], "needs a rooms file"),
        (["import", "mp3d", "{missing}", "--out", "{out}"], "does not exist"),
        (["import", "ros", "{map}", "--out", "{out}", "--rooms", "{missing}"], "rooms file"),
    ],
)
def test_import_errors_exit_2_with_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str], fragment: str
) -> None:
    path = write_map(tmp_path)
    (tmp_path / "rooms.yaml").unlink()
    names = {"map": str(path), "out": str(tmp_path / "out"), "missing": str(tmp_path / "nothing.house")}
    assert main([a.format(**names) for a in argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[0].startswith("sgplan: error:") and fragment in err[0] and "Traceback" not in "\n".join(err)




def test_real_house_plans_a_mission_in_words(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    real_house = scene_example("example_mp3d_scene.house")
    scene = tmp_path / "house"
    assert main(["import", "mp3d", str(real_house), "--out", str(scene)]) == 0
    out = tmp_path / "run.json"
    text = "go to the kitchen, then a bathroom; never enter the bedroom"
    assert main(["plan", "--scene", str(scene), "--text", text, "--verify", "--json", str(out)]) == 0
    record = json.loads(out.read_text())
    assert record["verified"] and record["status"] == "optimal" and 5.0 < record["cost_m"] < 10.0
