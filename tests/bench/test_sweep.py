"""Executors and sweeps: right costs, statuses apart, results files, resume, crash/timeout, interrupt."""

from __future__ import annotations

import csv
import json
import os
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from sgplan.assembly import make_problem
from sgplan.bench.cases import BenchError, Case
from sgplan.bench.executors import WORKER_ENV, LocalExecutor, worker_command
from sgplan.bench.results import COLUMNS, RESULTS_JSONL, ResultStore, writing_lock
from sgplan.bench.sweep import SweepInterrupted, pending_cases, run_sweep
from sgplan.bench.worker import PARENT_ENV
from sgplan.formats import load_scene
from sgplan.mission import load_mission_folder
from sgplan.options import PlanOptions
from sgplan.planning import plan
from tests.bench.conftest import BAD_START, SCENE

FAKE_WORKER = [sys.executable, str(Path(__file__).with_name("fake_worker.py"))]


def _direct_cost(case: Case) -> float:
    building = load_scene(case.scene_dir)
    mission = load_mission_folder(case.mission_dir, profile=case.profile)
    options = PlanOptions(profile=case.profile, reach_model=case.reach_model)
    problem = make_problem(building, mission, building.initial_cells[case.start], options).problem
    return plan(problem, case.setup).cost_m


def test_local_executor_gives_the_costs_of_plan(swept: tuple[list[Case], ResultStore]) -> None:
    cases, store = swept
    rows = {r["key"]: r for r in store.rows()}
    assert set(rows) == {c.key for c in cases}
    optimal = [c for c in cases if rows[c.key]["status"] == "optimal"]
    assert len(optimal) == 5
    for case in optimal:
        row = rows[case.key]
        assert row["cost_m"] == pytest.approx(_direct_cost(case), abs=1e-9)
        assert row["first_cost_m"] >= row["cost_m"] - 1e-9 and row["cost_ratio"] >= 1.0 - 1e-12
        assert 0 <= row["first_time_s"] <= row["optimal_time_s"] <= row["search_s"] + 1e-9
        assert (
            sum(row[f"exp_{lv}"] for lv in ("anchor", "occupancy", "object", "room", "floor"))
            == row["expansions"]
        )
        assert row["peak_rss_mb"] > 50 and row["wall_s"] > row["load_s"] > 0 and row["precompute_s"] > 0
        assert row["guidance"] == "mission" and row["profile"] == "authors" and row["executor"] == "local"
        assert row["reach_model"] == "box"  # the authors profile's
        assert len(row["iterations"]) == row["num_iterations"] and len(row["queues"]) == len(
            row["iterations"][0]["expansions"]
        )


def test_infeasible_and_invalid_starts_are_recorded_with_reasons(
    swept: tuple[list[Case], ResultStore],
) -> None:
    _, store = swept
    infeasible = store.get(f"{SCENE}/3/0/ALL/authors/tl=none")
    invalid = store.get(f"{SCENE}/1/{BAD_START}/ALL/authors/tl=none")
    assert infeasible["status"] == "unsatisfiable" and "Never enter the bathroom" in infeasible["reason"]
    assert invalid["status"] == "invalid-start" and "lies in no room" in invalid["reason"]
    assert infeasible["cost_m"] is None and invalid.get("first_time_s") is None


def test_a_sweep_with_a_chosen_reach_model_records_it_and_plans_with_it(data_dir: Path,
                                                                       tmp_path: Path) -> None:
    """Mission 2 reaches the teddy bear: the visible model's optimum, recorded as such, is a plan's."""
    from sgplan.bench.cases import Grid, discover, expand

    grid = [Grid(missions=("2",), starts=(0,), setups=("NO-LLM",))]
    cases = expand(discover(data_dir), grid, profile="authors", reach_model="visible")
    store = ResultStore(tmp_path / "out")
    run_sweep(cases, store, LocalExecutor(1, timeout_s=300))
    (row,) = store.rows()
    assert row["reach_model"] == "visible" and row["key"].endswith("/reach=visible")
    assert row["status"] == "optimal" and row["cost_m"] == pytest.approx(_direct_cost(cases[0]), abs=1e-9)
    boxed = Case.from_dict({**cases[0].to_dict(), "reach_model": None})
    assert _direct_cost(boxed) < row["cost_m"]  # the authors' window reaches the bear through a wall


def test_results_files_have_one_row_per_case_and_stable_columns(
    swept: tuple[list[Case], ResultStore],
) -> None:
    cases, store = swept
    csv_path, json_path = store.export()
    with open(csv_path, newline="") as handle:
        reader = csv.DictReader(handle)
        assert tuple(reader.fieldnames) == COLUMNS
        rows = list(reader)
    assert len(rows) == len(cases) == len(json.loads(json_path.read_text()))
    assert {r["status"] for r in rows} == {"optimal", "unsatisfiable", "invalid-start"}


def test_rerun_runs_nothing_and_a_torn_last_line_is_dropped(
    swept: tuple[list[Case], ResultStore], tmp_path: Path
) -> None:
    cases, store = swept
    copy = tmp_path / RESULTS_JSONL
    lines = store.path.read_text().splitlines(keepends=True)
    # Two rows lost and a third half-written, as after an interrupt in the middle of an append.
    copy.write_text("".join(lines[:-3]) + lines[-3][: len(lines[-3]) // 2])
    resumed = ResultStore(tmp_path)
    assert len(resumed) == len(cases) - 3
    assert not copy.read_text().endswith("\n")  # a reader leaves the file alone; the next append cuts it
    missing = {c.key for c in pending_cases(cases, resumed)}
    assert len(missing) == 3
    assert pending_cases(cases, store) == []

    class Recording:
        name = "recording"

        def __init__(self) -> None:
            self.ran: list[str] = []

        def run(self, todo):  # replays the recorded rows instead of planning again
            for case in todo:
                self.ran.append(case.key)
                yield store.get(case.key)

    executor = Recording()
    summary = run_sweep(cases, resumed, executor)
    assert set(executor.ran) == missing and summary.skipped == len(cases) - 3 and summary.ran == 3
    assert len(ResultStore(tmp_path)) == len(cases) and copy.read_text().count("\n") == len(cases)
    assert len(ResultStore(tmp_path)) == len(cases)


def test_an_interrupt_swallowed_by_a_finaliser_stops_the_sweep_after_the_row_it_came_with(
    swept: tuple[list[Case], ResultStore], tmp_path: Path
) -> None:
    """Ctrl-C landing while the garbage collector runs a weakref callback is lost to Python ("Exception
    ignored in ..."); the sweep still stops at its next row, with that row stored."""
    from sgplan.runtime.process import interrupts_handled

    cases, store = swept

    class InterruptedWhileFreed:
        def __del__(self) -> None:
            raise KeyboardInterrupt

    class Replaying:
        name = "replaying"

        def run(self, todo):
            for case in todo:
                InterruptedWhileFreed()
                yield store.get(case.key)

    fresh = ResultStore(tmp_path)
    with pytest.raises(SweepInterrupted) as stop, interrupts_handled(termination=False, hold_after=False):
        run_sweep(cases, fresh, Replaying())
    assert stop.value.summary.ran == 1 and len(ResultStore(tmp_path)) == 1


def test_crash_and_wall_timeout_are_recorded_and_the_sweep_goes_on(data_dir: Path, tmp_path: Path) -> None:
    def case(mission: str) -> Case:
        return Case(
            SCENE, mission, 0, "ALL", "authors", str(data_dir / SCENE),
            str(data_dir / SCENE / "missions" / mission),
        )

    cases = [case("crash"), case("hang"), case("1"), case("2")]
    store = ResultStore(tmp_path)
    t0 = time.perf_counter()
    summary = run_sweep(cases, store, LocalExecutor(2, timeout_s=3.0, command=FAKE_WORKER))
    assert time.perf_counter() - t0 < 30
    assert summary.ran == 4 and summary.statuses == {"crashed": 1, "wall-timeout": 1, "optimal": 2}
    crashed, hung = store.get(cases[0].key), store.get(cases[1].key)
    assert "SIGSEGV" in crashed["reason"] and "about to crash" in crashed["reason"]
    assert "wall timeout of 3 s" in hung["reason"] and hung["wall_s"] >= 3.0
    assert run_sweep(cases, store, LocalExecutor(2, timeout_s=3.0, command=FAKE_WORKER)).ran == 0
    retried = run_sweep(cases, store, LocalExecutor(2, timeout_s=1.0, command=FAKE_WORKER), retry=True)
    assert retried.ran == 2 and len(store) == 4


def _rows_in(folder: Path) -> list[dict]:
    path = folder / RESULTS_JSONL
    return [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []


def _bench_command(data_dir: Path, out: Path) -> list[str]:
    return [
        sys.executable, "-m", "sgplan.cli", "bench", "--data", str(data_dir), "--out", str(out), "--missions",
        "1", "--starts", "0,1", "--setups", "ALL", "NO-LLM", "A*", "--jobs", "1", "--no-report",
    ]


def _start_sweep_that_hangs_after_one_case(command: list[str], marker: Path) -> subprocess.Popen:
    """Start ``command`` with a stand-in worker that answers the first case and hangs on the next, and
    return once the first row is recorded (and a moment later, so that the sweep has counted it): a
    signal sent then always lands mid-sweep, however fast or loaded the machine is. ``marker`` is the
    stand-in's answered-once file."""
    env = {**os.environ, WORKER_ENV: shlex.join(FAKE_WORKER), "FAKE_WORKER_ONCE": str(marker)}
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    out = Path(command[command.index("--out") + 1])
    deadline = time.monotonic() + 120
    while not _rows_in(out) and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.1)
    time.sleep(0.5)  # the row is in the file; let the sweep finish recording it (the next case hangs)
    return proc


def _workers_alive(sweep_pid: int) -> list[int]:
    """Pids of live worker processes started by the sweep ``sweep_pid`` (their environment names it)."""
    needle = f"{PARENT_ENV}={sweep_pid}".encode()
    alive = []
    for environ in Path("/proc").glob("[0-9]*/environ"):
        try:
            if needle in environ.read_bytes().split(b"\0"):
                alive.append(int(environ.parent.name))
        except OSError:
            continue
    return alive


def _wait_for_no_workers(sweep_pid: int, timeout_s: float = 10.0) -> list[int]:
    deadline = time.monotonic() + timeout_s
    while (alive := _workers_alive(sweep_pid)) and time.monotonic() < deadline:
        time.sleep(0.1)
    return alive


def test_interrupting_the_command_and_rerunning_finishes_only_the_missing_cases(
    data_dir: Path, tmp_path: Path
) -> None:
    out = tmp_path / "out"
    command = _bench_command(data_dir, out)
    proc = _start_sweep_that_hangs_after_one_case(command, tmp_path / "answered")
    proc.send_signal(signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    first = _rows_in(out)
    assert len(first) == 1
    assert (out / "results.csv").exists()  # exported on the way out

    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert f"{len(first)} already in" in done.stderr
    final = _rows_in(out)
    assert len(final) == 6 == len({r["key"] for r in final})
    assert final[: len(first)] == first  # the finished rows were kept, not re-run
    assert all(r["status"] == "optimal" for r in final)
    interrupted, call = [json.loads(line) for line in (out / "sweeps.jsonl").read_text().splitlines()]
    assert interrupted["interrupted"] and interrupted["ran"] == 1 and interrupted["skipped"] == 0
    assert call["ran"] == 6 - len(first) and call["skipped"] == len(first) and call["jobs"] == 1
    assert not call["interrupted"]


def test_the_worker_command_can_be_replaced_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(WORKER_ENV, "taskset -c 1 'my python' -m sgplan.bench.worker")
    assert worker_command() == ["taskset", "-c", "1", "my python", "-m", "sgplan.bench.worker"]
    monkeypatch.setenv(WORKER_ENV, "python 'unclosed")
    with pytest.raises(BenchError, match=WORKER_ENV):
        LocalExecutor(1)
    monkeypatch.setenv(WORKER_ENV, "/no/such/worker -m x")
    with pytest.raises(BenchError, match="cannot find the program '/no/such/worker'"):
        LocalExecutor(1)


def test_a_worker_that_cannot_start_stops_the_sweep_with_a_clear_error(swept, tmp_path: Path) -> None:
    cases, _ = swept
    with pytest.raises(BenchError, match="cannot start the worker '/no/such/python'"):
        run_sweep(cases[:2], ResultStore(tmp_path), LocalExecutor(1, command=["/no/such/python"]))


def test_a_last_row_without_its_newline_is_kept(swept, tmp_path: Path) -> None:
    _, store = swept
    lines = store.path.read_text().splitlines()
    (tmp_path / RESULTS_JSONL).write_text("\n".join(lines[:2]))  # the 2nd row lacks its newline
    copy = ResultStore(tmp_path)
    assert len(copy) == 2
    copy.append(store.get(json.loads(lines[2])["key"]))
    assert [json.loads(line)["key"] for line in (tmp_path / RESULTS_JSONL).read_text().splitlines()] == \
        [json.loads(line)["key"] for line in lines[:3]]


def test_a_second_sweep_into_the_same_folder_is_refused(tmp_path: Path) -> None:
    with writing_lock(tmp_path), pytest.raises(BenchError, match="another `sgplan bench` is writing"), \
            writing_lock(tmp_path):
        pass
    with writing_lock(tmp_path):  # released
        pass


@pytest.mark.parametrize(("content", "fragment"), [
    (b'{"key": "a", "status": "optimal"}\n', "missing scene, mission, start, setup, profile"),
    (b"\xff\xfe\n", "is not UTF-8"),
    (b"[1, 2]\n", "line 1 is not a result row"),
])
def test_a_damaged_results_file_gets_a_clear_error(tmp_path: Path, content: bytes, fragment: str) -> None:
    (tmp_path / RESULTS_JSONL).write_bytes(content)
    with pytest.raises(BenchError, match=fragment):
        ResultStore(tmp_path)


def test_retry_reruns_failed_rows_including_errors(
    swept: tuple[list[Case], ResultStore], tmp_path: Path
) -> None:
    cases, store = swept
    copy = ResultStore(tmp_path)
    for status, case in zip(("error", "crashed", "wall-timeout", "optimal"), cases):
        copy.append({**store.get(case.key), "status": status})
    retried = {c.key for c in pending_cases(cases[:4], copy, retry=True)}
    assert retried == {c.key for c in cases[:3]}
    assert pending_cases(cases[:4], copy) == []


@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="needs Linux /proc")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGHUP, signal.SIGKILL])
def test_no_worker_outlives_a_terminated_sweep(data_dir: Path, tmp_path: Path, sig: signal.Signals) -> None:
    proc = _start_sweep_that_hangs_after_one_case(
        _bench_command(data_dir, tmp_path / "out"), tmp_path / "answered"
    )
    assert len(_workers_alive(proc.pid)) == 1, "the hanging worker should be running"
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=60)
    # SIGTERM and SIGHUP stop the sweep like Ctrl-C (exit 128 + signal); after SIGKILL the orphaned
    # worker notices and exits.
    assert proc.returncode == (-signal.SIGKILL if sig == signal.SIGKILL else 128 + sig), stderr
    assert _wait_for_no_workers(proc.pid) == []
    if sig != signal.SIGKILL:
        (logged,) = [
            json.loads(line) for line in (tmp_path / "out" / "sweeps.jsonl").read_text().splitlines()
        ]
        assert logged["interrupted"] and logged["ran"] == 1
