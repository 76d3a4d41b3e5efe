"""``sgplan guide``: room-level guidance (llm_heuristic.yaml) for a mission folder.

``--llm openai:MODEL`` asks a language model for every room x automaton state and keeps only the calls
that the scene graph allows; ``--llm offline`` (the default) uses the symbolic guide, which is not a
language model. The run record of the LLM calls goes beside the output (``llm_guidance_record.json``).
"""

from __future__ import annotations

import argparse
import contextlib
from pathlib import Path

from sgplan.commands.common import (
    add_profile_argument,
    add_scene_arguments,
    load_scene_arg,
    plan_options,
    positive_int,
    say,
)
from sgplan.commands.translate import add_llm_arguments, backend_note, open_backends_from_args
from sgplan.english import count


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "guide", help="write room-level guidance (llm_heuristic.yaml) for a mission folder",
        description="Write the guidance the LLM-guided setups read (ALL, OCC, OBJ, ROOM, FLR; "
        "llm_heuristic.yaml: per room and automaton state, the move/reach calls suggested) for a mission "
        "folder, from a language model or offline. Exit codes: 0 written, 2 an error, 70 a bug.",
    )
    add_scene_arguments(parser)
    parser.add_argument(
        "--mission-dir", required=True, metavar="DIR", help="mission folder (automaton.aut, ap_desc.yaml)"
    )
    parser.add_argument("--out", metavar="FILE", help="where to write (default: DIR/llm_heuristic.yaml)")
    add_profile_argument(parser, extra_help="; here: how automaton.aut's missing edges are read")
    add_llm_arguments(parser, translates=False)
    parser.add_argument(
        "--max-concurrency", type=positive_int, default=4, metavar="N", help="LLM calls in flight (default 4)"
    )
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from sgplan.errors import LLMError
    from sgplan.llm.translation import GUIDANCE_RECORD_NAME
    from sgplan.mission import load_mission_folder, write_guidance

    building = load_scene_arg(args.scene, args.data)
    mission = load_mission_folder(args.mission_dir, profile=plan_options(args).profile, guidance=False)
    mission.check_scene(building)
    options: dict[str, object] = {}
    if args.llm != "offline":
        options.update(max_concurrency=args.max_concurrency, mission_text=mission.grounded_text)
    backends = open_backends_from_args(args, **options)
    say(f"guidance from {backends.guide.name} ({backend_note(backends)})")
    out = Path(args.out) if args.out else Path(args.mission_dir) / "llm_heuristic.yaml"
    try:
        guidance = backends.guide.guide(building, mission.automaton, mission.descriptions)
    except LLMError:
        if backends.chat is not None:  # every call failed: keep the record of what was tried
            with contextlib.suppress(LLMError):  # but never in place of the real error
                say(f"wrote the LLM run record {backends.record.save(out.parent / GUIDANCE_RECORD_NAME)}")
        raise
    write_guidance(guidance, out)
    entries = sum(len(states) for states in guidance.values())
    print(
        f"wrote {out}: {count(entries, 'entry', 'entries')} for {count(len(guidance), 'room')} x "
        f"{count(mission.automaton.num_states, 'automaton state')}"
    )
    report = getattr(backends.guide, "report", None)
    if backends.chat is not None and report is not None:
        summary = backends.record.to_json()["summary"]
        print(
            f"LLM: {report.asked} entries asked ({summary['from_cache']} from the cache), {report.skipped} "
            "with "
            f"nothing left to do, {report.failed} failed; calls kept {report.calls_kept}, dropped "
            f"{report.calls_dropped}; "
            f"{report.routes_broken} entries whose calls do not form one route"
        )
        for reason in report.reasons[:5]:
            say(f"  dropped: {reason}")
        record_path = backends.record.save(out.parent / GUIDANCE_RECORD_NAME)
        print(f"wrote the LLM run record {record_path}")
    return 0
