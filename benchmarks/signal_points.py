"""Signal `sgplan bench` at chosen points of a sweep and count how it ends, optionally for another checkout.

tests/faults/test_writes.py sends its signal at a random time, which lands only where the machine's speed
puts it; this script puts it at the N-th Python line event of the sweep's main thread, counted from its
first appended row to the process's end (a tracer started at that append sends the signal to its own
process, then stops tracing), for N spread over the whole count and, densely, over its last ``--tail``
fraction (the export, the report and the exit path). The sweep is the one of that test: the fake worker,
two cases already recorded, eight to run. A point is ``clean`` when the exit code is 0 or 128 + signal,
stderr holds no traceback and no earlier row is lost; otherwise the outcome says what went wrong.

    .venv/bin/python benchmarks/signal_points.py                     # this checkout
    git archive cfd3899 src | tar -x -C /tmp/before                  # an older checkout's sources
    .venv/bin/python benchmarks/signal_points.py --pythonpath /tmp/before/src
"""

from __future__ import annotations

import argparse
import collections
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FAKE_WORKER = f"{sys.executable} {ROOT / 'tests' / 'bench' / 'fake_worker.py'}"

_TRACED_SWEEP = """
import os, sys, threading
sig, target = int(sys.argv[1]), int(sys.argv[2])
count = 0

def tracer(frame, event, arg):
    global count
    count += 1
    if count != target:
        return tracer
    sys.settrace(None)
    while frame is not None:
        frame.f_trace, frame = None, frame.f_back
    os.kill(os.getpid(), sig)
    return None

from sgplan.bench import results
append = results.ResultStore.append

def traced_append(self, row):
    if sys.gettrace() is None and count == 0 and threading.current_thread() is threading.main_thread():
        sys.settrace(tracer)
        frame = sys._getframe(1)
        while frame is not None:
            frame.f_trace, frame = tracer, frame.f_back
    return append(self, row)

results.ResultStore.append = traced_append
import atexit
atexit.register(lambda: os.write(2, f"[events {count}]\\n".encode()))
from sgplan.cli import main
main(sys.argv[3:], fast_exit=True)
"""


def _bench_args(data: Path, out: Path, starts: str) -> list[str]:
    return ["bench", "--data", str(data), "--out", str(out), "--missions", "1", "--setups", "ALL", "A*",
            "--jobs", "1", "--no-report", "--starts", starts]


def _make_data(root: Path) -> Path:
    sys.path.insert(0, str(ROOT))
    from sgplan.api import add_guidance
    from sgplan.mission import compile_mission, save_mission_folder
    from sgplan.scene.demo import demo_building
    from sgplan.scene.native import write_native_scene
    from tests.bench.conftest import MISSIONS, SCENE

    building = demo_building()
    scene = write_native_scene(building, root / SCENE)
    for name, formula in MISSIONS.items():
        guided, _ = add_guidance(compile_mission(formula), building)
        save_mission_folder(guided, scene / "missions" / name)
    return root


def _run_point(
    data: Path, earlier: Path, work: Path, env: dict[str, str], sig: int, n: int
) -> tuple[str, str]:
    """The outcome of one sweep signalled at line event ``n`` (0: never), and its stderr."""
    out = work / "out"
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir()
    shutil.copy(earlier, out / "results.jsonl")
    argv = [sys.executable, "-c", _TRACED_SWEEP, str(sig), str(n), *_bench_args(data, out, "0-4")]
    run = subprocess.run(argv, env=env, capture_output=True, timeout=300)
    stderr = run.stderr.decode(errors="replace")
    if not (out / "results.jsonl").read_bytes().startswith(earlier.read_bytes()):
        return "data-loss", stderr
    if "Traceback" in stderr:
        return "traceback", stderr
    if run.returncode not in (0, 128 + sig):
        return f"exit {run.returncode}", stderr
    return "clean", stderr


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pythonpath", help="the src folder whose sgplan the sweeps import")
    parser.add_argument("--points", type=int, default=8, help="points over the whole count (default 8)")
    parser.add_argument("--tail", type=float, default=0.06, help="fraction of the count at its end sampled "
                        "densely (default 0.06)")
    parser.add_argument("--tail-points", type=int, default=8, help="points in the tail (default 8)")
    args = parser.parse_args()
    env = {**os.environ, "SGPLAN_BENCH_WORKER": FAKE_WORKER}
    if args.pythonpath:
        env["PYTHONPATH"] = args.pythonpath
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        data = _make_data(work / "data")
        subprocess.run([sys.executable, "-m", "sgplan.cli", *_bench_args(data, work / "first", "0")], env=env,
                       capture_output=True, check=True, timeout=300)
        earlier = work / "first" / "results.jsonl"
        _, stderr = _run_point(data, earlier, work, env, signal.SIGINT, 0)
        total = int(stderr.rsplit("[events ", 1)[1].split("]")[0])
        tail_from = int(total * (1 - args.tail))
        spread = (1 + total * k // args.points for k in range(args.points))
        tail = (tail_from + (total - tail_from) * k // args.tail_points for k in range(args.tail_points))
        points = sorted({*spread, *tail})
        print(f"{total} line events from the first new row to the end; {len(points)} points per signal")
        counts: collections.Counter[str] = collections.Counter()
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            for n in points:
                outcome, stderr = _run_point(data, earlier, work, env, sig, n)
                counts[outcome] += 1
                if outcome != "clean":
                    said = [line for line in stderr.splitlines() if line.strip() and "[events" not in line]
                    print(f"{sig.name} at event {n}/{total}: {outcome}: {said[-1][:150] if said else ''}")
    print(", ".join(f"{outcome}: {k}" for outcome, k in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
