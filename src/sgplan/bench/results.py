"""Benchmark results: the row schema and the append-only store a sweep resumes from.

A sweep's output folder holds ``results.jsonl``: one JSON object per finished case, appended with a
single ``write`` + ``fsync`` as the case finishes, so an interrupt leaves at most one incomplete last
line, which is dropped on the next open. ``results.csv`` (the columns of :data:`COLUMNS`) and
``results.json`` (full rows, with per-iteration records) are regenerated from it, atomically.
When a case is recorded twice (a re-run with ``retry``), the last row wins.
"""

from __future__ import annotations

import contextlib
import csv
import fcntl
import io
import json
import os
import socket
import sys
import time
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

from sgplan.bench.cases import BenchError, Case
from sgplan.bench.worker import MEASURED
from sgplan.files import write_texts_atomically
from sgplan.planning.setups import LEVEL_NAMES
from sgplan.safeio import clip, quote, read_bytes
from sgplan.scene.fields import is_int, is_number

RESULTS_JSONL, RESULTS_CSV, RESULTS_JSON = "results.jsonl", "results.csv", "results.json"
SWEEPS_JSONL = "sweeps.jsonl"
"""One line per sweep call: when, cases run / resumed, wall seconds, executor, jobs."""

FAILED = ("error", "crashed", "wall-timeout")
"""The case did not run to its end: a bug or bad input (``error``), the worker process died
(``crashed``), or it ran past the per-case wall timeout and was killed (``wall-timeout``)."""
RETRYABLE = FAILED
"""Statuses that ``--retry`` runs again (an ``error`` may come from a bug fixed since)."""
LOCK_FILE = ".lock"
REQUIRED = ("key", "scene", "mission", "start", "setup", "profile", "status")
"""Fields every stored row must have (the report groups and keys rows by them)."""

COLUMNS = (
    "key", "scene", "mission", "start", "setup", "profile", "reach_model", "time_limit_s", "status", "reason",
    "start_cell", "cost_m", "first_cost_m", "cost_ratio", "first_time_s", "optimal_time_s",
    "num_iterations", "expansions", *(f"exp_{level}" for level in LEVEL_NAMES),
    "load_s", "precompute_s", "search_s", "wall_s", "peak_rss_mb", "guidance", "path_cells",
    "scene_reused", "ltlf_accepts", "executor", "host", "finished_at",
)
"""The CSV columns, in order (documented in docs/bench.md); ``results.json`` rows add ``queues``,
``iterations``, ``gallery`` and ``ltlf_violations``."""


def make_row(case: Case, measured: dict[str, Any], *, wall_s: float | None, executor: str) -> dict[str, Any]:
    """A result row: the case's fields, the worker's measurements, and the parent's wall time."""
    row: dict[str, Any] = {
        "key": case.key, "scene": case.scene, "mission": case.mission, "start": case.start,
        "setup": case.setup, "profile": case.profile, "reach_model": case.effective_reach_model,
        "time_limit_s": case.time_limit_s,
    }
    row.update(dict.fromkeys(MEASURED))
    row.update(measured)
    row.update(
        wall_s=wall_s, executor=executor, host=socket.gethostname(),
        finished_at=time.strftime("%Y-%m-%dT%H:%M:%S%z"),
    )
    return row


def failed_row(case: Case, status: str, reason: str, *, wall_s: float | None, executor: str,
               peak_rss_mb: float | None = None) -> dict[str, Any]:
    """The row of a case whose worker did not report (``crashed`` / ``wall-timeout`` / ``error``)."""
    return make_row(case, {"status": status, "reason": reason, "peak_rss_mb": peak_rss_mb},
                    wall_s=wall_s, executor=executor)


def make_folder(folder: str | Path) -> Path:
    """``folder`` as a path, created if needed (a BenchError saying why if it cannot be)."""
    path = Path(folder).expanduser()
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise BenchError(f"cannot create the output folder {path}: {error.strerror}") from None
    return path


_TEXT_FIELDS = ("key", "scene", "mission", "setup", "profile", "status")
_NUMBER_FIELDS = tuple(
    c for c in COLUMNS
    if c.endswith(("_s", "_m", "_mb")) or c in ("cost_ratio", "num_iterations", "expansions", "path_cells")
    or c.startswith("exp_")
)
"""Fields that hold a finite number or null in every row (the report computes with them)."""


def _refuse_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a JSON number")


def _parse_row(data: bytes | str) -> tuple[dict[str, Any] | None, str]:
    """The row in one line of results.jsonl, or ``None`` and what is wrong with it."""
    try:
        row = json.loads(data, parse_constant=_refuse_constant)
    except (UnicodeDecodeError, ValueError, RecursionError) as error:
        return None, f"not a JSON object ({clip(str(error), 80)})"
    if not isinstance(row, dict):
        return None, f"not a JSON object but {type(row).__name__}"
    missing = [k for k in REQUIRED if k not in row]
    if missing:
        return None, f"missing {', '.join(missing)}"
    wrong = [k for k in _TEXT_FIELDS if not isinstance(row[k], str)]
    if not is_int(row["start"]):
        wrong.append("start")
    # Finite and within float range: int/float comparison is exact, so a huge JSON integer is refused here
    # instead of overflowing in the report's float arithmetic (math.isfinite would raise on it).
    wrong += [k for k in _NUMBER_FIELDS if row.get(k) is not None
              and not (is_number(row[k]) and abs(row[k]) <= sys.float_info.max)]
    if wrong:
        return (
            None,
            f"field(s) {', '.join(wrong)} of the wrong type ({wrong[0]} = {quote(row.get(wrong[0]))})",
        )
    return row, ""


def _is_row(data: bytes) -> bool:
    return _parse_row(data)[0] is not None


class ResultStore:
    """The results of one output folder (see the module docstring).

    Parameters
    ----------
    folder:
        the output folder; created if needed.
    """

    def __init__(self, folder: str | Path) -> None:
        self.folder = make_folder(folder)
        self.path = self.folder / RESULTS_JSONL
        self._rows: dict[str, dict[str, Any]] = {}
        self._partial = 0
        self._newline_missing = False
        self._load()

    def _load(self) -> None:
        if not (self.path.exists() or self.path.is_symlink()):
            return
        data = read_bytes(self.path, BenchError, "results file")
        complete = data[: data.rfind(b"\n") + 1]
        tail = data[len(complete):]
        if tail.strip() and _is_row(tail):
            # A whole row without its newline (a hand edit): kept; the next append adds the newline.
            complete, self._newline_missing = data + b"\n", True
        else:
            # An interrupted append leaves a partial last line: ignored here, cut off by the next append.
            self._partial = len(tail)
        try:
            text = complete.decode("utf-8")
        except UnicodeDecodeError as error:
            raise BenchError(f"is not UTF-8 text (byte {error.start}); fix or remove it", self.path) from None
        for number, line in enumerate(text.splitlines(), 1):
            if not line.strip():
                continue
            row, problem = _parse_row(line)
            if row is None:
                raise BenchError(
                    f"line {number} is not a result row ({problem}); fix or remove it", self.path
                )
            self._rows[row["key"]] = row

    def __len__(self) -> int:
        return len(self._rows)

    def __contains__(self, key: str) -> bool:
        return key in self._rows

    def get(self, key: str) -> dict[str, Any] | None:
        return self._rows.get(key)

    def rows(self) -> list[dict[str, Any]]:
        """The latest row of every recorded case, in the order first recorded."""
        return list(self._rows.values())

    def append(self, row: dict[str, Any]) -> None:
        """Record ``row`` durably: one write of one complete line, then fsync. Only the holder of
        :func:`writing_lock` may append."""
        line = (json.dumps(row, allow_nan=False) + "\n").encode("utf-8")
        fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        try:
            if self._partial:
                os.ftruncate(fd, os.fstat(fd).st_size - self._partial)
                self._partial = 0
            if self._newline_missing:
                line = b"\n" + line
                self._newline_missing = False
            written = os.write(fd, line)
            if written != len(line):  # pragma: no cover - a full disk
                raise BenchError(f"short write ({written} of {len(line)} bytes)", self.path)
            os.fsync(fd)
        finally:
            os.close(fd)
        self._rows[row["key"]] = row

    def export(self) -> tuple[Path, Path]:
        """(Re)write ``results.csv`` and ``results.json`` from the recorded rows; returns their paths."""
        rows = self.rows()
        buffer = io.StringIO()
        writer = csv.DictWriter(buffer, fieldnames=COLUMNS, extrasaction="ignore", lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: _csv_value(row.get(k)) for k in COLUMNS})
        csv_path, json_path = self.folder / RESULTS_CSV, self.folder / RESULTS_JSON
        try:
            # Both files are written in full before either replaces its old version, so a failed write
            # (a full disk) leaves the two earlier files, which agree.
            write_texts_atomically({csv_path: buffer.getvalue(),
                                    json_path: json.dumps(rows, indent=1, allow_nan=False) + "\n"})
        except OSError as error:
            raise BenchError(f"cannot write results.csv and results.json ({error.strerror or error}); "
                             "the earlier ones are unchanged", self.folder) from None
        return csv_path, json_path


def _csv_value(value: Any) -> Any:
    if value is None:
        return ""
    if isinstance(value, (list, tuple)):
        return " ".join(str(v) for v in value)
    return value


def load_rows(folder: str | Path) -> list[dict[str, Any]]:
    """The rows recorded in ``folder/results.jsonl`` (a clear error if there are none)."""
    path = Path(folder).expanduser() / RESULTS_JSONL
    rows = ResultStore(path.parent).rows() if path.is_file() else []
    if not rows:
        raise BenchError(f"no results in {path.parent}: run `sgplan bench --out {path.parent}` first")
    return rows


def record_sweep(folder: str | Path, info: dict[str, Any]) -> None:
    """Append one sweep call's summary (``info`` plus the time) to ``folder/sweeps.jsonl``."""
    line = json.dumps({"finished_at": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **info}, allow_nan=False)
    path = Path(folder).expanduser() / SWEEPS_JSONL
    try:
        with open(path, "a", encoding="utf-8") as handle:
            handle.write(line + "\n")
    except OSError as error:
        raise BenchError(f"cannot record the sweep: {error.strerror or error}", path) from None


def load_sweeps(folder: str | Path) -> list[dict[str, Any]]:
    """The sweep calls recorded in ``folder`` (none if the file is absent; unreadable lines skipped, since
    this log is informative only)."""
    path = Path(folder).expanduser() / SWEEPS_JSONL
    out = []
    try:
        text = path.read_text(encoding="utf-8", errors="replace") if path.is_file() else ""
    except OSError:
        text = ""
    for line in text.splitlines():
        try:
            entry = json.loads(line, parse_constant=_refuse_constant)
        except (ValueError, RecursionError):
            continue
        if isinstance(entry, dict):
            out.append(entry)
    return out


def counts(rows: Iterable[dict[str, Any]]) -> dict[str, int]:
    """Number of rows per status."""
    out: dict[str, int] = {}
    for row in rows:
        out[row["status"]] = out.get(row["status"], 0) + 1
    return out


@contextlib.contextmanager
def writing_lock(folder: str | Path) -> Iterator[None]:
    """Hold the exclusive right to append to ``folder``'s results (an advisory ``flock`` on
    ``folder/.lock``, released when the process ends however it ends).

    Raises
    ------
    BenchError
        another sweep is writing into ``folder``.
    """
    path = Path(folder).expanduser() / LOCK_FILE
    try:
        handle = open(path, "a+b")  # noqa: SIM115 - closed below, after the lock is released
    except OSError as error:
        raise BenchError(f"cannot open the lock file: {error.strerror or error}", path) from None
    with handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise BenchError("another `sgplan bench` is writing into this folder; wait for it or use another "
                             "--out", path.parent) from None
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)
