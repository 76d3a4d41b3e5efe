"""The ``sgplan`` command line: parse arguments, call the library, print. No logic of its own.

Each sub-command lives in a module of :mod:`sgplan.commands` with a ``register(subparsers)`` function
that adds its parser and sets ``run`` to a function ``(args) -> exit code``.

Every :class:`~sgplan.errors.SgplanError` is printed as ``sgplan: error: <message>`` and exits with its
``exit_code`` (2; 3 for a mission that no path in the scene satisfies);
``--debug`` shows the traceback instead.
"""

from __future__ import annotations

import argparse
import signal
import sys
from collections.abc import Sequence

from sgplan.commands import REGISTRY
from sgplan.errors import SgplanError

def _build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="sgplan",
        description="Optimal scene-graph planning of natural-language missions with LLM guidance.",
    )
    parser.add_argument("--debug", action="store_true", help="show tracebacks for sgplan errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for register in REGISTRY:
        register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``sgplan`` console script; returns the process exit code."""
    parser = _build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.run(args) or 0)
    except SgplanError as error:
        if args.debug:
            raise
        print(f"sgplan: error: {error}", file=sys.stderr)
        return error.exit_code
    except KeyboardInterrupt as stop:
        print("sgplan: interrupted", file=sys.stderr)
        return 128 + int(getattr(stop, "signum", None) or signal.SIGINT)  # the shell's convention


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
