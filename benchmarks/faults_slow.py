"""Count the outcomes of the fault-injection suite (tests/faults), optionally against another checkout.

Runs the suite in record mode: every case in its own subprocess under a memory limit, outcomes appended
to a JSON-lines file instead of asserted, so that a crash or a hang of the code under test is counted,
not fatal. Prints the count of each outcome (clean / traceback / hang / crash / accepted / data-loss) and
the cases that were not clean.

    .venv/bin/python benchmarks/faults_slow.py                       # this checkout, the CI example counts
    .venv/bin/python benchmarks/faults_slow.py --slow                # 5x the generated examples
    git worktree add /tmp/orig 3f1b758                               # the code before issue 14
    .venv/bin/python benchmarks/faults_slow.py --pythonpath /tmp/orig/src --out /tmp/before.jsonl

Each case starts an interpreter, so a run takes ~3 s per case (~10-15 minutes for the ~240 cases).
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTCOMES = ("clean", "traceback", "hang", "crash", "accepted", "data-loss")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pythonpath", help="src folder of the sgplan to measure (default: this checkout's)")
    parser.add_argument("--out", default="faults.jsonl", help="outcome file (JSON lines; replaced)")
    parser.add_argument("--slow", action="store_true", help="5x as many generated examples")
    parser.add_argument("pytest_args", nargs="*", help="extra pytest arguments, e.g. -k yaml")
    args = parser.parse_args()
    out = Path(args.out).resolve()
    out.unlink(missing_ok=True)
    env = {**os.environ, "SGPLAN_FAULTS_RECORD": str(out), "SGPLAN_FAULTS_SCALE": "5" if args.slow else "1"}
    if args.pythonpath:
        env["SGPLAN_FAULTS_PYTHONPATH"] = str(Path(args.pythonpath).resolve())
    subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests/faults", *args.pytest_args],
        cwd=ROOT, env=env, check=False,
    )
    rows = [json.loads(line) for line in out.read_text().splitlines()] if out.exists() else []
    counts = collections.Counter(row["outcome"] for row in rows)
    print(f"\n{len(rows)} cases: " + ", ".join(f"{counts.get(o, 0)} {o}" for o in OUTCOMES)
          + "".join(f", {n} {o}" for o, n in counts.items() if o not in OUTCOMES))
    by_case = collections.Counter((row["case"], row["outcome"]) for row in rows if row["outcome"] != "clean")
    for (case, outcome), number in sorted(by_case.items()):
        print(f"  {outcome:10} x{number:<3} {case}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
