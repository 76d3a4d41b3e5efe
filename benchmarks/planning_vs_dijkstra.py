"""sgplan's search against the compiled blind product-graph Dijkstra, per shipped Gibson case, in one run.

For every case (3 scenes x 5 missions x the chosen starts, authors profile) the parent process runs the
reference (benchmarks/dijkstra_reference, compiled C, exact) three times and keeps the fastest, and one
child process per setup runs sgplan (``planning_gibson.py --one``: imports, load, plan, exit). Per case it
prints sgplan's search to the optimum divided by the Dijkstra's search (both exclude precompute / indexing),
the first-path time, both optimal costs (they must agree to 1e-6 m), the child's whole-process wall seconds
and peak RSS; then the median and worst ratio per setup. Needs the Gibson data and a C compiler (it says
so if none exists).

Before/after in one run: export an older tree and pass it as a variant; the variants run back to back on
each case, so machine load hits them alike (report ratios, the machine is shared). A variant whose folder
holds ``tests/`` beside ``src/`` loads its cases with its own ``tests/planning/gibson_cases.py`` (export
both: the case loader follows the source tree's API); otherwise with this checkout's:

    git archive <commit> src tests | tar -x -C /tmp/sgplan-before
    .venv/bin/python benchmarks/planning_vs_dijkstra.py \
        --variant before=/tmp/sgplan-before/src --variant after=src

    .venv/bin/python benchmarks/planning_vs_dijkstra.py                       # this tree, starts 0-1
    .venv/bin/python benchmarks/planning_vs_dijkstra.py --repeat-sgplan 3 ...  # fastest of 3 per variant
    .venv/bin/python benchmarks/planning_vs_dijkstra.py --from-json a.json b.json  # summarise saved runs

With several variants it also says, against the first, on how many cases the status, cost or expansions
differ (a refactoring must leave none) and the ratio of their searches to the optimum.
    .venv/bin/python benchmarks/planning_vs_dijkstra.py --scenes Allensville --setups A* --json out.json
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from benchmarks.dijkstra_reference.reference import NoCompilerError, find_compiler, solve

SCENES = ("Allensville", "Benevolence", "Collierville")
CHILD = REPO / "benchmarks" / "planning_gibson.py"


def run_child(src: Path, scene: str, mission: int, start: int, setup: str) -> dict:
    """One sgplan process on one case with ``src`` first on the import path, then the tests beside it (if
    any), then this checkout's; adds its wall seconds."""
    own_tests = [str(src.parent)] if (src.parent / "tests" / "planning" / "gibson_cases.py").is_file() else []
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(src), *own_tests, str(REPO)]))
    t0 = time.perf_counter()
    out = subprocess.run(
        [sys.executable, str(CHILD), "--profile", "authors", "--one", scene, str(mission), str(start), setup],
        capture_output=True, text=True, cwd=REPO, env=env, check=False,
    )
    wall = time.perf_counter() - t0
    if out.returncode != 0:
        return {"status": "crashed", "message": out.stderr[-1500:], "wall_s": wall}
    row = json.loads(out.stdout.strip().splitlines()[-1])
    row["wall_s"] = wall
    return row


def summary(rows: list[dict], variants: list[str], setups: list[str]) -> None:
    """Median / worst per variant and setup of the search ratio, first path, wall and RSS."""
    print("\nsummary (solved cases; ratio = sgplan search to optimum / Dijkstra search)")
    print(f"{'variant':<10} {'setup':<7} {'cases':>5} {'ratio med':>9} {'worst':>7} {'<=1':>5} {'<=1.5':>5} "
          f"{'1st s med':>9} {'1st worst':>9} {'wall med':>8} {'wall max':>8} {'RSS med':>7} {'RSS max':>7}")
    for variant in variants:
        for setup in setups:
            mine = [r for r in rows if r["variant"] == variant and r["setup"] == setup and "ratio" in r]
            if not mine:
                continue
            ratios = [r["ratio"] for r in mine]
            first = [r["first_s"] for r in mine]
            wall = [r["wall_s"] for r in mine]
            rss = [r["rss_mb"] for r in mine]
            print(
                f"{variant:<10} {setup:<7} {len(mine):>5} "
                f"{statistics.median(ratios):>9.2f} {max(ratios):>7.2f} "
                f"{sum(x <= 1 for x in ratios):>5} {sum(x <= 1.5 for x in ratios):>5} "
                f"{statistics.median(first):>9.4f} {max(first):>9.4f} {statistics.median(wall):>8.2f} "
                f"{max(wall):>8.2f} {statistics.median(rss):>7.0f} {max(rss):>7.0f}"
            )


def agreement(rows: list[dict], variants: list[str], setups: list[str]) -> int:
    """Each variant against the first on the same cases: cases whose status, cost or expansions differ (a
    refactoring must leave none), and per setup the ratio of the search to the optimum (this variant / the
    first) over the cases both solved: median, geometric mean, total. Returns the number of differences."""
    if len(variants) < 2:
        return 0
    by_case: dict[tuple, dict[str, dict]] = {}
    for r in rows:
        by_case.setdefault((r["scene"], r["mission"], r["start"], r["setup"]), {})[r["variant"]] = r
    first = variants[0]
    differing = 0
    print(f"\nagainst {first} (ratio = search to the optimum / {first}'s)")
    for variant in variants[1:]:
        pairs = [(v[first], v[variant]) for v in by_case.values() if first in v and variant in v]
        bad = [a for a, b in pairs if (a.get("status"), a.get("cost"), a.get("expansions"))
               != (b.get("status"), b.get("cost"), b.get("expansions"))]
        differing += len(bad)
        print(f"{variant}: {len(pairs)} cases, {len(bad)} differ in status, cost or expansions"
              + "".join(f"; {a['scene']} m{a['mission']} s{a['start']} {a['setup']}" for a in bad[:10]))
        for setup in setups:
            solved = [(a["opt_s"], b["opt_s"]) for a, b in pairs
                      if a["setup"] == setup and "opt_s" in a and "opt_s" in b]
            if not solved:
                continue
            ratios = [b / a for a, b in solved]
            total_a, total_b = sum(a for a, _ in solved), sum(b for _, b in solved)
            print(f"  {setup:<7} {len(solved):>3} solved: median {statistics.median(ratios):.3f}, "
                  f"geometric mean {statistics.geometric_mean(ratios):.3f}, total {total_b / total_a:.3f} "
                  f"({total_b:.2f} / {total_a:.2f} s)")
    return differing


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="+", default=list(SCENES))
    parser.add_argument("--missions", nargs="+", type=int, default=[1, 2, 3, 4, 5])
    parser.add_argument("--starts", nargs="+", type=int, default=[0, 1])
    parser.add_argument("--setups", nargs="+", default=["A*", "ALL", "NO-LLM"])
    parser.add_argument("--variant", action="append", metavar="NAME=SRC",
                        help="a source tree to time (repeatable); default: this tree's src")
    parser.add_argument("--repeat", type=int, default=3, help="reference runs per case (the fastest counts)")
    parser.add_argument("--repeat-sgplan", type=int, default=1, metavar="N",
                        help="sgplan processes per case and variant, the variants taking turns (the fastest "
                        "search to the optimum counts)")
    parser.add_argument("--json", type=Path, help="also write every row to this file")
    parser.add_argument("--from-json", type=Path, nargs="+", metavar="FILE",
                        help="run nothing: summarise the rows of earlier --json files")
    args = parser.parse_args()
    if args.from_json:
        rows = [row for path in args.from_json for row in json.loads(path.read_text())]
        names = list(dict.fromkeys(r["variant"] for r in rows))
        setups = list(dict.fromkeys(r["setup"] for r in rows))
        summary(rows, names, setups)
        bad = [r for r in rows if not r["agree"]]
        print(f"\n{len(rows)} runs; cost disagreements with the reference: {len(bad)}")
        return 1 if agreement(rows, names, setups) or bad else 0
    try:
        find_compiler()
    except NoCompilerError as error:
        print(f"planning_vs_dijkstra: {error}", file=sys.stderr)
        return 2
    variants = {}
    for spec in args.variant or [f"this={REPO / 'src'}"]:
        name, _, src = spec.partition("=")
        variants[name] = Path(src).resolve()

    from sgplan.datasets import find_gibson_root
    from tests.planning.gibson_cases import load_case

    root = find_gibson_root()
    rows: list[dict] = []
    print(f"{'case':<28} {'variant':<8} {'status':<13} {'dijk s':>7} {'pops':>8} {'opt s':>7} {'ratio':>6} "
          f"{'1st s':>7} {'expans':>8} {'wall s':>6} {'RSS MB':>6}  cost check")
    t_start = time.perf_counter()
    for scene in args.scenes:
        for mission in args.missions:
            for start in args.starts:
                problem = load_case(root, scene, mission, start)
                # The fastest of 3 runs: the machine is shared, and one slow run would flatter sgplan.
                ref = min((solve(problem) for _ in range(args.repeat)), key=lambda r: r["search_s"])
                del problem
                for setup in args.setups:
                    runs: dict[str, list[dict]] = {variant: [] for variant in variants}
                    for _ in range(args.repeat_sgplan):
                        for variant, src in variants.items():
                            runs[variant].append(run_child(src, scene, mission, start, setup))
                    for variant in variants:
                        row = min(runs[variant], key=lambda r: r.get("opt_s", float("inf")))
                        row.update(
                            variant=variant,
                            scene=scene,
                            mission=mission,
                            start=start,
                            setup=setup,
                            dijkstra_s=ref["search_s"],
                            dijkstra_pops=ref["pops"],
                            dijkstra_cost=ref["cost"],
                        )
                        name = f"{scene} m{mission} s{start} {setup}"
                        if "cost" in row:
                            agree = abs(row["cost"] - ref["cost"]) <= 1e-6
                            row["ratio"] = row["opt_s"] / max(ref["search_s"], 1e-9)
                            print(
                                f"{name:<28} {variant:<8} {row['status']:<13} {ref['search_s']:>7.3f} "
                                f"{ref['pops']:>8} {row['opt_s']:>7.3f} {row['ratio']:>6.2f} "
                                f"{row['first_s']:>7.4f} "
                                f"{row['expansions']:>8} {row['wall_s']:>6.2f} {row['rss_mb']:>6.0f}  "
                                f"{row['cost']:.6f} {'ok' if agree else 'MISMATCH ' + repr(ref['cost'])}",
                                flush=True,
                            )
                        else:
                            agree = ref["cost"] == float("inf") and row["status"] in (
                                "infeasible",
                                "invalid-start",
                            )
                            print(
                                f"{name:<28} {variant:<8} {row['status']:<13} {ref['search_s']:>7.3f} "
                                f"{ref['pops']:>8} {'':>7} {'':>6} {'':>7} {'':>8} {row['wall_s']:>6.2f} "
                                f"{row.get('rss_mb', 0):>6.0f}  {'ok (no path)' if agree else 'MISMATCH'}",
                                flush=True,
                            )
                        row["agree"] = agree
                        rows.append(row)
    summary(rows, list(variants), args.setups)
    bad = [r for r in rows if not r["agree"]]
    print(
        f"\n{len(rows)} runs in {time.perf_counter() - t_start:.0f} s; "
        f"cost disagreements with the reference: {len(bad)}"
    )
    differing = agreement(rows, list(variants), args.setups)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1, default=str))
    return 1 if bad or differing else 0


if __name__ == "__main__":
    sys.exit(main())
