"""The ``sgplan`` command line: parse arguments, call the library, print. No logic of its own.

Each sub-command lives in a module of :mod:`sgplan.commands` with a ``register(subparsers)`` function
that adds its parser and sets ``run`` to a function ``(args) -> exit code``.

Every :class:`~sgplan.errors.SgplanError` is printed as ``sgplan: error: <message>`` and exits with its
``exit_code`` (2; 4 for a mission that no path in the scene satisfies); ``--debug`` shows the traceback
instead. ``--debug``, ``--quiet`` and ``--verbose`` go before or after the sub-command.
"""

from __future__ import annotations

import argparse
import atexit
import contextlib
import gc
import os
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


def main(argv: Sequence[str] | None = None, *, fast_exit: bool | None = None) -> int:
    """Entry point of the ``sgplan`` console script; returns the process exit code.

    ``fast_exit`` (default: when ``argv`` is ``None``, i.e. when run as the console script) says that the
    process is sgplan's own: then it is set up by :func:`prepare_own_process` first, and it ends here
    through :func:`exit_now` instead of returning: every output file is already written atomically and
    closed by then, so only the interpreter's teardown is skipped (0.3-0.8 s after a plan: freeing numba's
    compiled code and every imported module one by one).
    """
    own_process = (argv is None) if fast_exit is None else fast_exit
    if own_process:
        prepare_own_process()
    code = _run(argv)
    if own_process and not _observed():
        exit_now(code)
    return code


GC_YOUNG_THRESHOLD = 300_000
"""Net allocations between two runs of the cyclic garbage collector in sgplan's own processes (Python's
default: 700); see :func:`prepare_own_process`."""


def prepare_own_process() -> None:
    """Set up a process that is sgplan's own (the console script, a bench worker), never one that merely
    imports sgplan: the choices below are the process owner's.

    - numba skips its BLAS probe (:func:`sgplan.jit.skip_blas_probe`: no scipy.linalg import, 0.1-0.25 s).
    - The cyclic garbage collector runs after :data:`GC_YOUNG_THRESHOLD` net allocations instead of 700.
      A plan's garbage is almost all acyclic (numpy arrays, containers: freed by reference counting),
      while numba's registries and the imports create some 10^5-10^6 long-lived objects that every
      collection walks again: with the default, a plan spent 60-110 ms in ~260 collections that freed
      ~2,000 objects (at 100,000: ~20 collections, ~35 ms; at 300,000: ~2, ~10 ms). The collector still
      runs, so cyclic garbage stays bounded (a plan leaves ~35,000 objects, a few MB, uncollected).
    - glibc returns every freed array of 4 MiB or more to the system at once
      (:func:`sgplan.malloc.return_freed_memory_promptly`: 12-22 MB less peak RSS on the large plans).
    """
    from sgplan.jit import skip_blas_probe
    from sgplan.malloc import return_freed_memory_promptly

    skip_blas_probe()
    return_freed_memory_promptly()
    gc.set_threshold(GC_YOUNG_THRESHOLD, *gc.get_threshold()[1:])


def _observed() -> bool:
    """Whether a profiler or tracer (cProfile, coverage, a debugger) runs, which writes its results at the
    interpreter's normal exit: then the process ends normally."""
    return sys.getprofile() is not None or sys.gettrace() is not None


def exit_now(code: int) -> None:
    """End the process with ``code`` at once: run the ``atexit`` handlers (logging's flush among them),
    flush stdout and stderr, then :func:`os._exit`, skipping the teardown of modules and objects.
    Only for the end of a process whose outputs are complete (nothing else may be left to run)."""
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a closed or broken pipe: nothing left to save
            stream.flush()
    os._exit(code)


def _run(argv: Sequence[str] | None) -> int:
    parser = _build_parser()
    args = parser.parse_args(argv)
    configure_logging(args)
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
    except (Exception, RecursionError, MemoryError) as error:  # a bug, never bad input: exit 70, not 2
        if args.debug:
            raise
        print(_internal_error_line(args, error), file=sys.stderr)
        return INTERNAL_ERROR


INTERNAL_ERROR = 70
"""Exit code of an unexpected exception (a bug in sgplan): sysexits' EX_SOFTWARE, distinct from 2 (bad input,
SgplanError) and 3 (a search budget ran out)."""


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
