"""Options every command shares: --version, --quiet / --verbose / --debug anywhere, the compile notice,
one spelling of lists, profiles and names; inspect --json and its start-cell flags."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import sgplan
from sgplan.cli import main
from sgplan.commands.bench import _scene_folders
from sgplan.commands.common import split_list
from sgplan.runtime import jit

FORMULA = ["--formula", 'F "enter(room_4)"', "--setup", "NO-LLM"]


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out.strip() == f"sgplan {sgplan.__version__}"


@pytest.mark.parametrize("where", ["before", "after"])
def test_quiet_verbose_and_debug_go_before_or_after_the_command(
    where: str, capsys: pytest.CaptureFixture[str]
) -> None:
    def run(*flags: str) -> str:
        argv = ["plan", "--scene", "demo", *FORMULA]
        assert main([*flags, *argv] if where == "before" else [*argv, *flags]) == 0
        return capsys.readouterr().err

    normal, quiet, verbose = run(), run("--quiet"), run("--verbose")
    assert "scene demo-house: start" in normal and "(w1, w2)" in normal
    assert quiet == "" and "guidance" not in normal
    def shape(text: str) -> set[str]:
        return {re.sub(r"[\d.]+ s\b", "T s", line) for line in text.splitlines()}  # timings vary between runs

    assert shape(normal) <= shape(verbose)
    with pytest.raises(sgplan.SgplanError):  # --debug re-raises instead of printing
        main(["plan", "--scene", "demo", "--formula", 'F "enter(room_999)"', "--debug"])


def test_the_compile_notice_is_said_when_kernels_are_cold(monkeypatch: pytest.MonkeyPatch,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    assert jit.kernels_cached() in (True, False, None)
    monkeypatch.setattr(jit, "_seen_cached", False)
    monkeypatch.setattr(jit, "kernels_cached", lambda: False)
    assert main(["plan", "--scene", "demo", *FORMULA]) == 0
    assert jit.NOTICE in capsys.readouterr().err
    monkeypatch.setattr(jit, "kernels_cached", lambda: True)
    assert main(["plan", "--scene", "demo", *FORMULA]) == 0
    assert jit.NOTICE not in capsys.readouterr().err


@pytest.mark.parametrize("command", ["demo", "plan"])
def test_the_compile_notice_is_the_first_thing_a_planning_command_says(command: str, tmp_path: Path) -> None:
    """Said before anything else runs: once one kernel is compiled (the scene checks run some), the cache
    index makes the others look cached and the notice would never come."""
    argv = ["demo", "--out", str(tmp_path)] if command == "demo" else ["plan", "--scene", "demo", *FORMULA]
    code = ("import sys; import sgplan.runtime.jit as jit; jit.kernels_cached = lambda: False; "
            f"from sgplan.cli import main; sys.exit(main({argv!r}, fast_exit=False))")
    done = subprocess.run([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=300, env={**os.environ, "PYTHONUNBUFFERED": "1"},
                          stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stdout
    said = done.stdout.splitlines()
    assert said[0] == jit.NOTICE and len(said) > 3 and jit.NOTICE not in said[1:]


def test_the_kernel_cache_is_read_until_it_is_found_cached(monkeypatch: pytest.MonkeyPatch) -> None:
    probes: list[bool | None] = [None, True, False]
    monkeypatch.setattr(jit, "_seen_cached", False)
    monkeypatch.setattr(jit, "kernels_cached", lambda: probes.pop(0))
    assert [jit.announce_compile() for _ in range(3)] == [False, False, False]
    assert probes == [False]  # "unknown" probes again, "cached" ends the probing for this process


def test_plan_takes_the_llm_options_and_names_in_any_case(capsys: pytest.CaptureFixture[str]) -> None:
    assert (
        main(
            [
                "plan", "--scene", "DEMO", "--formula", 'F "enter(room_4)"', "--setup", "no-llm", "--profile",
                "LTLF",
            ]
        )
        == 0
    )
    code = main(["plan", "--scene", "demo", "--text", "Go to the kitchen.", "--samples", "2", "--rpm", "5"])
    assert code == 2 and "--rpm, --samples only apply to a language model" in capsys.readouterr().err


def test_one_list_syntax_and_scene_names_in_any_case(tmp_path: Path) -> None:
    assert split_list(["a,b", "c", " d , "]) == ["a", "b", "c", "d"] and split_list(None) is None
    for name in ("Collierville", "Benevolence"):
        (tmp_path / name).mkdir()
    assert _scene_folders(tmp_path, ["collierville", "BENEVOLENCE", "nope"]) == [
        "Collierville", "Benevolence", "nope",
    ]


def test_inspect_json_and_flags_start_cells_inside_obstacles(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["inspect", "demo", "--json", "-"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["name"] == "demo-house" and summary["initial_cells_free"] == [True] * 5
    assert (
        main(["inspect", "demo", "--robot-radius", "1.0", "--no-objects", "--json", str(tmp_path / "s.json")])
        == 0
    )
    text = capsys.readouterr().out
    flags = json.loads((tmp_path / "s.json").read_text())["initial_cells_free"]
    assert False in flags and "NOT FREE" in text and "a plan cannot start there" in text
    assert "components of [" in text and "; " in text.split("components of [")[1].split("]")[0]
