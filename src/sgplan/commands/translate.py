"""``sgplan translate``: a natural-language mission -> grounded formula -> automaton, saved as a mission
folder.

The language backend is ``--llm openai:MODEL`` (any OpenAI-compatible server; ``--base-url``, ``--cache``,
``--replay``) or ``--llm offline`` (the pattern translator, not a language model; the default). When the
mission cannot be translated as written (an ambiguous or unknown reference, no valid formula after the
repairs) and the terminal is interactive, the user is asked to rephrase it (an empty line or the end of
input gives up); otherwise the error ends the command (exit code 2).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from sgplan.commands.common import (
    add_scene_arguments,
    load_scene_arg,
    non_negative_int,
    positive_int,
    positive_number,
    positive_seconds,
    say,
)
from sgplan.commands.sayback import check_before_planning, say_back
from sgplan.english import count
from sgplan.errors import MissionError

if TYPE_CHECKING:
    from sgplan.llm.backends import Backends


def add_llm_arguments(parser: argparse.ArgumentParser, *, translates: bool = True) -> None:
    """The options choosing the language backend, the same on every command that talks to one
    (``translate``, ``guide``, ``plan``); ``translates`` adds the translation options."""
    group = parser.add_argument_group("language backend")
    group.add_argument(
        "--llm",
        default="offline",
        metavar="SPEC",
        help="'openai:MODEL' for any OpenAI-compatible server, or 'offline' for the rule-based "
        "backends, which are not language models (default: offline)",
    )
    group.add_argument("--base-url", metavar="URL",
                       help="API root of the server, e.g. http://127.0.0.1:11434/v1 (default: OpenAI's, or "
                            "$OPENAI_BASE_URL)")
    group.add_argument("--llm-config", metavar="FILE", help="YAML file with LLM settings (see docs/llm.md)")
    group.add_argument(
        "--cache", metavar="DIR", help="record every LLM call in DIR and answer recorded calls from it"
    )
    group.add_argument(
        "--replay", action="store_true", help="answer only from --cache, never contact a server"
    )
    group.add_argument("--llm-deadline", type=positive_seconds, metavar="S",
                       help="give up on one LLM call (all its retries included) after S seconds "
                            "(default: deadline_s of the LLM config, 120)")
    group.add_argument(
        "--rpm", type=positive_number, metavar="R", help="at most R LLM requests per minute (hosted APIs)"
    )
    if translates:
        group.add_argument(
            "--samples", type=positive_int, default=1, metavar="K",
            help="translate K times and keep the majority by automaton equivalence (default 1)",
        )
        group.add_argument(
            "--max-repairs", type=non_negative_int, default=3, metavar="N",
            help="times an invalid formula is sent back for repair before giving up (default 3)",
        )


def open_backends_from_args(args: argparse.Namespace, **options: Any) -> Backends:
    """:func:`sgplan.llm.backends.open_backends` for the options of :func:`add_llm_arguments`."""
    from sgplan.llm.backends import open_backends

    if getattr(args, "samples", None) is not None:
        options.setdefault("samples", args.samples)
        options.setdefault("max_repairs", args.max_repairs)
    return open_backends(
        args.llm, base_url=args.base_url, cache_dir=args.cache, replay=args.replay,
        config_path=args.llm_config, requests_per_minute=args.rpm, deadline_s=args.llm_deadline, **options,
    )


def backend_note(backends: Backends) -> str:
    """What answers, for progress lines: ``offline, not a language model`` or ``language model M``."""
    return "offline, not a language model" if backends.chat is None else backends.description


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "translate", help="translate a natural-language mission into a mission folder",
        description="Translate a mission in English into a mission folder (formula, automaton, propositions; "
        "with a language model, its record too), said back in words first. --llm offline (the default) is "
        "sgplan's rule-based translator, which refuses what it cannot read with certainty. Exit codes: 0 "
        "written, 2 an error or a refusal (the reason is printed), 70 a bug.",
    )
    add_scene_arguments(parser)
    parser.add_argument("--text", required=True, help="the mission in natural language")
    parser.add_argument("--out", required=True, metavar="MISSION_DIR",
                        help="mission folder to write (the authors' layout plus llm_record.json)")
    add_llm_arguments(parser)
    parser.set_defaults(run=run)


def _rephrased(ask: Callable[[str], str]) -> str:
    """The user's rephrased mission, or ``""`` to give up (an empty line, or stdin closed)."""
    try:
        return ask("Rephrase the mission (empty line to give up): ").strip()
    except EOFError:
        return ""


def run(args: argparse.Namespace, ask: Callable[[str], str] | None = None) -> int:
    """Translate and save; ``ask`` prompts for a rephrased mission (default: ``input`` on a terminal)."""
    from sgplan.llm.translation import translate_to_folder
    from sgplan.logic import to_infix

    if not args.text.strip():
        raise MissionError("--text is empty: give the mission in natural language")
    building = load_scene_arg(args.scene, args.data)
    backends = open_backends_from_args(args)
    say(f"translating with {backends.translator.name} ({backend_note(backends)})")
    if ask is None and sys.stdin.isatty() and sys.stderr.isatty():
        ask = input
    text = args.text
    while True:
        try:
            translation, mission = translate_to_folder(
                text, building, backends.translator, args.out, backends.record
            )
            break
        except MissionError as error:
            # An error naming a file (the --out folder) is not about the wording: rephrasing cannot fix it.
            if ask is None or error.path is not None:
                raise
            say(f"sgplan: the mission cannot be translated as written: {error}")
            text = _rephrased(ask)
            if not text:
                raise
    print(f"grounded: {translation.grounded_text}")
    print(f"tokens:   {list(translation.tokens)}")
    print(f"formula:  {to_infix(translation.formula)}")
    for warning in getattr(translation, "warnings", ()):
        print(f"warning:  {warning}")
    print(f"automaton: {count(mission.automaton.num_states, 'state')} over "
          f"{count(len(mission.automaton.aps), 'proposition')}")
    say_back(mission, building)
    check_before_planning(mission, building, stop=False)
    summary = backends.record.to_json()["summary"]
    if backends.chat is not None:
        say(f"{summary['calls']} LLM calls ({summary['from_cache']} from the cache)")
    print(f"wrote the mission folder {args.out} (backend {translation.backend})")
    return 0
