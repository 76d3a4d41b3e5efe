"""Trajectory files: the poses a robot drove, as CSV, and what such a file recorded beside them.

Two shapes are read (docs/execution.md, "Trajectory files"):

- the CSV that ``sgplan plan --waypoints`` writes (dense or simplified; columns
  :data:`sgplan.outputs.robot_files.CSV_COLUMNS`), or any CSV with a header naming at least ``x_m``, ``y_m``
  and ``floor``. Of the other columns, ``q`` (the automaton state after the pose), ``cost_m`` (metres
  from the first pose) and ``row``, ``col`` (the pose's cell) are optional and checked against what the
  monitor recomputes (:func:`recorded_mismatches`); the rest are ignored;
- plain ``x_m,y_m,floor`` rows without a header.

Blank lines and lines starting with ``#`` are skipped. Every error names the file, the line and the field.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from sgplan.errors import TrajectoryError
from sgplan.execution.poses import metric_cells
from sgplan.outputs.robot_files import CSV_COLUMNS
from sgplan.safeio import quote, read_text
from sgplan.scene.grid import OccupancyGrid

REQUIRED = ("x_m", "y_m", "floor")
CHECKED = ("q", "cost_m", "row", "col")
"""Optional columns compared with the monitor's own values."""
MAX_TRAJECTORY_BYTES = 256 * 2**20
COST_TOLERANCE_M = 1e-3
"""How far a recorded ``cost_m`` may differ from the recomputed one (the writer rounds to 0.1 mm)."""


@dataclass(frozen=True)
class Trajectory:
    """The poses of a trajectory file and the columns it recorded beside them.

    Attributes
    ----------
    path:
        the file read (``None`` when made in code).
    poses:
        ``(n, 3)`` float64 ``x_m, y_m, floor`` (metres in the scene's frame, floor index).
    lines:
        ``(n,)`` the 1-based file line of each pose.
    recorded:
        the optional columns present (:data:`CHECKED`), each ``(n,)``: ``q``, ``row``, ``col`` int64,
        ``cost_m`` float64.
    from_sgplan:
        the header is that of ``sgplan plan --waypoints`` (:data:`sgplan.outputs.robot_files.CSV_COLUMNS`):
        the straight line between two poses is then the path's own segment, checked legal when it was
        written, so any distance between them is expected.
    """

    path: Path | None
    poses: np.ndarray
    lines: np.ndarray
    recorded: dict[str, np.ndarray]
    from_sgplan: bool = False

    def pose_name(self, k: int) -> str:
        """``pose 12 (line 14)``: how messages name pose ``k``."""
        return f"pose {k} (line {int(self.lines[k])})"


def read_trajectory(path: str | Path) -> Trajectory:
    """Read a trajectory CSV (see the module).

    Cost: linear in the file (the numbers are converted column by column).

    Raises
    ------
    TrajectoryError
        a missing or unreadable file, no poses, a header without ``x_m``, ``y_m`` or ``floor`` or with a
        column twice, a row with another number of fields, or a field that is not a number (finite; a
        whole number for ``floor``, ``q``, ``row``, ``col``) -- naming the line and the field.
    """
    path = Path(path)
    text = read_text(path, TrajectoryError, "trajectory file", MAX_TRAJECTORY_BYTES)
    rows: list[list[str]] = []
    lines: list[int] = []
    for number, line in enumerate(text.splitlines(), start=1):
        if line.strip() and not line.lstrip().startswith("#"):
            rows.append(next(csv.reader([line])))
            lines.append(number)
    if not rows:
        raise TrajectoryError("no poses: expected a header naming x_m, y_m, floor, or x_m,y_m,floor rows",
                              path)
    header, first_line = [name.strip() for name in rows[0]], lines[0]
    if _is_number(header[0]):
        header = list(REQUIRED)
        if len(rows[0]) != len(REQUIRED):
            raise TrajectoryError(f"{len(rows[0])} fields; a trajectory without a header has rows "
                                  "x_m,y_m,floor", path, first_line)
    else:
        rows, lines = rows[1:], lines[1:]
        _check_header(header, path, first_line)
    if not rows:
        raise TrajectoryError("no poses after the header", path, first_line)
    for fields, number in zip(rows, lines):
        if len(fields) != len(header):
            raise TrajectoryError(f"{len(fields)} fields, the header has {len(header)} ({', '.join(header)})",
                                  path, number)
    line_array = np.array(lines, dtype=np.int64)
    columns = {name: [fields[k] for fields in rows] for k, name in enumerate(header)
               if name in REQUIRED or name in CHECKED}
    values = {name: _numbers(name, strings, line_array, path) for name, strings in columns.items()}
    poses = np.column_stack([values[name] for name in REQUIRED])
    recorded = {name: values[name] for name in CHECKED if name in values}
    for name in recorded:
        if name != "cost_m":
            recorded[name] = recorded[name].astype(np.int64)
    return Trajectory(path, poses, line_array, recorded, from_sgplan=tuple(header) == CSV_COLUMNS)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _check_header(header: list[str], path: Path, line: int) -> None:
    missing = [name for name in REQUIRED if name not in header]
    if missing:
        raise TrajectoryError(
            f"the header has no {', '.join(missing)} column (found: {quote(', '.join(header), 120)}); a "
            "trajectory needs x_m, y_m and floor", path, line)
    twice = sorted({name for name in header if header.count(name) > 1 and name in REQUIRED + CHECKED})
    if twice:
        raise TrajectoryError(f"the header names {', '.join(twice)} more than once", path, line)


def _numbers(name: str, strings: list[str], lines: np.ndarray, path: Path) -> np.ndarray:
    """The column ``name`` as float64, every value finite (and whole, but for metres)."""
    whole = name not in ("x_m", "y_m", "cost_m")
    try:
        values = np.array(strings, dtype=np.float64)
        bad = ~np.isfinite(values) | ((values != np.round(values)) if whole else False)
    except ValueError:  # some field is no number: find the first
        bad = np.array([not _is_number(s) for s in strings])
        values = np.zeros(len(strings))
    if np.any(bad):
        k = int(np.argmax(bad))
        what = "a whole number" if whole else "a finite number of metres"
        raise TrajectoryError(f"field {name}: {quote(strings[k].strip())} is not {what}", path, int(lines[k]))
    return values


def recorded_mismatches(trajectory: Trajectory, grid: OccupancyGrid, states: np.ndarray,
                        lengths_m: np.ndarray) -> list[str]:
    """What the file recorded that differs from the monitor's own values, one message per column:
    ``q`` against ``states`` (the automaton state after each pose), ``cost_m`` against ``lengths_m``
    (metres from the first pose along the route the monitor assumed), ``row``, ``col`` against the cells
    of ``x_m``, ``y_m`` in ``grid``. Each message names the first line that differs and how many do."""
    cells = metric_cells(trajectory.poses[:, :2], grid)
    ours = {"q": states.astype(np.int64), "cost_m": lengths_m, "row": cells[:, 0], "col": cells[:, 1]}
    why = {
        "q": "the monitor computes {ours} (the file was made for another mission or semantics profile?)",
        "cost_m": "the route through the poses is {ours:.4f} m long (the file was edited?)",
        "row": "the cell of its x_m is in row {ours} (the file was made for another scene or grid?)",
        "col": "the cell of its y_m is in column {ours} (the file was made for another scene or grid?)",
    }
    messages = []
    for name, recorded in trajectory.recorded.items():
        differs = (np.abs(recorded - ours[name]) > COST_TOLERANCE_M if name == "cost_m"
                   else recorded != ours[name])
        if differs.any():
            k = int(np.argmax(differs))
            count = int(differs.sum())
            value = f"{recorded[k]:.4f}" if name == "cost_m" else str(recorded[k])
            more = f"; {count - 1} more lines differ" if count > 1 else ""
            reason = why[name].format(ours=ours[name][k])
            messages.append(f"line {int(trajectory.lines[k])}: {name} is {value}, but {reason}{more}")
    return messages
