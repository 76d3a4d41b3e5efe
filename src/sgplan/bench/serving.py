"""A long-lived worker process (``python -m sgplan.bench.worker --serve``) that runs many cases in turn.

The local executor keeps one per job, so a case does not pay an interpreter start, the imports, the
compiled kernels' loading and the scene's loading again (benchmarks/results/comment_measurements.md). A case
is still measured the same way and isolated from the sweep: the parent times each request (``wall_s``)
and kills the worker after the per-case wall timeout; a worker that crashed, timed out or answered
nonsense is never asked again, and the next case gets a fresh one.
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import signal
import subprocess
import tempfile
import threading
import time
from collections.abc import Sequence
from typing import IO, Any

from sgplan.bench.cases import BenchError, Case
from sgplan.bench.results import failed_row, make_row
from sgplan.bench.worker import SERVE_FLAG

STDERR_TAIL = 600
"""Characters of a dead worker's last output kept in the row's reason."""

_POLL_S = 0.2
"""How often a wait for an answer looks at the cancel event."""


class ServingWorker:
    """One ``worker --serve`` process; :meth:`run` sends it a case and waits for its answer line."""

    def __init__(self, command: Sequence[str], env: dict[str, str]) -> None:
        # A file, not a pipe, so nothing fills up; closed by kill().
        self._stderr: IO[bytes] = tempfile.TemporaryFile()  # noqa: SIM115 - lives as long as the worker
        try:
            self.proc = subprocess.Popen(
                [*command, SERVE_FLAG], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=self._stderr,
                env=env,
                start_new_session=True,  # a terminal Ctrl-C reaches the sweep, which then stops the workers
            )
        except OSError as error:  # every case would fail the same way: stop the sweep
            self._stderr.close()
            raise BenchError(f"cannot start the worker {command[0]!r}: {error.strerror or error}") from None
        self._buffer = b""
        self.cases = 0

    def run(self, case: Case, *, timeout_s: float, gallery_dir: str | None, executor: str,
            cancel: threading.Event | None = None) -> tuple[dict[str, Any], bool]:
        """The result row of ``case`` (never raises for the case), and whether this worker may run
        another one (False after a crash, a timeout, a bad answer or a cancel: it is then dead)."""
        self.cases += 1
        stderr_from = os.fstat(self._stderr.fileno()).st_size
        request = json.dumps({"case": case.to_dict(), "gallery_dir": gallery_dir}) + "\n"
        t0 = time.perf_counter()
        try:
            assert self.proc.stdin is not None
            self.proc.stdin.write(request.encode())
            self.proc.stdin.flush()
            line = self._read_line(t0 + timeout_s, cancel)
        except OSError:  # the worker is gone (broken pipe): reported below from its exit status
            line = b""
        wall_s = time.perf_counter() - t0
        if line is None:
            rss = peak_rss_of(self.proc.pid)
            self.kill()
            reason = f"killed after the per-case wall timeout of {timeout_s:g} s"
            return failed_row(case, "wall-timeout", reason, wall_s=wall_s, executor=executor,
                              peak_rss_mb=rss), False
        try:
            measured = json.loads(line)
        except ValueError:
            measured = None
        if isinstance(measured, dict) and "status" in measured:
            return make_row(case, measured, wall_s=wall_s, executor=executor), True
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.proc.wait(timeout=1.0)  # a crashed worker is gone already: its exit status says how
        self._stop()
        reason = death(self.proc.returncode, self._stderr_since(stderr_from))
        self.kill()
        return failed_row(case, "crashed", reason, wall_s=wall_s, executor=executor), False

    def _read_line(self, deadline: float, cancel: threading.Event | None) -> bytes | None:
        """The next stdout line; ``b""`` at end of output (the worker died), ``None`` at the deadline."""
        assert self.proc.stdout is not None
        fd = self.proc.stdout.fileno()
        while b"\n" not in self._buffer:
            remaining = deadline - time.perf_counter()
            if remaining <= 0:
                return None
            if cancel is not None and cancel.is_set():
                return b""
            ready, _, _ = select.select([fd], [], [], min(remaining, _POLL_S))
            if ready:
                chunk = os.read(fd, 1 << 16)
                if not chunk:
                    return b""
                self._buffer += chunk
        line, _, self._buffer = self._buffer.partition(b"\n")
        return line

    def _stderr_since(self, offset: int) -> str:
        with contextlib.suppress(OSError):
            self._stderr.seek(offset)
            return self._stderr.read().decode(errors="replace")
        return ""

    def _stop(self) -> None:
        with contextlib.suppress(OSError):
            self.proc.kill()
        self.proc.wait()

    def kill(self) -> None:
        """Stop the worker now (if still running), reap it and close its files."""
        self._stop()
        for stream in (self.proc.stdin, self.proc.stdout, self._stderr):
            with contextlib.suppress(OSError):
                if stream is not None:
                    stream.close()


def peak_rss_of(pid: int) -> float | None:
    """Peak resident memory (MiB) of a live process, from /proc (Linux); ``None`` elsewhere."""
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except (OSError, ValueError, IndexError):
        pass
    return None


def death(returncode: int, stderr: str) -> str:
    """Why a worker gave no result: its signal or exit code, and the tail of its output."""
    if returncode < 0:
        try:
            how = f"was killed by signal {signal.Signals(-returncode).name}"
        except ValueError:
            how = f"was killed by signal {-returncode}"
    else:
        how = f"exited with code {returncode} without a result"
    tail = stderr.strip()[-STDERR_TAIL:]
    return f"the worker process {how}" + (f"; its last output: {tail}" if tail else "")
