"""Score the offline pattern translator on blind mission sets and write the committed score files.

    .venv/bin/python benchmarks/translation_blind.py            # writes
    benchmarks/results/translation_blind.md
    .venv/bin/python benchmarks/translation_blind.py --out -    # print the report instead
    .venv/bin/python benchmarks/translation_blind.py --set benchmarks/data/blind_missions{,_2,_3}.jsonl
                                                                # one line per set: right / wrong / refused

With several sets, each set's report is written beside the others when ``--reports DIR`` is given, and
one table row per set is printed (``--out`` then writes that table).

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
from collections.abc import Callable
from functools import cache
from pathlib import Path

from sgplan import mission_from_formula  # the public one: any source tree has it
from sgplan.datasets import find_gibson_root
from sgplan.errors import SgplanError
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
    """The formula in plain words, or in infix with the reason when it cannot be made a mission (an
    automaton too large to build)."""
    try:
        return explain_mission(mission_from_formula(formula), building).text
    except SgplanError as exc:
        return f"{to_infix(formula)}\n(not explained: {exc})"


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
    parser.add_argument("--set", type=Path, nargs="+", default=[DEFAULT_SET])
    parser.add_argument(
        "--gibson", type=Path, default=None, help="folder holding Allensville/ ... (default: auto)"
    )
    parser.add_argument("--out", default=None,
                        help="the score file to write (one set) or the table (several), or - for stdout")
    parser.add_argument("--reports", type=Path, default=None,
                        help="with several sets: also write each set's report in this folder")
    args = parser.parse_args(argv)
    root = find_gibson_root(args.gibson)

    @cache
    def building_of(scene: str) -> Building:
        if scene == "demo":
            return demo_building()
        if root is None:
            raise SystemExit("the Gibson data is needed for this set (see sgplan.datasets)")
        return load_authors_scene(root / scene)

    if len(args.set) == 1:
        return one_set(args.set[0], args.out or str(DEFAULT_OUT), building_of)
    rows = ["| set | missions | right | wrong | refused |", "|---|---:|---:|---:|---:|"]
    wrong = 0
    for path in args.set:
        score = score_translator(PatternTranslator(), load_jsonl_set(path), building_of,
                                 set_path=str(path), explain=explain)
        if args.reports is not None:
            out = args.reports / f"translation_{path.stem.replace('_missions', '')}.md"
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_text(report(score, path.resolve(), str(out)), encoding="utf-8")
        c = score.counts
        rows.append(f"| `{path.name}` | {len(score.results)} | {c['right']} | {c['wrong']} | "
                    f"{c['refused']} |")
        wrong += c["wrong"]
    table = "\n".join(rows) + "\n"
    if args.out in (None, "-"):
        print(table, end="")
    else:
        Path(args.out).write_text(table, encoding="utf-8")
    return 1 if wrong else 0


def one_set(path: Path, out_arg: str, building_of: Callable[[str], Building]) -> int:
    """Score one set and write (or print, ``-``) its report."""
    missions = load_jsonl_set(path)
    started = time.perf_counter()
    score = score_translator(PatternTranslator(), missions, building_of, set_path=str(path), explain=explain)
    seconds = time.perf_counter() - started
    out = Path(out_arg).resolve()
    text = report(score, path.resolve(), out_arg if out_arg == "-" or not out.is_relative_to(REPO)
                  else str(out.relative_to(REPO)))
    if out_arg == "-":
        print(text, end="")
        return 1 if score.counts["wrong"] else 0
    Path(out_arg).parent.mkdir(parents=True, exist_ok=True)
    Path(out_arg).write_text(text, encoding="utf-8")
    counts = score.counts
    print(f"right {counts['right']}/{len(score.results)}, wrong {counts['wrong']}, "
          f"refused {counts['refused']}; ({seconds:.1f} s); wrote {out_arg}")
    return 1 if counts["wrong"] else 0


if __name__ == "__main__":
    sys.exit(main())
