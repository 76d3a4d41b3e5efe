"""Whole-process cost of the CLI and of ``sgplan bench``: source trees compared in one run.

Part 1 (``plan``): for every shipped Gibson mission, the chosen starts and setups, each variant runs
``python -m sgplan.cli plan --scene S --mission-dir M --start-index K --setup X --profile authors --json F``
as a fresh process, variants back to back on each case (so machine load hits them alike), warm caches
(numba's, Python's bytecode cache beside each source tree, and sgplan's scene cache in a private folder,
all warmed by one run per variant and scene first; ``--no-bytecode-cache``: compile from source each time).
Per case: wall seconds (fork to exit, measured here) and peak RSS (``ru_maxrss`` of the child from
``wait4``), plus the planner's own precompute + search seconds from the JSON, so the fixed cost (the rest)
shows; then median and worst per variant and setup.

Part 2 (``--bench``): ``sgplan bench`` on a selection (default: missions 1-2 x starts 0-4 x ALL / NO-LLM /
A* on the three scenes, 90 cases; ``--bench-args`` replaces it), each variant into a fresh folder, wall
seconds of the whole command.

    git archive main src | tar -x -C /tmp/sgplan-before
    .venv/bin/python benchmarks/fixed_cost.py --variant before=/tmp/sgplan-before/src --variant after=src
    .venv/bin/python benchmarks/fixed_cost.py --variant after=src --missions 1 --starts 0 --bench
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SCENES = ("Allensville", "Benevolence", "Collierville")
DEFAULT_BENCH = "--missions 1 2 --starts 0-4 --setups ALL NO-LLM A* --jobs 2"  # older trees read no "1,2"


BYTECODE = True
"""Whether the children may write and use Python's bytecode cache (``__pycache__`` beside the sources, as
any installed or once-imported package has): ``--no-bytecode-cache`` makes every child compile sgplan's
modules from source, as a shell with ``PYTHONDONTWRITEBYTECODE=1`` and a fresh tree does (~0.05-0.1 s)."""


def child_env(src: Path, cache: Path) -> dict[str, str]:
    env = dict(os.environ, PYTHONPATH=str(src), SGPLAN_CACHE_DIR=str(cache))
    env.pop("SGPLAN_NO_CACHE", None)
    if BYTECODE:  # the warm-up run writes it, like numba's cache and the scene cache
        env.pop("PYTHONDONTWRITEBYTECODE", None)
    else:
        env["PYTHONDONTWRITEBYTECODE"] = "1"
    return env


def run_plan(src: Path, cache: Path, data: Path, scene: str, mission: str, start: int, setup: str) -> dict:
    """One ``sgplan plan`` process; its wall seconds, peak RSS (MiB), exit code and JSON timings."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "plan.json"
        argv = [sys.executable, "-m", "sgplan.cli", "plan", "--scene", str(data / scene), "--mission-dir",
                str(data / scene / "missions" / mission), "--start-index", str(start), "--setup", setup,
                "--profile", "authors", "--json", str(out), "--quiet"]
        t0 = time.perf_counter()
        proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=tmp,
                                env=child_env(src, cache))
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        record = json.loads(out.read_text()) if out.exists() else {}
    timings = record.get("timings") or {}
    return {"wall_s": wall, "rss_mb": usage.ru_maxrss / 1024.0, "code": proc.returncode,
            "status": record.get("status"), "cost_m": record.get("cost_m"),
            "planner_s": (timings.get("precompute_s") or 0.0) + (timings.get("search_s") or 0.0)}


def plan_part(args: argparse.Namespace, variants: dict[str, Path], caches: dict[str, Path]) -> None:
    data = args.data
    cases = [(scene, mission, start, setup) for scene in args.scenes for mission in args.missions
             for start in args.starts for setup in args.setups]
    for name, src in variants.items():  # warm numba's and the scene cache, once per scene
        for scene in args.scenes:
            run_plan(src, caches[name], data, scene, args.missions[0], args.starts[0], args.setups[0])
    rows: list[dict] = []
    print("| case | " + " | ".join(f"{v} wall s | {v} RSS MB | {v} fixed s" for v in variants) + " |")
    print("|---|" + "---|---|---|" * len(variants))
    for scene, mission, start, setup in cases:
        cells = []
        for name, src in variants.items():
            row = run_plan(src, caches[name], data, scene, mission, start, setup)
            row.update(variant=name, setup=setup, case=f"{scene}/{mission}/{start}/{setup}")
            rows.append(row)
            fixed = row["wall_s"] - row["planner_s"]
            cells.append(f"{row['wall_s']:.2f} | {row['rss_mb']:.0f} | {fixed:.2f}")
        costs = {r["cost_m"] for r in rows[-len(variants):]}
        flag = "" if len(costs) == 1 else f" COSTS DIFFER {costs}"
        case = f"{scene}/{mission}/{start}/{setup} ({rows[-1]['status']})"
        print(f"| {case} | " + " | ".join(cells) + f" |{flag}", flush=True)
    print("\n| variant | setup | n | median wall s | worst wall s | median RSS MB | worst RSS MB | "
          "median fixed s (wall - precompute - search) |\n|---|---|---|---|---|---|---|---|")
    for name in variants:
        for setup in args.setups:
            mine = [r for r in rows if r["variant"] == name and r["setup"] == setup]
            walls, rss = [r["wall_s"] for r in mine], [r["rss_mb"] for r in mine]
            fixed = [r["wall_s"] - r["planner_s"] for r in mine]
            print(f"| {name} | {setup} | {len(mine)} | {statistics.median(walls):.2f} | {max(walls):.2f} | "
                  f"{statistics.median(rss):.0f} | {max(rss):.0f} | {statistics.median(fixed):.2f} |")


def bench_part(args: argparse.Namespace, variants: dict[str, Path], caches: dict[str, Path]) -> None:
    print(f"\nsgplan bench {args.bench_args} --profile authors (whole command, fresh output folder):")
    walls = {}
    for name, src in variants.items():
        with tempfile.TemporaryDirectory() as out:
            # Source trees older than `--quiet` show their progress bar instead.
            common = (src / "sgplan" / "commands" / "common.py").read_text()
            quiet = ["--quiet"] if "--quiet" in common else []
            argv = [sys.executable, "-m", "sgplan.cli", "bench", "--data", str(args.data), "--out", out,
                    "--profile", "authors", "--no-report", *quiet, *shlex.split(args.bench_args)]
            t0 = time.perf_counter()
            done = subprocess.run(argv, capture_output=True, text=True, env=child_env(src, caches[name]),
                                  check=False)
            walls[name] = time.perf_counter() - t0
            results = Path(out) / "results.jsonl"
            if not results.exists():
                sys.exit(f"{name}: sgplan bench wrote no results (exit {done.returncode}):\n"
                         + done.stderr[-2000:])
            rows = [json.loads(line) for line in results.read_text().splitlines()]
        statuses: dict[str, int] = {}
        for row in rows:
            statuses[row["status"]] = statuses.get(row["status"], 0) + 1
        print(f"  {name}: {walls[name]:.1f} s wall, exit {done.returncode}, {len(rows)} cases {statuses}",
              flush=True)
        walls[f"{name}:costs"] = {r["key"]: r["cost_m"] for r in rows}  # type: ignore[assignment]
    names = list(variants)
    for i, first in enumerate(names):
        for other in names[i + 1:]:
            a, b = walls[f"{first}:costs"], walls[f"{other}:costs"]
            same = a == b
            gaps = [abs(a[k] - b[k]) for k in a.keys() & b.keys() if a[k] is not None and b[k] is not None]
            print(f"  {first} / {other}: x{walls[first] / walls[other]:.2f} wall; costs identical: {same} "
                  f"({len(a.keys() & b.keys())} cases in both, largest cost difference "
                  f"{max(gaps, default=0.0):.3g} m, unpaired {len(a.keys() ^ b.keys())})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variant", action="append", metavar="NAME=SRC", help="a source tree (repeatable)")
    parser.add_argument("--data", type=Path, default=REPO.parent / "shared" / "datasets" / "gibson-3dsg")
    parser.add_argument("--scenes", nargs="+", default=list(SCENES))
    parser.add_argument("--missions", nargs="+", default=["1", "2", "3", "4", "5"])
    parser.add_argument("--starts", nargs="+", type=int, default=[0, 1])
    parser.add_argument("--setups", nargs="+", default=["A*", "ALL"])
    parser.add_argument("--no-plan", action="store_true", help="skip part 1")
    parser.add_argument("--bench", action="store_true", help="also run part 2")
    parser.add_argument("--bench-args", default=DEFAULT_BENCH)
    parser.add_argument("--no-bytecode-cache", action="store_true",
                        help="children compile sgplan from source every time (see BYTECODE)")
    args = parser.parse_args()
    global BYTECODE
    BYTECODE = not args.no_bytecode_cache
    given = args.variant or [f"this={REPO / 'src'}"]
    variants = {name: Path(path).resolve() for name, path in (v.split("=", 1) for v in given)}
    with tempfile.TemporaryDirectory() as root:
        caches = {name: Path(root) / name for name in variants}
        if not args.no_plan:
            plan_part(args, variants, caches)
        if args.bench:
            bench_part(args, variants, caches)


if __name__ == "__main__":
    main()
