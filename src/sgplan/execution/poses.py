"""Poses a robot drove, as grid cells: converted, checked, and joined into the route the monitor follows.

A pose is metric ``(x_m, y_m, floor)`` (the scene's frame, as :mod:`sgplan.outputs.waypoints` writes
them) or a cell ``(row, col, floor)``; a metric pose lies in the cell that contains it
(``row = floor((x_m - origin_x) / res_x)``, likewise ``col``), never moved elsewhere.

- A pose that is not finite, lies off the grid or on a floor the scene lacks cannot be read:
  :class:`~sgplan.errors.TrajectoryError` naming it.
- A pose on a cell a robot may not enter (a wall, furniture, the stairs between their portals, the
  robot's clearance around obstacles, outside every room) is read as it lies and reported as a
  :class:`PoseIssue` saying where and why.
- Between two poses on different floors the robot took the stairs: the route goes to the staircase
  portal of the first floor, takes the stairs (one flight per floor) and comes from the portal of the
  next. Floors with no stairs between them are an error.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np

from sgplan.errors import TrajectoryError
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building, CatCode

Cell3 = tuple[int, int, int]
"""A cell ``(row, col, floor)``."""
PoseNamer = Callable[[int], str]
"""Names pose number ``k`` in messages (default ``pose k``; a file reader adds its line)."""
IssueKind = Literal["obstacle", "gap", "crosses-obstacle"]


def pose_name(k: int) -> str:
    """The default :data:`PoseNamer`: ``pose 12``."""
    return f"pose {k}"


@dataclass(frozen=True)
class PoseIssue:
    """Something about the poses a monitor read that its verdict relies on
    (see :mod:`sgplan.execution.monitor`).

    Attributes
    ----------
    kind:
        ``"obstacle"``: poses on cells a robot may not enter (read as they lie); ``"gap"``: poses farther
        than the tolerance from the pose before (the straight line between them assumed);
        ``"crosses-obstacle"``: the straight line from the pose before crosses such cells.
    first_pose, last_pose:
        the run of consecutive poses concerned (indices over every pose the monitor read).
    message:
        one sentence naming them, where they are and what the monitor assumed.
    """

    kind: IssueKind
    first_pose: int
    last_pose: int
    message: str

    def to_dict(self) -> dict[str, object]:
        return {"kind": self.kind, "first_pose": self.first_pose, "last_pose": self.last_pose,
                "message": self.message}


def as_poses(poses: object, what: str) -> np.ndarray:
    """``poses`` (one pose or a sequence of them) as an ``(n, 3)`` float64 array.

    Raises
    ------
    TrajectoryError
        any other shape, or values that are not numbers.
    """
    try:
        array = np.asarray(poses, dtype=np.float64)
    except (TypeError, ValueError):
        raise TrajectoryError(f"{what}: expected numbers (x_m, y_m, floor) or (row, col, floor)") from None
    if array.ndim == 1 and array.size:
        array = array[None, :]
    if array.size == 0:
        return np.zeros((0, 3))
    if array.ndim != 2 or array.shape[1] != 3:
        raise TrajectoryError(f"{what}: expected one pose of 3 values or an (n, 3) array, got shape "
                              f"{array.shape}")
    return array


def cells_of_poses(poses: np.ndarray, grid: OccupancyGrid, *, metric: bool, first: int,
                   name: PoseNamer = pose_name) -> np.ndarray:
    """The ``(n, 3)`` int64 cells ``[row, col, floor]`` of ``(n, 3)`` poses (metric or cells).

    ``first`` is the index of ``poses[0]`` among every pose read (for messages).

    Raises
    ------
    TrajectoryError
        the first pose that is not finite, not on a whole floor number, on a floor the scene lacks, or
        off the grid; for cell poses, a row or column that is not a whole number.
    """
    floors, rows, cols = grid.shape
    bad = ~np.isfinite(poses).all(axis=1)
    bad |= poses[:, 2] != np.round(poses[:, 2])
    if not metric:
        bad |= (poses[:, :2] != np.round(poses[:, :2])).any(axis=1)
    if bad.any():
        k = int(np.argmax(bad))
        kind = "x_m, y_m" if metric else "row, col"
        raise TrajectoryError(f"{name(first + k)}: {_pose_text(poses[k], metric)} is not a pose ({kind} "
                              "finite numbers, the floor a whole number)")
    floor = poses[:, 2].astype(np.int64)
    row_col = metric_cells(poses[:, :2], grid) if metric else poses[:, :2].astype(np.int64)
    off = (floor < 0) | (floor >= floors) | (row_col < 0).any(axis=1) | (row_col >= (rows, cols)).any(axis=1)
    if off.any():
        k = int(np.argmax(off))
        raise TrajectoryError(f"{name(first + k)}: {_pose_text(poses[k], metric)} "
                              f"{_off_grid(grid, int(floor[k]), metric)}")
    return np.column_stack([row_col, floor])


def metric_cells(xy_m: np.ndarray, grid: OccupancyGrid) -> np.ndarray:
    """``(n, 2)`` int64 ``(row, col)`` of the cells holding the metric points ``(n, 2)`` ``(x_m, y_m)``
    (possibly off the grid)."""
    return np.floor((xy_m - np.asarray(grid.origin_m)) / np.asarray(grid.resolution_m)).astype(np.int64)


def _pose_text(pose: np.ndarray, metric: bool) -> str:
    if metric:
        return f"(x {pose[0]:g} m, y {pose[1]:g} m, floor {pose[2]:g})"
    return f"(row {pose[0]:g}, col {pose[1]:g}, floor {pose[2]:g})"


def _off_grid(grid: OccupancyGrid, floor: int, metric: bool) -> str:
    floors, rows, cols = grid.shape
    if not 0 <= floor < floors:
        return f"is on no floor of the scene (floors 0..{floors - 1})"
    if not metric:
        return f"lies off the {rows} x {cols} grid"
    (x0, y0), (rx, ry) = grid.origin_m, grid.resolution_m
    return (f"lies off the grid (x from {x0:g} to {x0 + rows * rx:g} m, y from {y0:g} to "
            f"{y0 + cols * ry:g} m): check the frame and the floor")


def route_through_stairs(cells: np.ndarray, grid: OccupancyGrid, *, first: int,
                         name: PoseNamer = pose_name) -> tuple[np.ndarray, np.ndarray]:
    """The route the monitor follows through ``cells`` (``(n, 3)``, the first one possibly the cell the
    robot already stands on), with the stairs portals inserted where consecutive cells change floor, and
    the row of each cell in it.

    Returns
    -------
    route, rows:
        ``(m, 3)`` int64 cells and ``(n,)`` int64 indices with ``route[rows[k]] == cells[k]``.

    Raises
    ------
    TrajectoryError
        consecutive poses on floors that no stairs join (``first`` numbers ``cells[0]``).
    """
    changes = np.flatnonzero(cells[1:, 2] != cells[:-1, 2]) + 1
    if not changes.size:
        return cells, np.arange(len(cells))
    links = {link.lower_floor: link for link in grid.stairs}
    inserted: list[np.ndarray] = []
    for k in changes.tolist():
        a, b = int(cells[k - 1, 2]), int(cells[k, 2])
        portals = []
        for lower in range(a, b) if b > a else range(a - 1, b - 1, -1):
            link = links.get(lower)
            if link is None:
                raise TrajectoryError(
                    f"{name(first + k - 1)} on floor {a} and {name(first + k)} on floor {b}: no stairs join "
                    f"floors {lower} and {lower + 1} in this scene"
                )
            ends = [(*link.lower_cell, lower), (*link.upper_cell, lower + 1)]
            portals += ends if b > a else ends[::-1]
        inserted.append(np.array(portals, dtype=np.int64))
    pieces = np.split(cells, changes)
    route = np.concatenate([part for pair in zip(pieces, [*inserted, None]) for part in pair
                            if part is not None])
    shift = np.zeros(len(cells), np.int64)
    shift[changes] = [len(p) for p in inserted]
    return route, np.arange(len(cells)) + np.cumsum(shift)


def segment_lengths_m(route: np.ndarray, grid: OccupancyGrid) -> tuple[np.ndarray, np.ndarray]:
    """Metres of the segment ending at each route row: ``(planar, stairs)``, both ``(m,)`` (row 0: 0).

    Planar: between the cell centres on one floor; stairs: the link's cost where the floor changes.
    """
    step = np.diff(route, axis=0)
    planar = np.hypot(step[:, 0] * grid.resolution_m[0], step[:, 1] * grid.resolution_m[1])
    stairs = np.zeros_like(planar)
    changes = np.flatnonzero(step[:, 2] != 0)
    if changes.size:
        cost = {link.lower_floor: link.cost_m for link in grid.stairs}
        planar[changes] = 0.0
        stairs[changes] = [cost[int(min(route[k, 2], route[k + 1, 2]))] for k in changes.tolist()]
    return np.concatenate([[0.0], planar]), np.concatenate([[0.0], stairs])


def runs(flags: np.ndarray, codes: np.ndarray | None = None) -> list[tuple[int, int]]:
    """``(first, last)`` index of each run of consecutive True ``flags`` (with equal ``codes``)."""
    flagged = np.flatnonzero(flags)
    if not flagged.size:
        return []
    breaks = np.diff(flagged) != 1
    if codes is not None:
        breaks |= codes[flagged[1:]] != codes[flagged[:-1]]
    starts = np.concatenate([[0], np.flatnonzero(breaks) + 1])
    ends = np.concatenate([starts[1:] - 1, [len(flagged) - 1]])
    return list(zip(flagged[starts].tolist(), flagged[ends].tolist()))


def _span(first: int, last: int, name: PoseNamer) -> str:
    return name(first) if first == last else f"{name(first)} to {name(last)}"


def obstacle_issues(cells: np.ndarray, grid: OccupancyGrid, building: Building, *, first: int,
                    name: PoseNamer = pose_name) -> list[PoseIssue]:
    """One :class:`PoseIssue` per run of consecutive poses on cells a robot may not enter, for one reason."""
    blocked = ~grid.traversable[cells[:, 2], cells[:, 0], cells[:, 1]]
    if not blocked.any():
        return []
    cat = np.zeros(len(cells), np.int64)
    for floor in np.unique(cells[blocked, 2]).tolist():
        on = blocked & (cells[:, 2] == floor)
        cat[on] = building.floors[floor].cat_map[cells[on, 0], cells[on, 1]]
    in_room = grid.room_map[cells[:, 2], cells[:, 0], cells[:, 1]] > 0
    issues = []
    for a, b in runs(blocked, 2 * cat + in_room):  # one reason per run
        row, col, floor = (int(v) for v in cells[a])
        x_m, y_m, _ = grid.cell_xyz(floor, (row, col))
        where = f"x {x_m:.2f} m, y {y_m:.2f} m, floor {floor}"
        why = _why_blocked(building, grid, int(cat[a]), bool(in_room[a]))
        text = (f"{name(first + a)} ({where}) lies {why}" if a == b else
                f"{_span(first + a, first + b, name)} lie {why} (the first at {where})")
        issues.append(PoseIssue("obstacle", first + a, first + b,
                                f"{text}, where the robot cannot be: read as it lies, not moved"))
    return issues


def _why_blocked(building: Building, grid: OccupancyGrid, code: int, in_room: bool) -> str:
    if code > 0:
        obj = building.object(id=code)
        return f"on the {obj.name.replace('_', ' ')} ({obj.key})"
    reasons = {
        CatCode.WALL: "in a wall",
        CatCode.STAIRS_UP: "on the stairs (only their portal cells are driven on)",
        CatCode.STAIRS_DOWN: "on the stairs (only their portal cells are driven on)",
        CatCode.CEILING: "outside the floor's map",
        CatCode.OUTSIDE: "outside the building",
    }
    if code in reasons:
        return reasons[CatCode(code)]
    if not in_room:
        return "outside every room"
    return f"within {grid.robot_radius_m:g} m (the robot radius) of an obstacle"


def gap_issues(gaps_m: np.ndarray, max_gap_m: float, *, first: int, name: PoseNamer = pose_name
               ) -> list[PoseIssue]:
    """One :class:`PoseIssue` per run of poses farther than ``max_gap_m`` (metres, on the floor) from the
    pose before them (``gaps_m[k]``: from pose ``k - 1`` to pose ``k``)."""
    issues = []
    for a, b in runs(gaps_m > max_gap_m):
        largest = float(gaps_m[a:b + 1].max())
        subject = (f"{name(first + a)} is {largest:.2f} m from the pose before" if a == b else
                   f"{_span(first + a, first + b, name)} are each more than {max_gap_m:g} m (up to "
                   f"{largest:.2f} m) from the pose before")
        issues.append(PoseIssue(
            "gap", first + a, first + b,
            f"{subject}, more than the {max_gap_m:g} m tolerance: the monitor assumed the straight line "
            "(and the stairs between floors)",
        ))
    return issues


def crossing_issues(crossing: np.ndarray, *, first: int, name: PoseNamer = pose_name) -> list[PoseIssue]:
    """One :class:`PoseIssue` per run of poses whose straight line from the pose before crosses cells a
    robot may not enter (``crossing[k]``: the line from pose ``k - 1`` to pose ``k`` does)."""
    return [
        PoseIssue(
            "crosses-obstacle", first + a, first + b,
            f"the straight line to {_span(first + a, first + b, name)} from the pose before crosses cells "
            "the robot cannot enter, so it went around: the monitor read the line's cells, not knowing which "
            "way",
        )
        for a, b in runs(crossing)
    ]
