"""``sgplan eval-translation``: score a language backend on your own missions with gold formulas.

Each mission of the JSONL set (format in :mod:`sgplan.llm.evaluate`) is translated by the backend of
``--llm`` (``offline`` or ``openai:MODEL`` with ``--cache`` / ``--replay``) over its scene, and compared
with its gold formula by automaton equivalence under the scene's facts. The command prints the refused
and the wrong missions (for a wrong one: what the gold and the translation each ask, one under the
other, and a shortest path on which they disagree), then the counts. Exit status 0 when nothing is
wrong, 1 when some translation is wrong (a mission silently misread), 2 on an error.
"""

from __future__ import annotations

import argparse
import json
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

from sgplan.commands.common import load_scene_arg, say
from sgplan.commands.translate import add_llm_arguments, open_backends_from_args
from sgplan.english import count

if TYPE_CHECKING:
    from sgplan.logic import Formula
    from sgplan.scene.model import Building


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "eval-translation", help="score a language backend on a JSONL set of missions with gold formulas",
        description="Score a translation backend on missions with gold formulas: each translation is right "
        "(the same language under the scene's facts), wrong, or refused. Exit codes: 0 no wrong "
        "translation, 1 some translation wrong, 2 an error, 70 a bug.",
    )
    parser.add_argument("--set", required=True, metavar="FILE.jsonl",
                        help="missions, one JSON object per line: id, scene, text, formula (see docs/llm.md)")
    parser.add_argument(
        "--data",
        metavar="DIR",
        default=None,
        help="folder holding the Gibson scenes named by the set (default: $SGPLAN_GIBSON_DIR, "
        "else ../shared/datasets/gibson-3dsg)",
    )
    parser.add_argument("--json", metavar="FILE", help="also write the full report (every mission) as JSON")
    parser.add_argument("--show-right", action="store_true", help="also list the missions translated right")
    add_llm_arguments(parser)  # with --samples / --max-repairs
    parser.set_defaults(run=run)


def _indented(label: str, text: str) -> str:
    pad = " " * (len(label) + 1)
    lines = text.splitlines() or [""]
    return "\n".join([f"    {label} {lines[0]}", *(f"    {pad}{line}" for line in lines[1:])])


def _explain(formula: Formula, building: Building) -> str:
    """What a formula asks in plain words over the scene (:func:`sgplan.explain.explain_mission`)."""
    from sgplan.explain import explain_mission
    from sgplan.mission import compile_mission

    return explain_mission(compile_mission(formula), building).text


def run(args: argparse.Namespace) -> int:
    from sgplan.llm.evaluate import load_jsonl_set, score_translator

    missions = load_jsonl_set(args.set)
    backends = open_backends_from_args(args)

    @cache
    def building_of(scene: str) -> Building:
        return load_scene_arg(scene, args.data)

    say(
        f"scoring {backends.translator.name} ({backends.description}) on "
        f"{count(len(missions), 'mission')} of {args.set}"
    )
    score = score_translator(
        backends.translator, missions, building_of, set_path=str(args.set), explain=_explain
    )
    for r in score.results:
        if r.outcome == "right" and not args.show_right:
            continue
        print(f"[{r.outcome}] {r.mission.id} ({r.mission.scene}): {r.mission.text}")
        if r.mission.id in score.explanations:
            gold, got = score.explanations[r.mission.id]
            print(_indented("expected:", gold))
            print(_indented("got:     ", got))
            print(f"    {r.detail.split('; ', 1)[-1]}")
        elif r.outcome != "right":
            print(f"    {r.detail}")
    counts, total = score.counts, len(score.results)
    print(f"right {counts['right']}/{total} ({100.0 * counts['right'] / total:.1f}%), "
          f"wrong {counts['wrong']}, refused {counts['refused']}  [{score.backend}]")
    if backends.chat is not None:
        summary = backends.record.to_json()["summary"]
        say(f"{summary['calls']} LLM calls ({summary['from_cache']} from the cache)")
    if args.json:
        Path(args.json).write_text(json.dumps(score.to_dict(), indent=2) + "\n", encoding="utf-8")
        say(f"wrote the report {args.json}")
    return 1 if counts["wrong"] else 0
