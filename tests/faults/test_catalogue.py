"""Hand-picked faults: every example of issue 14, and the file-system oddities where a file is expected
(a directory, a symlink loop, a FIFO, an unreadable file, an empty path)."""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from tests.faults.harness import RECORD, can_drop_file_permission_override, check
from tests.faults.inputs import fresh_copy
from tests.faults.strategies import ANCHOR_BOMB, DEEP

PLAN = ["--time-limit", "5", "--setup", "NO-LLM"]


def _inspect(scene: Path) -> list[str]:
    return ["inspect", str(scene)]


def _plan_mission(folder: Path) -> list[str]:
    return ["plan", "--scene", "demo", "--mission-dir", str(folder), *PLAN]


def _bomb_in(field_line: str) -> str:
    return "bombs:\n  a: " + ANCHOR_BOMB.replace("\n", "\n  ").rstrip() + "\n" + field_line + "\n"


# -- scene files: each must be refused ---------------------------------------------------------------------

SCENE_FAULTS: dict[str, tuple[str, Callable[[Path], None]]] = {
    "robot radius 1000 m": (
        "radius_config.bash",
        lambda s: (s / "radius_config.bash").write_text("ROBOT_RADIUS=1000\n"),
    ),
    "reach 1e308 m": (
        "radius_config.bash",
        lambda s: (s / "radius_config.bash").write_text("OBJECT_REACH_RADIUS=1e308\n"),
    ),
    "radius file is a directory": ("radius_config.bash", lambda s: _replace_by_dir(s / "radius_config.bash")),
    "initial positions is a directory": (
        "initial_positions.yaml",
        lambda s: _replace_by_dir(s / "initial_positions.yaml"),
    ),
    "building.yaml is a directory": ("building.yaml", lambda s: _replace_by_dir(s / "building.yaml")),
    "building.yaml symlink loop": ("building.yaml", lambda s: _symlink_loop(s / "building.yaml")),
    "radius file symlink loop": ("radius_config.bash", lambda s: _symlink_loop(s / "radius_config.bash")),
    "map symlink loop": ("0.png", lambda s: _symlink_loop(s / "cat_maps" / "0.png")),
    "radius file is a FIFO": ("radius_config.bash", lambda s: _fifo(s / "radius_config.bash")),
    "anchor bomb in grid size": (
        "building.yaml",
        lambda s: _yaml_field(s / "building.yaml", "grid_map_size"),
    ),
    "anchor bomb in a start": (
        "initial_positions.yaml",
        lambda s: (s / "initial_positions.yaml").write_text(_bomb_in("- *i")),
    ),
    "deep YAML nesting": (
        "building.yaml",
        lambda s: (s / "building.yaml").write_text("[" * DEEP + "]" * DEEP),
    ),
    "deep block nesting": ("building.yaml", lambda s: (s / "building.yaml").write_text("- " * 20000 + "x\n")),
    "duplicate key": (
        "building.yaml",
        lambda s: (s / "building.yaml").write_text((s / "building.yaml").read_text() + "num_floors: 2\n"),
    ),
    "UTF-16 building.yaml": (
        "building.yaml",
        lambda s: (s / "building.yaml").write_bytes((s / "building.yaml").read_text().encode("utf-16")),
    ),
    "map 20000 x 20000": ("0.png", lambda s: _huge_png(s)),
    "map not a PNG": ("0.png", lambda s: (s / "cat_maps" / "0.png").write_bytes(b"GIF89a" + bytes(100))),
}


def _replace_by_dir(path: Path) -> None:
    path.unlink(missing_ok=True)
    path.mkdir()
    (path / "inside").write_text("x")


def _symlink_loop(path: Path) -> None:
    path.unlink(missing_ok=True)
    loop = path.with_name(path.name + ".loop")
    os.symlink(loop, path)
    os.symlink(path, loop)


def _fifo(path: Path) -> None:
    path.unlink(missing_ok=True)
    os.mkfifo(path)


def _yaml_field(path: Path, key: str) -> None:
    lines = path.read_text().splitlines()
    index = next(i for i, line in enumerate(lines) if line.strip().startswith(f"{key}:"))
    indent = lines[index][: len(lines[index]) - len(lines[index].lstrip())]
    lines[index] = f"{indent}{key}: *i"
    # The anchors go first (a YAML alias must follow its anchor).
    path.write_text(_bomb_in("\n".join(lines)))


def _huge_png(scene: Path) -> None:
    """A valid 20000 x 20000 grayscale PNG (a few hundred kB compressed), and a grid that matches it."""
    image = Image.fromarray(np.zeros((20000, 20000), np.uint8))
    image.save(scene / "cat_maps" / "0.png", optimize=False, compress_level=1)
    text = (scene / "building.yaml").read_text().replace("- 12\n  - 16", "- 20000\n  - 20000")
    (scene / "building.yaml").write_text(text)


@pytest.mark.parametrize("fault", list(SCENE_FAULTS))
def test_scene_fault(templates: dict[str, Path], fault: str) -> None:
    name, damage = SCENE_FAULTS[fault]
    with fresh_copy(templates["authors"]) as scene:
        damage(scene)
        run = check(f"scene/{fault}", _inspect(scene), must_fail=True,
                    subprocess_only=fault.startswith(("anchor", "deep", "map 20000")))
        assert RECORD or name in run.stderr.strip().splitlines()[-1]


def test_unreadable_files(templates: dict[str, Path]) -> None:
    """Files and folders without read permission, read by a process that obeys permissions (tests may run
    as root, who reads everything: the CLI runs with the permission override capabilities dropped)."""
    if os.geteuid() == 0 and not can_drop_file_permission_override():
        pytest.skip("running as root without the right to drop CAP_DAC_OVERRIDE: every file is readable")
    root = Path(tempfile.mkdtemp(prefix="sgplan-fault-", dir="/tmp"))
    try:
        os.chmod(root, 0o755)
        cases = {
            "unreadable radius file": ("radius_config.bash", 0o000),
            "unreadable building.yaml": ("building.yaml", 0o000),
            "unreadable scene folder": (".", 0o000),
            "unreadable maps folder": ("cat_maps", 0o000),
        }
        for fault, (name, mode) in cases.items():
            scene = root / fault.replace(" ", "-")
            shutil.copytree(templates["authors"], scene)
            for path in [scene, *scene.rglob("*")]:
                os.chmod(path, 0o755 if path.is_dir() else 0o644)
            os.chmod(scene / name, mode)
            check(f"scene/{fault}", _inspect(scene), must_fail=True, unprivileged=os.geteuid() == 0)
    finally:
        for path in [root, *root.rglob("*")]:
            os.chmod(path, 0o755)
        shutil.rmtree(root)


# -- missions -------------------------------------------------------------------------------------------

MISSION_FAULTS: dict[str, Callable[[Path], None]] = {
    "40 APs": lambda m: _edit(
        m / "automaton.aut", r"^AP: \d+", "AP: 40" + "".join(f' "q{k}"' for k in range(40))
    ),
    "5,000,000 states": lambda m: _edit(m / "automaton.aut", r"^States: \d+", "States: 5000000"),
    "ap_desc reach 1e5 m": lambda m: _edit(
        m / "ap_desc.yaml", r"reach_distance: .*", "reach_distance: 100000.0"
    ),
    "ap_desc reach 1e308 m": lambda m: _edit(
        m / "ap_desc.yaml", r"reach_distance: .*", "reach_distance: 1.0e+308"
    ),
    "ap_desc duplicate keys": lambda m: (m / "ap_desc.yaml").write_text(
        (m / "ap_desc.yaml").read_text() + (m / "ap_desc.yaml").read_text()
    ),
    "ap_desc uuid is a list": lambda m: _edit(m / "ap_desc.yaml", r"uuid: \d+", "uuid: [1, 2]"),
    "ap_desc type is a list": lambda m: _edit(
        m / "ap_desc.yaml", r"type: kReachObject", "type: [kReachObject]"
    ),
    "guidance calls are a bomb": lambda m: (m / "llm_heuristic.yaml").write_text(_bomb_in("1: {0: *i}")),
    "guidance calls not strings": lambda m: (m / "llm_heuristic.yaml").write_text("1: {0: [[1, 2], 3]}\n"),
    "automaton is a directory": lambda m: _replace_by_dir(m / "automaton.aut"),
    "ap_desc is a symlink loop": lambda m: _symlink_loop(m / "ap_desc.yaml"),
    "guidance is a directory": lambda m: _replace_by_dir(m / "llm_heuristic.yaml"),
    "deep HOA label": lambda m: _edit(m / "automaton.aut", r"\[[^\]]*\]", "[" + "!" * 5000 + "0]", count=1),
    "ap_dict deep literal": lambda m: (m / "ap_dict.txt").write_text("{" * 5000 + "}" * 5000),
}


def _edit(path: Path, pattern: str, replacement: str, count: int = 0) -> None:
    import re

    text = path.read_text()
    new = re.sub(pattern, lambda _: replacement, text, count=count, flags=re.MULTILINE)
    assert new != text, f"{pattern} not in {path}"
    path.write_text(new)


@pytest.mark.parametrize("fault", list(MISSION_FAULTS))
def test_mission_fault(templates: dict[str, Path], fault: str) -> None:
    with fresh_copy(templates["mission"]) as mission:
        MISSION_FAULTS[fault](mission)
        check(f"mission/{fault}", _plan_mission(mission), must_fail=True,
              subprocess_only=fault in ("5,000,000 states", "guidance calls are a bomb"))


# -- command lines --------------------------------------------------------------------------------------

FLAT_500 = repr(["AND"] * 499 + ["enter(room_5)", "enter(room_7)"] * 250)
NOT_CHAIN = repr(["NOT"] * 4001 + ["enter(room_5)"])


@pytest.mark.parametrize(
    ("fault", "argv", "must_fail"),
    [
        ("empty --formula", ["plan", "--scene", "demo", "--formula", "", *PLAN], True),
        ("empty --mission-dir", ["plan", "--scene", "demo", "--mission-dir", "", *PLAN], True),
        ("empty --text", ["translate", "--scene", "demo", "--text", " ", "--out", "{tmp}/m"], True),
        ("flat conjunction of 500 terms", ["plan", "--scene", "demo", "--formula", FLAT_500, *PLAN], True),
        ("chain of 4001 NOTs", ["plan", "--scene", "demo", "--formula", NOT_CHAIN, *PLAN], False),
        (
            "bench start range 0-99999999999",
            ["bench", "--out", "{tmp}/b", "--data", "{tmp}", "--starts", "0-99999999999"], True,
        ),
        ("demo --out is a file", ["demo", "--out", "{tmp}/file"], True),
    ],
)
def test_command_line(tmp_path: Path, fault: str, argv: list[str], must_fail: bool) -> None:
    (tmp_path / "file").write_text("not a folder\n")
    check(f"cli/{fault}", [a.replace("{tmp}", str(tmp_path)) for a in argv], must_fail=must_fail)


@pytest.mark.parametrize("name", [".lock", "results.jsonl", "sweeps.jsonl"])
def test_bench_folder_entries_that_are_directories(tmp_path: Path, name: str) -> None:
    out = tmp_path / "out"
    (out / name).mkdir(parents=True)
    check(f"bench/{name} is a directory", ["bench", "--out", str(out), "--data", str(tmp_path / "none")],
          must_fail=True)
