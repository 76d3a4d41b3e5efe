"""What a CLI process pays before and after its work: a command does not import what it does not use,
and the console script ends without the interpreter's teardown once its outputs are complete."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from sgplan.runtime.process import GC_YOUNG_THRESHOLD

HEAVY = ("numba", "scipy", "PIL", "matplotlib", "rich", "openai", "sgplan.planning.amra")


def _modules_after(code: str) -> set[str]:
    """The modules a fresh interpreter holds after running ``code`` (an import in a clean process)."""
    out = subprocess.run(
        [sys.executable, "-c", f"{code}\nimport sys, json\nprint(json.dumps(sorted(sys.modules)))"],
        capture_output=True, text=True, check=True,
    )
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


def test_building_the_parser_imports_no_planner_or_heavy_library() -> None:
    loaded = _modules_after("from sgplan.cli import _build_parser\n_build_parser()")
    assert not [m for m in HEAVY if m in loaded]


def test_building_the_parser_imports_no_bench_machinery_yet_bench_help_names_the_case_timeout() -> None:
    from sgplan.bench.executors import DEFAULT_CASE_TIMEOUT_S

    loaded = _modules_after("from sgplan.cli import _build_parser\n_build_parser()")
    assert not [m for m in loaded if m.startswith("sgplan.bench")] and "numpy" not in loaded
    out = subprocess.run([sys.executable, "-m", "sgplan.cli", "bench", "--help"], capture_output=True,
                         text=True, check=True, env={**os.environ, "COLUMNS": "200"})
    assert f"kill a case's worker after S wall seconds (default: {DEFAULT_CASE_TIMEOUT_S:g})" in out.stdout


def test_loading_a_native_scene_folder_loads_no_importer(tmp_path: Path) -> None:
    from sgplan.scene.demo import demo_building
    from sgplan.scene.native import write_native_scene

    folder = write_native_scene(demo_building(), tmp_path / "house")
    loaded = _modules_after(f"import sgplan\nb = sgplan.load_scene({str(folder)!r})\nassert b.rooms()")
    assert not [m for m in loaded if m.startswith(("sgplan.importers", "scipy.spatial", "scipy.linalg"))]


def test_importing_a_planning_module_does_not_load_the_search() -> None:
    loaded = _modules_after("import sgplan.planning.problem")
    assert "sgplan.planning.amra" not in loaded and "sgplan.planning._search" not in loaded


def test_translating_a_mission_does_not_load_the_planner() -> None:
    loaded = _modules_after(
        "import sgplan\nbuilding = sgplan.load_scene('demo')\n"
        "sgplan.mission_from_text('Go to the kitchen.', building)"
    )
    assert "numba" not in loaded and "sgplan.planning.amra" not in loaded and "matplotlib" not in loaded


def test_inspect_without_drawing_loads_no_plotting_or_planner() -> None:
    # The first inspect builds the grid (compiled obstacle inflation) and caches it; later ones load it.
    inspect = "from sgplan.cli import main\nmain(['inspect', 'demo', '--json', '-'])"
    first, again = _modules_after(inspect), _modules_after(inspect)
    assert not [m for m in ("matplotlib", "sgplan.planning.amra", "rich", "openai") if m in first]
    assert "numba" not in again


def test_planning_package_names_still_resolve_lazily() -> None:
    import sgplan.planning as planning
    from sgplan.planning.amra import plan
    from sgplan.planning.setups import SETUPS

    assert planning.plan is plan and planning.SETUPS is SETUPS
    assert {"plan", "PlanningProblem", "SETUPS"} <= set(dir(planning))


def test_console_script_exits_fast_with_outputs_complete_and_atexit_run(tmp_path: Path) -> None:
    """As the console script (argv None), ``main`` ends the process itself: the exit code is the
    command's, stdout (a pipe, block-buffered) is complete, the JSON file is whole, atexit handlers ran,
    and the interpreter's teardown (here: an object whose finaliser would print) is skipped."""
    marker = tmp_path / "atexit-ran"
    boot = (
        "import atexit, sys\n"
        f"atexit.register(lambda: open({str(marker)!r}, 'w').close())\n"
        "class Noisy:\n"
        "    def __del__(self):\n"
        "        print('TEARDOWN', flush=True)\n"
        "keep = Noisy()\n"
        f"sys.argv = ['sgplan', 'plan', '--scene', 'demo', '--formula', 'F \"enter(room_5)\"', "
        f"'--start-room', 'kitchen', '--json', '-', '--quiet']\n"
        "from sgplan.cli import main\n"
        "main()\n"
        "print('NOT REACHED')\n"
    )
    out = subprocess.run([sys.executable, "-c", boot], capture_output=True, text=True, check=False)
    assert out.returncode == 0, out.stderr
    record = json.loads(out.stdout)  # the whole JSON document, nothing after it
    assert record["status"] == "optimal"
    assert marker.exists()
    assert "TEARDOWN" not in out.stdout and "NOT REACHED" not in out.stdout


def test_main_with_argv_returns_instead_of_exiting() -> None:
    from sgplan.cli import main

    assert main(["plan", "--scene", "demo", "--formula", "F p"]) == 2  # returns: the test goes on


@pytest.mark.gibson
def test_planning_a_gibson_mission_loads_no_scipy_image_or_sparse_code(gibson_root: Path) -> None:
    """Label rasters, reach regions and the automaton's reachability are plain numpy: scipy.ndimage and
    scipy.sparse (~0.3 s and ~30 MB to import) stay out of a plan (they are for drawing and importers)."""
    scene = gibson_root / "Benevolence"
    loaded = _modules_after(
        "from sgplan.cli import main\n"
        f"main(['plan', '--scene', {str(scene)!r}, '--mission-dir', {str(scene / 'missions' / '1')!r}, "
        "'--setup', 'ALL', '--profile', 'authors', '--quiet'], fast_exit=False)"
    )
    assert "sgplan.planning.amra" in loaded  # it did plan
    assert not [m for m in ("scipy.ndimage", "scipy.sparse") if m in loaded]


_BLAS_STATE = (
    "import json, sys\n"
    "def blas_state():\n"
    "    import numba.np.arraymath as am\n"
    "    return {'have_blas': am._HAVE_BLAS, 'scipy_linalg': 'scipy.linalg' in sys.modules,\n"
    "            'blocked': sys.modules.get('scipy.linalg.cython_blas', 0) is None,\n"
    "            'hooks': [type(f).__name__ for f in sys.meta_path if 'Blas' in type(f).__name__],\n"
    "            'loader': type(am.__loader__).__name__, 'gc_young': __import__('gc').get_threshold()[0]}\n"
)


def test_the_console_script_plans_without_importing_scipy_linalg(tmp_path: Path) -> None:
    """The console script lets numba skip its BLAS probe (no scipy.linalg import), restores sys.modules
    after, runs the garbage collector less often, and the plan is the library's (same cost, verified by
    the checker)."""
    import sgplan

    state, out_json = tmp_path / "state.json", tmp_path / "plan.json"
    formula = 'F("enter(room_4)" & F "enter(room_11)")'
    boot = (
        _BLAS_STATE + "import atexit\n"
        f"atexit.register(lambda: open({str(state)!r}, 'w').write(json.dumps(blas_state())))\n"
        f"sys.argv = ['sgplan', 'plan', '--scene', 'demo', '--formula', {formula!r}, '--start-index', '1', "
        f"'--setup', 'NO-LLM', '--json', {str(out_json)!r}, '--quiet']\n"
        "from sgplan.cli import main\n"
        "main()\n"
    )
    out = subprocess.run([sys.executable, "-c", boot], capture_output=True, text=True, check=False)
    assert out.returncode == 0, out.stderr
    assert json.loads(state.read_text()) == {"have_blas": False, "scipy_linalg": False, "blocked": False,
                                             "hooks": [], "loader": "SourceFileLoader",
                                             "gc_young": GC_YOUNG_THRESHOLD}
    record = json.loads(out_json.read_text())
    demo = sgplan.load_scene("demo")
    expected = sgplan.plan(demo, sgplan.mission_from_formula(formula, demo), 1, setup="NO-LLM")
    assert record["status"] == "optimal" and record["cost_m"] == pytest.approx(expected.cost_m, abs=1e-9)


def test_library_use_keeps_numbas_blas_probe() -> None:
    """``import sgplan`` and a Session's plan leave numba as the user's program would have it: the probe
    ran (scipy.linalg imported, BLAS found) and no import hook of sgplan's is left behind."""
    code = (
        _BLAS_STATE + "import sgplan\n"
        "demo = sgplan.load_scene('demo')\n"
        "result = sgplan.Session(demo).plan(sgplan.mission_from_formula('F \"enter(room_5)\"', demo), 0,"
        " setup='NO-LLM')\n"
        "assert result.status == 'optimal'\n"
        "print(json.dumps(blas_state()))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    state = json.loads(out.stdout.strip().splitlines()[-1])
    assert state["have_blas"] is True and state["scipy_linalg"] is True and state["hooks"] == []
    assert state["gc_young"] == 700  # Python's default: the garbage collector is the user's business


def test_the_blas_hook_is_one_shot_and_falls_back_when_numba_differs() -> None:
    """Installed once; a second call or an already loaded numba registry installs nothing; if numba's
    module cannot be found where expected, the hook steps aside (the normal finders take over)."""
    code = (
        "import json, sys\n"
        "from sgplan.runtime.jit import _SkipBlasProbe, skip_blas_probe\n"
        "first, second = skip_blas_probe(), skip_blas_probe()\n"
        "hook = next(f for f in sys.meta_path if isinstance(f, _SkipBlasProbe))\n"
        "sys.meta_path.remove(hook)\n"
        "stray = _SkipBlasProbe().find_spec('numba.np.arraymath', ['/nonexistent'])\n"
        "import numba.np.arraymath\n"
        "late = skip_blas_probe()\n"
        "print(json.dumps([first, second, stray is None, late, numba.np.arraymath._HAVE_BLAS]))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout.strip().splitlines()[-1]) == [True, False, True, False, True]



def test_a_reader_that_stops_early_ends_the_command_quietly(monkeypatch: pytest.MonkeyPatch,
                                                            capfd: pytest.CaptureFixture[str]) -> None:
    """`sgplan inspect demo | head -1`: the closed pipe is the shell's business (exit 141), not a bug."""
    from sgplan.cli import main

    read_end, write_end = os.pipe()
    os.close(read_end)  # the reader has left: every write to the pipe fails with EPIPE
    with open(write_end, "w", buffering=1) as gone:
        monkeypatch.setattr(sys, "stdout", gone)
        assert main(["inspect", "demo"], fast_exit=False) == 141
    assert "error" not in capfd.readouterr().err
