"""Setting up and ending a process that is sgplan's own (the console script, a bench worker), never one
that merely imports sgplan: the choices here are the process owner's."""

from __future__ import annotations

import atexit
import contextlib
import gc
import os
import signal
import sys
from collections.abc import Iterator

GC_YOUNG_THRESHOLD = 300_000
"""Net allocations between two runs of the cyclic garbage collector in sgplan's own processes (Python's
default: 700); see :func:`prepare_own_process`."""


def prepare_own_process() -> None:
    """Set up a process that is sgplan's own.

    - numba skips its BLAS probe (:func:`sgplan.runtime.jit.skip_blas_probe`: no scipy.linalg import).
    - The cyclic garbage collector runs after :data:`GC_YOUNG_THRESHOLD` net allocations instead of 700.
      A plan's garbage is almost all acyclic (numpy arrays, containers: freed by reference counting),
      while numba's registries and the imports create some 10^5-10^6 long-lived objects that every
      collection walks again, so the default spends much of a short plan re-walking them
      (benchmarks/results/runtime.md). The collector still runs, so cyclic garbage stays bounded.
    - glibc returns every large freed array to the system at once
      (:func:`sgplan.runtime.malloc.return_freed_memory_promptly`).
    """
    from sgplan.runtime.jit import skip_blas_probe
    from sgplan.runtime.malloc import return_freed_memory_promptly

    skip_blas_probe()
    return_freed_memory_promptly()
    gc.set_threshold(GC_YOUNG_THRESHOLD, *gc.get_threshold()[1:])


def observed() -> bool:
    """Whether a profiler or tracer (cProfile, coverage, a debugger) runs, which writes its results at the
    interpreter's normal exit: then the process must end normally, not through :func:`exit_now`."""
    return sys.getprofile() is not None or sys.gettrace() is not None


INTERRUPTS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
"""The signals by which a user stops sgplan (Ctrl-C, ``kill``, a closed terminal)."""


def _raise_interrupt(signum: int, frame: object) -> None:
    stop = KeyboardInterrupt()
    stop.signum = signum  # type: ignore[attr-defined]  # the exit status says which signal
    raise stop


def hold_interrupts() -> None:
    """Ignore :data:`INTERRUPTS` for the rest of the process. For the end of a process whose outputs are
    complete, so that a late signal can neither raise in the exit path (a ``KeyboardInterrupt`` inside an
    ``atexit`` handler prints a traceback) nor kill it by its default action (exit -signal).

    The disposition is set (``SIG_IGN``), not the signal mask: a mask is per thread, and the kernel hands
    a signal sent to the process to any thread that does not block it. Main thread only.
    """
    for sig in INTERRUPTS:
        signal.signal(sig, signal.SIG_IGN)


_swallowed: list[KeyboardInterrupt] = []
"""Interrupts raised where Python could not propagate them, kept by :func:`interrupts_handled` for
:func:`raise_swallowed_interrupt`."""


def raise_swallowed_interrupt() -> None:
    """Raise again an interrupt that Python swallowed, if one was (see :func:`interrupts_handled`).

    For loops that must stop on Ctrl-C (a sweep): call it between two steps.
    """
    if _swallowed:
        stop = _swallowed[-1]
        _swallowed.clear()
        raise stop


@contextlib.contextmanager
def interrupts_handled(*, termination: bool, hold_after: bool) -> Iterator[None]:
    """Inside the block, with ``termination``, SIGTERM and SIGHUP raise ``KeyboardInterrupt`` like Ctrl-C
    (with a ``signum`` attribute), so that the caller's cleanup runs and it can exit with 128 + signal.

    A signal that arrives while the garbage collector runs a weakref callback or a ``__del__`` raises its
    ``KeyboardInterrupt`` inside it, where Python cannot propagate it: Python would print "Exception
    ignored in ..." with a traceback and go on as if no one had asked to stop. Inside the block such an
    interrupt is kept silently instead (``sys.unraisablehook``) and raised again at the next
    :func:`raise_swallowed_interrupt`, or at the block's end if the block ends normally.

    With ``hold_after`` (sgplan's own process, which ends right after the block, see :func:`exit_now`)
    the interrupts are ignored from the block's end on (:func:`hold_interrupts`) instead of getting their
    earlier handlers back: a signal arriving between the block's end and the process's end would
    otherwise kill it by its default action or raise where nothing catches it, after every output was
    complete. Without it, the earlier handlers come back.
    """
    previous = {sig: signal.signal(sig, _raise_interrupt) for sig in INTERRUPTS[1:]} if termination else {}
    unraisable_hook = sys.unraisablehook

    def keep_interrupt(unraisable: sys.UnraisableHookArgs) -> None:
        if isinstance(unraisable.exc_value, KeyboardInterrupt):
            _swallowed.append(unraisable.exc_value)
        else:
            unraisable_hook(unraisable)

    sys.unraisablehook = keep_interrupt
    try:
        yield
        raise_swallowed_interrupt()  # the block ended, but someone asked it to stop on the way
    finally:
        sys.unraisablehook = unraisable_hook
        _swallowed.clear()
        if hold_after:
            hold_interrupts()
        else:
            for sig, handler in previous.items():
                signal.signal(sig, handler)


def exit_now(code: int) -> None:
    """End the process with ``code`` at once: hold the interrupts (:func:`hold_interrupts`), run the
    ``atexit`` handlers (logging's flush among them), flush stdout and stderr, then :func:`os._exit`,
    skipping the teardown of modules and objects (freeing numba's compiled code and every imported module
    one by one).
    Only for the end of a process whose outputs are complete (nothing else may be left to run)."""
    hold_interrupts()
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a closed or broken pipe: nothing left to save
            stream.flush()
    os._exit(code)
