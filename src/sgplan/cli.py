"""The ``sgplan`` command line: parse arguments, call the library, print. No logic of its own.

Each sub-command lives in a module of :mod:`sgplan.commands` with a ``register(subparsers)`` function
that adds its parser and sets ``run`` to a function ``(args) -> exit code``.

Every :class:`~sgplan.errors.SgplanError` is printed as ``sgplan: error: <message>`` and exits with code 2;
``--debug`` shows the traceback instead. ``--debug``, ``--quiet`` and ``--verbose`` go before or after the
sub-command.
"""

from __future__ import annotations

import argparse
import signal
import sys
from collections.abc import Sequence

from sgplan import __version__
from sgplan.commands import REGISTRY
from sgplan.commands.common import add_common_options, configure_logging
from sgplan.errors import SgplanError


def _build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="sgplan",
        description="Optimal scene-graph planning of natural-language missions with LLM guidance.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    add_common_options(parser, top=True)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for register in REGISTRY:
        register(sub)
    for command in sub.choices.values():
        add_common_options(command, top=False)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``sgplan`` console script; returns the process exit code."""
    parser = _build_parser()
    args = parser.parse_args(argv)
    configure_logging(args)
    try:
        return int(args.run(args) or 0)
    except SgplanError as error:
        if args.debug:
            raise
        print(f"sgplan: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as stop:
        print("sgplan: interrupted", file=sys.stderr)
        return 128 + int(getattr(stop, "signum", None) or signal.SIGINT)  # the shell's convention


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
