"""Score the offline pattern translator on the blind mission set and write the committed score file.

    .venv/bin/python benchmarks/translation_blind.py            # writes
    benchmarks/results/translation_blind.md
    .venv/bin/python benchmarks/translation_blind.py --out -    # print the report instead

The set (benchmarks/data/blind_missions.jsonl, described in benchmarks/data/README_blind.md) was written
by someone who had read neither the translator's code nor docs/offline.md; it is a held-out test, not a
list of phrases to tune to. Scoring is the library's (:func:`sgplan.llm.evaluate.score_translator`, the
code behind ``sgplan eval-translation``): right = the same automaton as the gold under the scene's facts,
refused = a MissionError with a reason, wrong = a formula that does not mean the mission. The report
lists every wrong and every refused mission. Exit status 1 if any translation is wrong. Needs the Gibson
data for the three Gibson scenes (see sgplan.datasets).
"""

from __future__ import annotations

import argparse
import sys
import time
from functools import cache
from pathlib import Path

from sgplan import mission_from_formula  # the public one: any source tree has it
from sgplan.datasets import find_gibson_root
from sgplan.explain import explain_mission
from sgplan.llm.evaluate import TranslationScore, load_jsonl_set, score_translator
from sgplan.llm.offline import PatternTranslator
from sgplan.logic import Formula, to_infix
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.demo import demo_building
from sgplan.scene.model import Building

REPO = Path(__file__).resolve().parents[1]
DEFAULT_SET = REPO / "benchmarks" / "data" / "blind_missions.jsonl"
DEFAULT_OUT = REPO / "benchmarks" / "results" / "translation_blind.md"


def explain(formula: Formula, building: Building) -> str:
    return explain_mission(mission_from_formula(formula), building).text


def report(score: TranslationScore, set_path: Path, out_name: str) -> str:
    """The score file: counts, then every wrong mission (gold and translation in words and in infix),
    then every refused one with its reason; ``out_name`` is where it is written (for the reproduce line)."""
    counts, total = score.counts, len(score.results)
    shown = set_path.relative_to(REPO) if set_path.is_relative_to(REPO) else set_path
    lines = [
        "# Offline translator on the blind mission set",
        "",
        f"Set: `{shown}` ({total} missions). Backend: `{score.backend}`. Reproduce: `.venv/bin/python "
        f"benchmarks/translation_blind.py --set {shown} --out {out_name}`.",
        "",
        "| outcome | missions | share |",
        "|---|---:|---:|",
        *(
            f"| {k} | {counts[k]} | {100.0 * counts[k] / total:.1f} % |"
            for k in ("right", "wrong", "refused")
        ),
        "",
        f"## Wrong ({counts['wrong']})",
        "",
    ]
    for r in score.results:
        if r.outcome != "wrong":
            continue
        lines += [f"- **{r.mission.id}** ({r.mission.scene}): {r.mission.text}"]
        if r.mission.gold is not None:
            lines += [f"  - gold: `{to_infix(r.mission.gold)}`"]
        if r.formula is not None:
            lines += [f"  - got: `{to_infix(r.formula)}`"]
        lines += [f"  - {r.detail.split('; ', 1)[-1]}"]
        if r.mission.id in score.explanations:
            gold, got = score.explanations[r.mission.id]
            lines += ["", "  ```", "  expected:", *(f"    {x}" for x in gold.splitlines()),
                      "  got:", *(f"    {x}" for x in got.splitlines()), "  ```"]
    lines += ["", f"## Refused ({counts['refused']})", ""]
    lines += [f"- **{r.mission.id}** ({r.mission.scene}): {r.mission.text}\n  - {r.detail}"
              for r in score.results if r.outcome == "refused"]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--set", type=Path, default=DEFAULT_SET)
    parser.add_argument(
        "--gibson", type=Path, default=None, help="folder holding Allensville/ ... (default: auto)"
    )
    parser.add_argument("--out", default=str(DEFAULT_OUT), help="the score file to write, or - for stdout")
    args = parser.parse_args(argv)

    root = find_gibson_root(args.gibson)

    @cache
    def building_of(scene: str) -> Building:
        if scene == "demo":
            return demo_building()
        if root is None:
            raise SystemExit("the Gibson data is needed for this set (see sgplan.datasets)")
        return load_authors_scene(root / scene)

    missions = load_jsonl_set(args.set)
    started = time.perf_counter()
    score = score_translator(
        PatternTranslator(), missions, building_of, set_path=str(args.set), explain=explain
    )
    seconds = time.perf_counter() - started
    out = Path(args.out).resolve()
    text = report(score, args.set.resolve(), args.out if args.out == "-" or not out.is_relative_to(REPO)
                  else str(out.relative_to(REPO)))
    if args.out == "-":
        print(text, end="")
    else:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text(text, encoding="utf-8")
        counts = score.counts
        print(
            f"right {counts['right']}/{len(score.results)}, wrong {counts['wrong']}, refused "
            f"{counts['refused']}; "
            f"({seconds:.1f} s); wrote {args.out}"
        )
    return 1 if score.counts["wrong"] else 0


if __name__ == "__main__":
    sys.exit(main())
