"""The layer contract of pyproject.toml (``[tool.importlinter]``) holds for sgplan, and breaks the build
when a lower layer imports a higher one: the same check ``.ci/run`` makes with ``lint-imports``."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytest.importorskip("importlinter", reason="import-linter (the test extra) checks the layers")


def _lint_imports(source_root: Path, config: Path) -> subprocess.CompletedProcess[str]:
    """``lint-imports`` on the sgplan package found first on ``source_root``."""
    lint_imports = Path(sys.executable).with_name("lint-imports")  # the test extra's console script
    return subprocess.run(
        [str(lint_imports), "--no-cache", str(config)], capture_output=True, text=True, timeout=300,
        env={**os.environ, "PYTHONPATH": str(source_root)}, cwd=source_root,
    )


def _lint_imports_with(module: str, addition: str, tmp_path: Path) -> subprocess.CompletedProcess[str]:
    """``lint-imports`` on a copy of sgplan in ``tmp_path`` whose ``module`` ends with ``addition``."""
    shutil.copytree(ROOT / "src" / "sgplan", tmp_path / "sgplan",
                    ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    target = tmp_path / "sgplan" / module
    target.write_text(target.read_text() + "\n\n" + addition)
    config = tmp_path / "layers.toml"
    config.write_text((ROOT / "pyproject.toml").read_text())
    return _lint_imports(tmp_path, config)


def test_the_layers_and_the_acyclic_contract_hold() -> None:
    done = _lint_imports(ROOT / "src", ROOT / "pyproject.toml")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Contracts: 2 kept, 0 broken." in done.stdout


@pytest.mark.parametrize(
    ("module", "upward", "said"),
    [
        # scene/ reading a format of importers/ (the import this round removed), even lazily
        ("scene/model.py", "def _later():\n    from sgplan.importers import detect\n",
         "sgplan.scene is not allowed to import sgplan.importers"),
        # the bench worker borrowing the CLI's helpers (the 10-file circle this round removed)
        ("bench/worker.py", "from sgplan.cli import main as _main\n",
         "sgplan.bench is not allowed to import sgplan.cli"),
    ],
)
def test_an_upward_import_breaks_the_contract(module: str, upward: str, said: str, tmp_path: Path) -> None:
    done = _lint_imports_with(module, upward, tmp_path)
    assert done.returncode == 1, done.stdout + done.stderr
    assert said in done.stdout and "BROKEN" in done.stdout


@pytest.mark.parametrize(
    ("module", "back", "said"),
    [
        # the session's parts naming the domain that uses them (the type-only cycle this round cut)
        ("planning/shared.py", "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
         "    from sgplan.planning.domain import ActionParts\n", "No cycles are allowed in sgplan.planning"),
        # a run's helper importing the run that calls it, even inside a function
        ("execution/impossible.py", "def _later():\n    from sgplan.execution.run import Run\n",
         "No cycles are allowed in sgplan.execution"),
        # the translator's noun-phrase slot importing the rules registered in it (the cycle cut last)
        ("llm/offline/syntax/noun_slot.py",
         "def _later():\n    from sgplan.llm.offline.syntax import phrases\n",
         "No cycles are allowed in sgplan.llm.offline.syntax"),
        # the discourse state naming the meaning's composition (Task and Step moved down to tasks.py)
        ("llm/offline/grounding/discourse.py", "from sgplan.llm.offline.meaning.compose import conj\n",
         "No cycles are allowed in sgplan.llm.offline"),
    ],
)
def test_an_import_cycle_in_a_package_breaks_the_contract(module: str, back: str, said: str,
                                                          tmp_path: Path) -> None:
    done = _lint_imports_with(module, back, tmp_path)
    assert done.returncode == 1, done.stdout + done.stderr
    assert said in done.stdout, done.stdout
