"""Where a run stands after the poses its robot reported: the mission's automaton state, read cell by
cell as the planner reads a path, and how far along the plan the robot got.

This is the service's own bookkeeping of a run (what is needed to say *done*, *violated* and what is
left to do); replanning after scene changes and amendments belongs to :mod:`sgplan.execution`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building
from sgplan.serve.errors import HTTPProblem

ON_TRACK, DONE, VIOLATED = "on-track", "done", "violated"


@dataclass(frozen=True)
class Progress:
    """A run's progress: automaton ``state``, poses seen, the last cell, the index of the plan's path
    cell the robot has come to (nearest on its floor, never going back), and the verdict."""

    state: int
    poses: int
    cell: tuple[int, int, int] | None
    path_index: int
    verdict: str

    def to_dict(self) -> dict[str, Any]:
        return {
            "state": self.state,
            "poses": self.poses,
            "cell": None if self.cell is None else list(self.cell),
            "path_index": self.path_index,
            "verdict": self.verdict,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Progress:
        cell = data.get("cell")
        return cls(
            int(data["state"]),
            int(data["poses"]),
            None if cell is None else tuple(cell),
            int(data["path_index"]),
            str(data["verdict"]),
        )


def start_progress(automaton: Automaton, path: list[list[int]] | None) -> Progress:
    """Before any pose: the state after the plan's start cell (the path's first row), or the initial one."""
    state = int(path[0][3]) if path else automaton.initial
    return Progress(state, 0, None, 0, _verdict(automaton, state))


def advance(
    progress: Progress,
    poses: list[tuple[float, float, int]],
    building: Building,
    grid: OccupancyGrid,
    labels: np.ndarray,
    automaton: Automaton,
    path: list[list[int]] | None,
) -> Progress:
    """``progress`` after ``poses`` (``[x_m, y_m, floor]``, oldest first): every pose's cell read by the
    automaton (the cells between two poses are not: a robot reports often enough for none to matter).

    Raises
    ------
    HTTPProblem
        422 naming the first pose off the map or on a floor that does not exist.
    """
    xy = np.asarray(poses, dtype=float)
    floors = xy[:, 2].astype(np.int64)
    bad_floor = np.flatnonzero((floors < 0) | (floors >= building.num_floors))
    if len(bad_floor):
        k = int(bad_floor[0])
        raise HTTPProblem(
            422, f"pose {k} is on floor {floors[k]}; the scene has floors 0-{building.num_floors - 1}"
        )
    origin = np.array([building.floors[f].origin_m for f in floors])
    res = np.array([building.floors[f].resolution_m for f in floors])
    rc = np.floor((xy[:, :2] - origin) / res).astype(np.int64)
    rows, cols = grid.traversable.shape[1:]
    off = np.flatnonzero((rc[:, 0] < 0) | (rc[:, 1] < 0) | (rc[:, 0] >= rows) | (rc[:, 1] >= cols))
    if len(off):
        k = int(off[0])
        raise HTTPProblem(422, f"pose {k} ({xy[k, 0]:g}, {xy[k, 1]:g}) m on floor {floors[k]} is off the map")
    state = progress.state
    for label in labels[floors, rc[:, 0], rc[:, 1]].tolist():
        state = automaton.step(state, int(label))
    last = (int(rc[-1, 0]), int(rc[-1, 1]), int(floors[-1]))
    return Progress(
        state,
        progress.poses + len(poses),
        last,
        _along(path, last, progress.path_index),
        _verdict(automaton, state),
    )


def _verdict(automaton: Automaton, state: int) -> str:
    if automaton.accepting[state]:
        return DONE
    return ON_TRACK if automaton.live_states()[state] else VIOLATED


def _along(path: list[list[int]] | None, cell: tuple[int, int, int], since: int) -> int:
    """The path row nearest ``cell`` on its floor at or after row ``since`` (``since`` if none is)."""
    if not path:
        return since
    rows = np.asarray(path[since:], dtype=np.int64)
    same = np.flatnonzero(rows[:, 2] == cell[2])
    if not len(same):
        return since
    d2 = (rows[same, 0] - cell[0]) ** 2 + (rows[same, 1] - cell[1]) ** 2
    return since + int(same[np.argmin(d2)])


def left_to_do(events: list[dict[str, Any]], progress: Progress, phrase: Callable[[str], str]) -> list[str]:
    """The steps of the plan still ahead of the robot, in words: where along the plan each move of the
    mission happens and what becomes true there, each proposition named by ``phrase`` (``"the kitchen
    (room_4, floor 0)"``); empty once done."""
    if progress.verdict == DONE:
        return []
    steps = []
    for event in events:
        if event.get("kind") != "state" or event["index"] <= progress.path_index:
            continue
        true = [
            phrase(e["proposition"])
            for e in events
            if e.get("kind") == "proposition" and e["index"] == event["index"]
        ]
        where = f"row {event['row']}, column {event['col']}, floor {event['floor']}"
        what = "at " + " and ".join(true) if true else "the mission moves on"
        tail = ": the mission is done" if event.get("accepting") else ""
        steps.append(f"{what} at {event['cost_m']:.2f} m along the plan ({where}){tail}")
    return steps
