"""Score the offline pattern translator on its pattern set (tests/llm/offline/sets/pattern_missions.jsonl).

Usage: python benchmarks/pattern_translator_score.py [--set PATH] [--gibson DIR] [--verbose]

Missions over Gibson scenes are skipped (and said so) when the data is not found. Prints one line per
mission that is not right (refused = a MissionError where a formula was expected; wrong = a formula not
equivalent to the gold, or a wrong error), then the score overall, on must-pass missions and on the 15
shipped paper missions. Exit status 1 if any translation is silently wrong.
"""

from __future__ import annotations

import argparse
import sys
import time
from functools import cache
from pathlib import Path

from sgplan.datasets import find_gibson_root
from sgplan.llm.evaluate import load_jsonl_set
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.evaluation import evaluate
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.demo import demo_building
from sgplan.scene.model import Building

DEFAULT_SET = Path(__file__).resolve().parents[1] / "tests/llm/offline/sets/pattern_missions.jsonl"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--set", type=Path, default=DEFAULT_SET)
    parser.add_argument(
        "--gibson", type=Path, default=None, help="folder holding Allensville/ ... (default: auto)"
    )
    parser.add_argument("--verbose", action="store_true", help="also print the right ones")
    args = parser.parse_args(argv)

    root = find_gibson_root(args.gibson)

    @cache
    def building_of(scene: str) -> Building:
        if scene == "demo":
            return demo_building()
        assert root is not None
        return load_authors_scene(root / scene)

    missions = load_jsonl_set(args.set)
    usable = [m for m in missions if m.scene == "demo" or root is not None]
    if len(usable) < len(missions):
        print(f"Gibson data not found: skipping {len(missions) - len(usable)} missions over Gibson scenes")
    started = time.perf_counter()
    results = evaluate(PatternTranslator(), usable, building_of)
    elapsed = time.perf_counter() - started
    for r in results:
        if r.outcome != "right" or args.verbose:
            flag = " (must pass)" if r.mission.must_pass and r.outcome != "right" else ""
            print(f"[{r.outcome}]{flag} {r.mission.id}: {r.mission.text}\n    {r.detail}")

    def line(label: str, subset: list) -> str:
        right = sum(r.outcome == "right" for r in subset)
        refused = sum(r.outcome == "refused" for r in subset)
        wrong = sum(r.outcome == "wrong" for r in subset)
        pct = 100.0 * right / len(subset) if subset else float("nan")
        return (
            f"{label:<22} {right:>3}/{len(subset):<3} right ({pct:5.1f}%), {refused} refused, {wrong} wrong"
        )

    print()
    print(line("all missions", results))
    print(line("must-pass missions", [r for r in results if r.mission.must_pass]))
    print(line("shipped paper missions", [r for r in results if r.mission.paper]))
    print(f"{len(results)} missions translated and checked in {elapsed:.2f} s")
    return 1 if any(r.outcome == "wrong" for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())
