"""Run the sgplan CLI on one damaged input and classify what happened.

Outcomes (what issue 14 counts):

``clean``
    exit 0 (the input happened to be valid and ``must_fail`` is off), exit 3 (a search budget ran out), or
    exit 2 (bad input) or 4 (no path satisfies the mission) with one ``... error: ...`` line last on stderr
    and no traceback;
``traceback``
    an exception escaped (in-process), a ``Traceback`` on stderr, or the internal-error exit code (70);
``hang``
    no exit within the time budget;
``crash``
    killed by a signal (a segfault, the memory limit) or an exit code other than 0, 2, 3, 4;
``accepted``
    a must-fail input that exited 0;
``data-loss``
    an earlier output (``survivors``) changed or vanished.

Cases run in this process (fast) unless they need a subprocess (resource limits, signals, a user id).
Two environment variables turn the suite into a measurement:

``SGPLAN_FAULTS_RECORD=FILE``
    append each case's outcome to FILE (JSON lines) instead of asserting, and run every case in a
    subprocess under a memory limit, so a crash or a hang of the code under test cannot stop the run;
``SGPLAN_FAULTS_SCALE=K``
    run K times as many generated examples (the heavier variant, benchmarks/faults_slow.py);
``SGPLAN_FAULTS_PYTHONPATH=DIR``
    the ``src`` folder whose sgplan the subprocesses import (e.g. an older checkout, to count its
    outcomes); by default the subprocesses import the sgplan under test.
"""

from __future__ import annotations

import contextlib
import ctypes
import hashlib
import io
import json
import os
import resource
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from hypothesis import HealthCheck, settings

from sgplan.cli import INTERNAL_ERROR
from sgplan.commands.plan import TIMEOUT_EXIT
from sgplan.errors import SgplanError, UnsatisfiableMissionError

CLEAN_EXITS = (0, SgplanError.exit_code, TIMEOUT_EXIT, UnsatisfiableMissionError.exit_code)
"""Exit codes of a run that ended as designed: done, bad input, a budget ran out, an unsatisfiable mission."""

RECORD = os.environ.get("SGPLAN_FAULTS_RECORD")
PYTHONPATH = os.environ.get("SGPLAN_FAULTS_PYTHONPATH")
TIME_BUDGET_S = float(os.environ.get("SGPLAN_FAULTS_TIME_BUDGET", "30"))
"""Wall seconds a case may take (generous: the CI machine is shared); beyond it the case is a hang."""
MEMORY_LIMIT_BYTES = 3 * 2**30
"""Address-space limit of a subprocess case (numba and numpy reserve ~1 GB of it at start)."""

EXAMPLES_SCALE = float(os.environ.get("SGPLAN_FAULTS_SCALE", "1"))
"""Multiplies every generated test's example count (benchmarks/faults_slow.py raises it)."""


def generated(examples: int) -> settings:
    """Hypothesis settings of a generated fault test: ``examples`` (scaled) fixed examples, the same on
    every run (derandomized, no example database), so that two versions of sgplan meet the same cases."""
    return settings(
        max_examples=max(1, round(examples * EXAMPLES_SCALE)), deadline=None, derandomize=True, database=None,
        suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
    )


_BOOT = "import sys\nfrom sgplan.cli import main\nsys.exit(main(sys.argv[1:]))"


@dataclass
class Run:
    """What one CLI run did. ``code`` is the exit code, ``None`` for a hang, negative for a signal."""

    code: int | None
    stdout: str
    stderr: str
    wall_s: float
    escaped: str | None = None
    """In-process only: the type and message of an exception that escaped ``main``."""


class _Hang(BaseException):
    """Raised by the in-process alarm; a BaseException so that no ``except Exception`` swallows it."""


def run_cli(
    argv: Sequence[str],
    *,
    subprocess_only: bool = False,
    rlimits: Mapping[int, int] | None = None,
    env: Mapping[str, str] | None = None,
    unprivileged: bool = False,
    timeout_s: float = TIME_BUDGET_S,
) -> Run:
    """Run ``sgplan argv``; in this process unless a subprocess is needed or the suite is recording."""
    if subprocess_only or RECORD or rlimits or env or unprivileged:
        return _run_subprocess(argv, rlimits or {}, env or {}, unprivileged, timeout_s)
    return _run_inprocess(argv, timeout_s)


def _run_inprocess(argv: Sequence[str], timeout_s: float) -> Run:
    from sgplan.cli import main

    out, err = io.StringIO(), io.StringIO()

    def alarm(signum: int, frame: object) -> None:
        raise _Hang

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout_s)
    started = time.monotonic()
    code: int | None
    escaped = None
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = main(list(argv))
            except SystemExit as stop:  # argparse
                code = stop.code if isinstance(stop.code, int) else 2
    except _Hang:
        code = None
    except BaseException as error:  # noqa: BLE001 - the outcome under test
        code, escaped = 1, f"{type(error).__name__}: {str(error)[:200]}"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    return Run(code, out.getvalue(), err.getvalue(), time.monotonic() - started, escaped)


def _run_subprocess(
    argv: Sequence[str], rlimits: Mapping[int, int], env: Mapping[str, str], unprivileged: bool,
    timeout_s: float,
) -> Run:
    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT_BYTES, MEMORY_LIMIT_BYTES))
        for kind, value in rlimits.items():
            resource.setrlimit(kind, (value, value))
        # A write past RLIMIT_FSIZE then fails with EFBIG (a full disk) instead of killing the process.
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        if unprivileged:
            drop_file_permission_override()

    full_env = {**os.environ, **env}
    if PYTHONPATH:
        full_env["PYTHONPATH"] = PYTHONPATH
    started = time.monotonic()
    proc = subprocess.Popen(
        [sys.executable, "-c", _BOOT, *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        preexec_fn=limit, env=full_env, text=True, errors="replace", start_new_session=True,
    )
    try:
        stdout, stderr = proc.communicate(timeout=timeout_s)
        code: int | None = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        stdout, stderr = proc.communicate()
        code = None
    return Run(code, stdout, stderr, time.monotonic() - started)


_PR_CAPBSET_DROP = 24
_CAP_DAC_OVERRIDE, _CAP_DAC_READ_SEARCH = 1, 2


def drop_file_permission_override() -> None:
    """Make this process (and what it executes) obey file permissions even as root.

    Drops CAP_DAC_OVERRIDE and CAP_DAC_READ_SEARCH from the capability bounding set, so that a mode-000
    file is unreadable as it would be for any user (switching to another user id is no option here: the
    interpreter may live under root's home). Raises OSError where the system does not allow it.
    """
    libc = ctypes.CDLL(None, use_errno=True)
    for capability in (_CAP_DAC_OVERRIDE, _CAP_DAC_READ_SEARCH):
        if libc.prctl(_PR_CAPBSET_DROP, capability, 0, 0, 0) != 0:
            errno = ctypes.get_errno()
            raise OSError(errno, os.strerror(errno))


def can_drop_file_permission_override() -> bool:
    """Whether :func:`drop_file_permission_override` works here (root with CAP_SETPCAP, on Linux)."""
    try:
        result = subprocess.run([sys.executable, "-c", "pass"], preexec_fn=drop_file_permission_override,
                                capture_output=True, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return False
    return result.returncode == 0


def classify(run: Run, *, must_fail: bool = False) -> str:
    """The outcome of ``run`` (see the module docstring); data loss is checked by :func:`check`."""
    if run.code is None or run.wall_s > TIME_BUDGET_S:
        return "hang"
    if run.escaped is not None or "Traceback" in run.stderr or run.code == INTERNAL_ERROR:
        return "traceback"
    if run.code < 0 or run.code not in CLEAN_EXITS:
        return "crash"
    if run.code == 0:
        return "accepted" if must_fail else "clean"
    if run.code == 3:  # a search budget ran out: the best path so far is written, no error
        return "clean"
    last = run.stderr.strip().splitlines()[-1] if run.stderr.strip() else ""
    return "clean" if "error:" in last else "traceback"


def snapshot(paths: Sequence[Path]) -> dict[str, str | None]:
    """A digest of every file under ``paths`` (``None`` for a missing path), to compare after a run."""
    digests: dict[str, str | None] = {}
    for root in paths:
        files = sorted(p for p in root.rglob("*") if p.is_file()) if root.is_dir() else [root]
        if not root.exists():
            digests[str(root)] = None
        for path in files:
            digests[str(path)] = hashlib.sha256(path.read_bytes()).hexdigest()
    return digests


def check(
    name: str,
    argv: Sequence[str],
    *,
    must_fail: bool = False,
    survivors: Sequence[Path] = (),
    allow: Sequence[str] = ("clean",),
    after: Callable[[Run], str | None] | None = None,
    **run_options: object,
) -> Run:
    """Run one case, classify it, and assert it is in ``allow`` (or record it, see the module docstring).

    ``survivors`` are earlier outputs that must be unchanged byte for byte afterwards; ``after`` may
    return an outcome of its own (e.g. "data-loss") from a closer look at the run.
    """
    before = snapshot(list(survivors))
    run = run_cli(argv, **run_options)  # type: ignore[arg-type]
    outcome = classify(run, must_fail=must_fail)
    if outcome == "clean" and before and snapshot(list(survivors)) != before:
        outcome = "data-loss"
    if outcome == "clean" and after is not None:
        outcome = after(run) or outcome
    record(name, outcome, run)
    if not RECORD:
        assert outcome in allow, (
            f"{name}: {outcome} (exit {run.code}, {run.wall_s:.1f} s)\n"
            f"argv: {list(argv)}\n{run.escaped or ''}\nstderr:\n{run.stderr[-3000:]}"
        )
    return run


def record(name: str, outcome: str, run: Run | None = None) -> None:
    """Append one outcome to ``$SGPLAN_FAULTS_RECORD`` (nothing when the suite is not recording)."""
    if not RECORD:
        return
    entry = {"case": name, "outcome": outcome}
    if run is not None:
        entry.update(code=run.code, wall_s=round(run.wall_s, 2), stderr=run.stderr.strip()[-300:])
    with open(RECORD, "a", encoding="utf-8") as handle:
        handle.write(json.dumps(entry) + "\n")
