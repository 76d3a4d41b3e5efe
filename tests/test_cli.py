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
def test_user_errors_exit_2_with_one_line(argv: list[str], fragment: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) <= 2 and err[0].startswith("sgplan: error:") and fragment in err[0]
    assert "Traceback" not in "\n".join(err)


def test_bad_scene_folder_names_the_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "building.yaml").write_text("floors: {0: {id: 0}}\n")
    assert main(["inspect", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "building.yaml" in err and "Traceback" not in err
