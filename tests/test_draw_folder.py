"""Several processes drawing into one ``--draw`` folder: the first holds it for its whole command, the
others are refused at their start with the holder's pid (never silently overwriting each other); a
holder that ends, or dies, frees the folder. Real processes throughout (the lock is the kernel's)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from sgplan.files import claim_file

SGPLAN = (sys.executable, "-m", "sgplan.cli")
HOLD = (
    "import sys; from pathlib import Path; from sgplan.files import claim_folder\n"
    "with claim_folder(Path(sys.argv[1])):\n"
    "    print('held', flush=True)\n"
    "    sys.stdin.read()\n"
)
COMMANDS = {
    "inspect": ["inspect", "demo", "-q"],
    "plan": ["plan", "--scene", "demo", "--formula", 'F "enter(room_5)"', "--start-index", "0", "-q"],
}


def _holder(folder: Path) -> subprocess.Popen[str]:
    """A process that holds ``folder`` until its stdin closes."""
    holder = subprocess.Popen([sys.executable, "-c", HOLD, str(folder)], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True)
    assert holder.stdout is not None and holder.stdout.readline().strip() == "held"
    return holder


def _sgplan(argv: list[str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SGPLAN, *argv], capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_second_process_is_refused_with_the_holders_pid_then_drawn_once_freed(
    command: str, tmp_path: Path
) -> None:
    folder = tmp_path / "drawings"
    holder = _holder(folder)
    try:
        refused = _sgplan([*COMMANDS[command], "--draw", str(folder)])
        assert refused.returncode == 2
        last = refused.stderr.strip().splitlines()[-1]
        assert last == (f"sgplan: error: --draw {folder}: another sgplan process (pid {holder.pid}) is "
                        "drawing into this folder now; wait for it to finish or choose another --draw folder")
        assert list(folder.iterdir()) == []  # refused before any work
    finally:
        holder.communicate("", timeout=60)
    drawn = _sgplan([*COMMANDS[command], "--draw", str(folder)])
    assert drawn.returncode == 0, drawn.stderr
    prefix = "plan_" if command == "plan" else ""
    assert {p.name for p in folder.iterdir()} >= {f"{prefix}floor_0.png", f"{prefix}floor_1.png"}
    assert claim_file(folder).read_text().strip().isdigit()  # the last writer's pid, beside the folder


def test_a_holder_that_dies_frees_the_folder(tmp_path: Path) -> None:
    holder = _holder(tmp_path / "drawings")
    holder.kill()
    holder.wait(timeout=60)
    assert _sgplan([*COMMANDS["inspect"], "--draw", str(tmp_path / "drawings")]).returncode == 0


def test_concurrent_commands_each_draw_whole_or_are_refused(tmp_path: Path) -> None:
    folder = tmp_path / "drawings"
    runs = [subprocess.Popen([*SGPLAN, *COMMANDS["inspect"], "--draw", str(folder)], stderr=subprocess.PIPE,
                             text=True) for _ in range(4)]
    outcomes = [(run.wait(timeout=300), run.stderr.read() if run.stderr else "") for run in runs]
    assert {code for code, _ in outcomes} <= {0, 2} and any(code == 0 for code, _ in outcomes)
    assert all("is drawing into this folder now" in err for code, err in outcomes if code == 2)
    assert sorted(p.name for p in folder.iterdir()) == ["floor_0.png", "floor_0.svg", "floor_1.png",
                                                        "floor_1.svg"]


def test_a_draw_folder_that_is_a_file_is_refused_before_any_work(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    refused = _sgplan([*COMMANDS["plan"], "--draw", str(tmp_path / "file")])
    assert refused.returncode == 2
    assert refused.stderr.strip().splitlines()[-1] == (
        f"sgplan: error: --draw {tmp_path / 'file'}: cannot use this folder: it is a file")
