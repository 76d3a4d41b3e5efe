"""Long-lived bench workers: few processes run many cases, a crash or a timeout costs only its worker
(replaced by a fresh one), and the results are those of a fresh process per case."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from sgplan.bench.cases import Case, discover, expand
from sgplan.bench.executors import LocalExecutor
from sgplan.bench.results import ResultStore
from sgplan.bench.sweep import run_sweep
from sgplan.bench.worker import SceneKeeper, _peak_rss_mb, measure, reset_peak_rss
from tests.bench.conftest import SCENE, SWEEP

FAKE_WORKER = [sys.executable, str(Path(__file__).with_name("fake_worker.py"))]
SAME = ("status", "cost_m", "first_cost_m", "num_iterations", "expansions", "start_cell", "path_cells",
        "guidance", "reason")


def _cases(data_dir: Path, missions: list[str]) -> list[Case]:
    return [
        Case(SCENE, mission, k, "ALL", "authors", str(data_dir / SCENE),
             str(data_dir / SCENE / "missions" / mission))
        for k, mission in enumerate(missions)
    ]


def _pids(rows: list[dict]) -> list[int]:
    return [int(r["reason"].split()[1]) for r in rows if r["status"] == "optimal"]


def _run(executor: LocalExecutor, cases: list[Case]) -> dict[str, dict]:
    return {row["key"]: row for row in executor.run(cases)}


def _serve(script: str, cases: list[Case]) -> subprocess.CompletedProcess[str]:
    """Run ``python -c script`` (a worker serving requests on stdin) on ``cases``; its finished process."""
    requests = "".join(json.dumps({"case": c.to_dict(), "gallery_dir": None}) + "\n" for c in cases)
    return subprocess.run([sys.executable, "-c", script], input=requests, capture_output=True, text=True,
                          timeout=300, check=False)


def test_two_jobs_run_many_cases_in_two_processes(data_dir: Path) -> None:
    executor = LocalExecutor(2, timeout_s=30, command=FAKE_WORKER)
    rows = _run(executor, _cases(data_dir, ["1"] * 8))
    assert len(rows) == 8 and all(r["status"] == "optimal" for r in rows.values())
    assert executor.workers_started == 2 and len(set(_pids(list(rows.values())))) <= 2
    assert max(int(r["reason"].split()[3]) for r in rows.values()) >= 4  # a worker ran several cases


def test_a_crash_costs_only_its_worker_which_is_replaced(data_dir: Path) -> None:
    executor = LocalExecutor(1, timeout_s=30, command=FAKE_WORKER)
    cases = _cases(data_dir, ["1", "1", "crash", "1", "1"])
    by_key = _run(executor, cases)
    assert [by_key[c.key]["status"] for c in cases] == ["optimal", "optimal", "crashed", "optimal", "optimal"]
    assert "SIGSEGV" in by_key[cases[2].key]["reason"] and "about to crash" in by_key[cases[2].key]["reason"]
    before, after = _pids([by_key[c.key] for c in cases[:2]]), _pids([by_key[c.key] for c in cases[3:]])
    assert len(set(before)) == 1 and len(set(after)) == 1 and before[0] != after[0]
    assert executor.workers_started == 2
    assert not Path(f"/proc/{before[0]}").exists()


def test_a_timeout_kills_its_worker_and_the_next_case_gets_a_fresh_one(data_dir: Path) -> None:
    executor = LocalExecutor(1, timeout_s=2.0, command=FAKE_WORKER)
    cases = _cases(data_dir, ["1", "hang", "1"])
    rows = {r["key"]: r for r in executor.run(cases)}
    hung = rows[cases[1].key]
    assert hung["status"] == "wall-timeout" and "wall timeout of 2 s" in hung["reason"]
    assert hung["wall_s"] >= 2
    first, last = _pids([rows[cases[0].key]]), _pids([rows[cases[2].key]])
    assert first != last and executor.workers_started == 2
    assert not Path(f"/proc/{first[0]}").exists()  # the hung worker was killed, not left behind
    assert rows[cases[2].key]["reason"].endswith("case 1")  # a fresh process


def test_long_lived_workers_give_the_results_of_a_process_per_case(
    data_dir: Path, swept: tuple[list[Case], ResultStore], tmp_path: Path
) -> None:
    cases, store = swept  # run with the default executor: long-lived workers
    fresh = ResultStore(tmp_path)
    run_sweep(cases, fresh, LocalExecutor(2, timeout_s=300, reuse_workers=False))
    for case in cases:
        kept, alone = store.get(case.key), fresh.get(case.key)
        assert {k: kept[k] for k in SAME} == {k: alone[k] for k in SAME}, case.key
        assert [it["cost_m"] for it in kept["iterations"] or []] == [
            it["cost_m"] for it in alone["iterations"] or []
        ]


def test_output_written_straight_to_fd_1_does_not_break_the_answers(data_dir: Path) -> None:
    """A long-lived worker's answers go to a private copy of stdout: a line written to file descriptor 1
    by anything else during a case lands on stderr, not between two answers."""
    noisy = (
        "import os, sys\nimport sgplan.bench.worker as w\nreal = w.measure\n"
        "def measure(*args, **kwargs):\n    os.write(1, b'noise from C\\n')\n"
        "    return real(*args, **kwargs)\n"
        "w.measure = measure\nsys.exit(w.main(['--serve']))"
    )
    cases = _cases(data_dir, ["1", "2"])
    done = _serve(noisy, cases)
    lines = done.stdout.splitlines()
    assert done.returncode == 0 and len(lines) == 2, done.stderr[-2000:]
    assert [json.loads(line)["status"] for line in lines] == ["optimal", "optimal"]
    assert done.stderr.count("noise from C") == 2


def test_a_worker_keeps_the_scene_between_cases_of_that_scene(data_dir: Path) -> None:
    cases = expand(discover(data_dir), SWEEP, profile="authors")
    keeper = SceneKeeper()
    rows, sessions = [], []
    for case in cases:
        rows.append(measure(case, scenes=keeper))
        sessions.append(keeper.session)
    assert keeper.loads == 1
    assert sum(r["status"] == "optimal" for r in rows) == 5
    # No scene loading after the first case: every case planned in the one session (its building kept).
    # (Timing it no longer tells: a native scene folder loads in a few ms.)
    assert all(session is sessions[0] for session in sessions)


def test_peak_memory_is_reset_before_each_case() -> None:
    import mmap

    # Reset first: the test process's peak from earlier tests may lie above anything allocated here. The
    # 40 MB come from mmap itself, not malloc, which may keep freed memory (the process's malloc settings).
    if not reset_peak_rss():
        pytest.skip("no /proc/self/clear_refs here")
    big = mmap.mmap(-1, 40_000_000)
    for page in range(0, 40_000_000, 4096):  # touched page by page: resident
        big[page] = 1
    peak_with = _peak_rss_mb()
    big.close()
    assert reset_peak_rss()
    assert _peak_rss_mb() < peak_with - 20


@pytest.mark.parametrize(("flag", "reuse"), [([], True), (["--fresh-workers"], False)])
def test_the_command_uses_long_lived_workers_unless_told(
    data_dir: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, flag: list[str], reuse: bool
) -> None:
    from sgplan.bench import executors
    from sgplan.cli import main

    made: list[LocalExecutor] = []

    class Recording(LocalExecutor):
        def __init__(self, *args: object, **kwargs: object) -> None:
            super().__init__(*args, **kwargs)  # type: ignore[arg-type]
            made.append(self)

    monkeypatch.setattr(executors, "LocalExecutor", Recording)
    argv = ["bench", "--data", str(data_dir), "--out", str(tmp_path), "--missions", "1", "--starts", "0",
            "--setups", "A*", "--jobs", "1", "--no-report", "--quiet", *flag]
    assert main(argv) == 0
    assert [e.reuse_workers for e in made] == [reuse]
    assert [r["status"] for r in ResultStore(tmp_path).rows()] == ["optimal"]


def test_a_worker_process_is_set_up_as_sgplans_own(data_dir: Path, tmp_path: Path) -> None:
    """``python -m sgplan.bench.worker`` runs :func:`sgplan.runtime.process.prepare_own_process`: numba
    skips its BLAS probe (no scipy.linalg) and the garbage collector runs less often; the answers are
    unchanged."""
    from sgplan.runtime.process import GC_YOUNG_THRESHOLD

    state = tmp_path / "state.json"
    boot = (
        "import atexit, gc, json, runpy, sys\n"
        "def dump():\n"
        "    import numba.np.arraymath as am\n"
        f"    open({str(state)!r}, 'w').write(json.dumps([am._HAVE_BLAS, 'scipy.linalg' in sys.modules,"
        " gc.get_threshold()[0]]))\n"
        "atexit.register(dump)\n"
        "sys.argv = ['worker', '--serve']\n"
        "runpy.run_module('sgplan.bench.worker', run_name='__main__')\n"
    )
    cases = _cases(data_dir, ["1", "2"])
    done = _serve(boot, cases)
    assert done.returncode == 0, done.stderr[-2000:]
    answers = [json.loads(line) for line in done.stdout.splitlines()]
    assert [a["status"] for a in answers] == ["optimal", "optimal"]
    assert [a["cost_m"] for a in answers] == [measure(c)["cost_m"] for c in cases]
    assert json.loads(state.read_text()) == [False, False, GC_YOUNG_THRESHOLD]
