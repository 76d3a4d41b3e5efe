"""Write failures (a full disk, simulated with RLIMIT_FSIZE), signals at random points of a sweep and
concurrent writers: the earlier outputs survive byte for byte, or the new ones are complete."""

from __future__ import annotations

import json
import os
import resource
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from sgplan.bench.executors import WORKER_ENV
from sgplan.commands.demo import DEMO_MISSION
from tests.bench.conftest import data_dir  # noqa: F401 - the bench tests' data folder, as a fixture here
from tests.faults.harness import PYTHONPATH, RECORD, check, generated, record

FAKE_WORKER = [sys.executable, str(Path(__file__).parents[1] / "bench" / "fake_worker.py")]
OTHER_MISSION = "Go to the bathroom on floor 0."


def _no_leftovers(folder: Path) -> str | None:
    """``data-loss`` if a temporary or staging file of an interrupted write was left behind."""
    left = [p.name for p in folder.iterdir() if p.name.endswith((".tmp", ".new", ".old"))]
    return "data-loss" if left else None


def test_plan_json_on_a_full_disk(tmp_path: Path) -> None:
    out = tmp_path / "result.json"
    earlier = json.dumps({"status": "optimal", "cost_m": 1.0}) + "\n"
    out.write_text(earlier)
    check(
        "write/plan --json on a full disk",
        [
            "plan", "--scene", "demo", "--formula", 'F "enter(room_5)"', "--setup", "NO-LLM", "--json",
            str(out),
        ],
        survivors=[out],
        rlimits={resource.RLIMIT_FSIZE: len(earlier) + 10},
        after=lambda run: _no_leftovers(tmp_path),
    )


@pytest.mark.parametrize("limit", [100, 1000])  # fails at automaton.aut / building_desc.yaml
def test_translate_over_a_mission_on_a_full_disk(tmp_path: Path, limit: int) -> None:
    folder = tmp_path / "mission"
    check(
        "write/translate (first)",
        ["translate", "--scene", "demo", "--text", DEMO_MISSION, "--out", str(folder)], allow=("clean",),
    )
    (folder / "llm_heuristic.yaml").write_text("{}\n")  # guidance of the earlier mission
    check(f"write/translate over a mission, disk full at {limit} B",
          ["translate", "--scene", "demo", "--text", OTHER_MISSION, "--out", str(folder)],
          must_fail=True, survivors=[folder], rlimits={resource.RLIMIT_FSIZE: limit},
          after=lambda run: _no_leftovers(tmp_path))


def test_bench_results_on_a_full_disk(tmp_path: Path) -> None:
    from tests.faults.test_inputs import _ROW

    out = tmp_path / "bench"
    out.mkdir()
    (out / "results.jsonl").write_text(json.dumps(_ROW) + "\n")
    check("write/bench report (first)", ["bench", "report", "--out", str(out)])
    second = {**_ROW, "key": "demo-house/1/1/ALL/authors/none", "start": 1, "reason": "x" * 3000}
    with open(out / "results.jsonl", "a") as handle:
        handle.write(json.dumps(second) + "\n")
    csv_size = (out / "results.csv").stat().st_size
    # Room for the new results.csv (a little longer), not for the new results.json (3 kB longer).
    check("write/bench report on a full disk", ["bench", "report", "--out", str(out)], must_fail=True,
          survivors=[out / "results.csv", out / "results.json"],
          rlimits={resource.RLIMIT_FSIZE: csv_size + 200}, after=lambda run: _no_leftovers(out))


def test_concurrent_translations_into_one_folder(tmp_path: Path) -> None:
    """Two translations into one folder at once, three times: the folder always holds one whole mission."""
    mission_files = ("GPT_LTL_formula.txt", "ap_desc.yaml", "automaton.aut", "NL_instructions.txt")
    references = []
    for k, text in enumerate((DEMO_MISSION, OTHER_MISSION)):
        alone = tmp_path / f"alone{k}"
        check(
            "write/translate (reference)",
            ["translate", "--scene", "demo", "--text", text, "--out", str(alone)],
        )
        references.append({name: (alone / name).read_bytes() for name in mission_files})
    folder = tmp_path / "shared"
    env = {**os.environ, **({"PYTHONPATH": PYTHONPATH} if PYTHONPATH else {})}
    for round_ in range(3):
        procs = [
            subprocess.Popen(
                [
                    sys.executable, "-m", "sgplan.cli", "translate", "--scene", "demo", "--text", text,
                    "--out", str(folder),
                ],
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                env=env,
            )
            for text in (DEMO_MISSION, OTHER_MISSION)
        ]
        codes = [p.wait(timeout=300) for p in procs]
        for p in procs:
            p.communicate()
        found = {
            name: (folder / name).read_bytes() if (folder / name).is_file() else None
            for name in mission_files
        }
        outcome = "clean" if codes == [0, 0] and found in references else "data-loss"
        record(f"write/concurrent translations, round {round_}", outcome)
        if not RECORD:
            assert codes == [0, 0]
            assert found in references, "the folder mixes two missions"


SIGNALS = st.sampled_from([signal.SIGINT, signal.SIGTERM, signal.SIGHUP])


@generated(2)
@given(sig=SIGNALS, delay_s=st.floats(0.0, 2.0))
def test_signal_at_a_random_point_of_a_sweep(data_dir: Path, tmp_path_factory: pytest.TempPathFactory,  # noqa: F811
                                             sig: signal.Signals, delay_s: float) -> None:
    out = tmp_path_factory.mktemp("sweep")
    env = {
        **os.environ, WORKER_ENV: shlex.join(FAKE_WORKER),
        **({"PYTHONPATH": PYTHONPATH} if PYTHONPATH else {}),
    }
    base = [
        sys.executable, "-m", "sgplan.cli", "bench", "--data", str(data_dir), "--out", str(out), "--missions",
        "1", "--setups", "ALL", "A*", "--jobs", "1", "--no-report",
    ]
    first = subprocess.run([*base, "--starts", "0"], env=env, capture_output=True, timeout=300)
    earlier = (out / "results.jsonl").read_bytes()
    proc = subprocess.Popen(
        [*base, "--starts", "0-4"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    # The random point is counted from the sweep's first new row, so that it lands mid-sweep (a signal
    # during the interpreter's start-up imports is Python's business, not the sweep's).
    deadline = time.monotonic() + 120
    while (
        (out / "results.jsonl").stat().st_size == len(earlier)
        and proc.poll() is None
        and time.monotonic() < deadline
    ):
        time.sleep(0.02)
    time.sleep(delay_s)
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=120)
    lines = (out / "results.jsonl").read_bytes()
    rows = [json.loads(line) for line in lines.splitlines() if line.strip()]
    exported = {}
    if (out / "results.json").exists():
        exported = {row["key"] for row in json.loads((out / "results.json").read_text())}
    whole = (first.returncode == 0 and lines.startswith(earlier) and proc.returncode in (0, 128 + sig)
             and (not exported or exported <= {row["key"] for row in rows}) and b"Traceback" not in stderr)
    record(f"signal/{sig.name} after {delay_s:.1f} s", "clean" if whole else "data-loss")
    if not RECORD:
        assert whole, stderr.decode()[-2000:]
        done = subprocess.run([*base, "--starts", "0-4"], env=env, capture_output=True, timeout=300)
        assert done.returncode == 0, done.stderr.decode()[-2000:]
        final = [json.loads(line) for line in (out / "results.jsonl").read_text().splitlines()]
        assert len({row["key"] for row in final}) == 10



_SIGNAL_AT = """
import atexit, os, signal, sys
import sgplan.commands.bench as bench
sig, point = int(sys.argv[1]), sys.argv[2]
if point == "exit":  # the last atexit handler to run: the exit path, every output complete
    atexit.register(os.kill, os.getpid(), sig)
else:  # as the sweep's closing line is said: rows and export done, the report and the exit to come
    say = bench.say
    def signalling_say(message):
        say(message)
        if message.startswith("ran "):
            os.kill(os.getpid(), sig)
    bench.say = signalling_say
from sgplan.cli import main
main(sys.argv[3:], fast_exit=True)
"""


@pytest.mark.parametrize("point", ["after-export", "exit"])
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_signal_once_the_sweep_is_complete(data_dir: Path, tmp_path: Path, point: str,  # noqa: F811
                                           sig: signal.Signals) -> None:
    """The points that the random test above hits only when the machine is slow, chosen: a signal after the
    results are exported killed the sweep by the signal's default action (exit -15, not 143), and one in
    the exit path raised inside an atexit handler (a printed traceback)."""
    env = {**os.environ, WORKER_ENV: shlex.join(FAKE_WORKER),
           **({"PYTHONPATH": PYTHONPATH} if PYTHONPATH else {})}
    bench = [
        "bench", "--data", str(data_dir), "--out", str(tmp_path), "--missions", "1", "--setups", "ALL", "A*",
        "--jobs", "1", "--starts", "0-4", "--no-report",
    ]
    run = subprocess.run([sys.executable, "-c", _SIGNAL_AT, str(int(sig)), point, *bench], env=env,
                         capture_output=True, timeout=300)
    stderr = run.stderr.decode()
    assert run.returncode in (0, 128 + sig), (run.returncode, stderr[-2000:])
    assert "Traceback" not in stderr, stderr[-2000:]
    rows = [json.loads(line) for line in (tmp_path / "results.jsonl").read_text().splitlines()]
    assert len({row["key"] for row in rows}) == 10
    exported = json.loads((tmp_path / "results.json").read_text())
    assert {row["key"] for row in exported} == {row["key"] for row in rows}
