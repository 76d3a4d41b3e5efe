"""The ``sgplan`` command line: parse arguments, call the library, print. No logic of its own.

Each sub-command lives in a module of :mod:`sgplan.commands` with a ``register(subparsers)`` function
that adds its parser and sets ``run`` to a function ``(args) -> exit code``.

Every :class:`~sgplan.errors.SgplanError` is printed as ``sgplan: error: <message>`` and exits with its
``exit_code`` (2; 4 for a mission that no path in the scene satisfies); ``--debug`` shows the traceback
instead. ``--debug``, ``--quiet`` and ``--verbose`` go before or after the sub-command.
"""

from __future__ import annotations

import argparse
import signal
import sys
from collections.abc import Sequence

from sgplan.commands import REGISTRY
from sgplan.commands.common import add_common_options, configure_logging, holding_draw_folder
from sgplan.errors import SgplanError
from sgplan.runtime.process import exit_now, interrupts_handled, observed, prepare_own_process
from sgplan.version import __version__


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


def main(argv: Sequence[str] | None = None, *, fast_exit: bool | None = None) -> int:
    """Entry point of the ``sgplan`` console script; returns the process exit code.

    ``fast_exit`` (default: when ``argv`` is ``None``, i.e. when run as the console script) says that the
    process is sgplan's own: then it is set up by :func:`prepare_own_process` first, and it ends here
    through :func:`exit_now` instead of returning: every output file is already written atomically and
    closed by then, so only the interpreter's teardown is skipped (:func:`sgplan.runtime.process.exit_now`).
    """
    own_process = (argv is None) if fast_exit is None else fast_exit
    if own_process:
        prepare_own_process()
    code = _run(argv, own_process=own_process)
    if own_process and not observed():
        exit_now(code)
    return code


def _run(argv: Sequence[str] | None, *, own_process: bool) -> int:
    """Run the command of ``argv``; its exit code. A command that sets ``termination_as_interrupt`` in
    its parser's defaults (a sweep, which must stop its workers and export on the way out) treats SIGTERM
    and SIGHUP like Ctrl-C. In sgplan's own process every interrupt is held once the command is over
    (:func:`~sgplan.runtime.process.interrupts_handled`): a signal landing in the exit path changes
    neither the exit code nor the output."""
    parser = _build_parser()
    args = parser.parse_args(argv)
    configure_logging(args)
    if args.command in COMPILING_COMMANDS:
        from sgplan.runtime.jit import announce_compile

        announce_compile()  # before any kernel runs: once one is compiled, the others look cached too
    try:
        termination = getattr(args, "termination_as_interrupt", False)
        with interrupts_handled(termination=termination, hold_after=own_process), holding_draw_folder(args):
            return int(args.run(args) or 0)
    except SgplanError as error:
        if args.debug:
            raise
        print(f"sgplan: error: {error}", file=sys.stderr)
        return error.exit_code
    except BrokenPipeError:  # the reader of stdout left (`sgplan inspect demo | head`): not an error of ours
        _silence_stdout()
        return 128 + signal.SIGPIPE  # what the shell reports for a pipe's writer it stopped
    except KeyboardInterrupt as stop:
        print("sgplan: interrupted", file=sys.stderr)
        return 128 + int(getattr(stop, "signum", None) or signal.SIGINT)  # the shell's convention
    except (Exception, RecursionError, MemoryError) as error:  # a bug, never bad input: exit 70, not 2
        if args.debug:
            raise
        print(_internal_error_line(args, error), file=sys.stderr)
        return INTERNAL_ERROR


COMPILING_COMMANDS = frozenset({"demo", "plan", "simulate", "monitor"})
"""Commands whose first run on a machine compiles the planner's numba kernels (said before it starts)."""

INTERNAL_ERROR = 70
"""Exit code of an unexpected exception (a bug in sgplan): sysexits' EX_SOFTWARE, distinct from 2 (bad input,
SgplanError) and 3 (a search budget ran out)."""


def _silence_stdout() -> None:
    """Point stdout at /dev/null, so that flushing what is left of it at exit raises nothing more."""
    import os

    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)


def _internal_error_line(args: argparse.Namespace, error: BaseException) -> str:
    """One line naming the command, the exception and the inputs, pointing to ``--debug``."""
    from sgplan.safeio import clip

    inputs = [f"{name}={clip(str(value), 60)}" for name, value in sorted(vars(args).items())
              if name in _INPUT_OPTIONS and value not in (None, False)]
    return (
        f"sgplan {args.command}: internal error: {type(error).__name__}: {clip(str(error), 200)} "
        f"(input: {', '.join(inputs) or 'none'}); run with --debug for the traceback, and please report it"
    )


_INPUT_OPTIONS = ("scene", "mission_dir", "formula", "text", "aps", "guidance", "out", "data", "cache",
                  "llm", "llm_config", "start", "start_index", "setup", "missions", "scenes", "starts",
                  "trajectory")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main(fast_exit=True))
