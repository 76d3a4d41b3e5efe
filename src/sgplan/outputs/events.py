"""The events along a planned path: where each proposition became true, and where the automaton moved.

An event is tied to the path row where it happens and carries the path cost up to that row, so a robot
(or a person) can tell "reached the sink (object_12) after 7.4 m, mission state 1 -> 2".
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Literal

import numpy as np

from sgplan.errors import SgplanError
from sgplan.logic.automaton import Automaton
from sgplan.scene.labels import Proposition
from sgplan.scene.model import Building

EventKind = Literal["proposition", "state"]


@dataclass(frozen=True)
class Event:
    """One event at path row ``index`` (cell ``row, col`` on ``floor``), after ``cost_m`` metres.

    ``kind == "proposition"``: ``proposition`` (the automaton's name, e.g. ``p1``) became true there;
    ``meaning`` is its token (``enter(room_5)``) and ``entity`` what it names (``kitchen``).
    ``kind == "state"``: the automaton moved ``from_state -> to_state`` there; ``accepting`` says whether
    the new state is accepting.
    """

    index: int
    kind: EventKind
    cost_m: float
    floor: int
    row: int
    col: int
    proposition: str | None = None
    meaning: str | None = None
    entity: str | None = None
    from_state: int | None = None
    to_state: int | None = None
    accepting: bool | None = None

    def to_dict(self) -> dict[str, object]:
        return {key: value for key, value in asdict(self).items() if value is not None}

    def describe(self) -> str:
        """One readable line, e.g. ``"12.40 m: enter(room_5) (kitchen) became true at (40, 61) floor 0"``."""
        where = f"at ({self.row}, {self.col}) floor {self.floor}"
        if self.kind == "proposition":
            what = self.meaning or self.proposition
            return (
                f"{self.cost_m:.2f} m: {what}{f' ({self.entity})' if self.entity else ''} became true {where}"
            )
        tail = " (accepting: mission done)" if self.accepting else ""
        return f"{self.cost_m:.2f} m: mission state {self.from_state} -> {self.to_state} {where}{tail}"


def _entity_name(building: Building, token: str | None) -> str | None:
    """The category or class named by ``enter(room_<u>)`` / ``reach(object_<u>)``, else ``None``."""
    if token is None:
        return None
    try:
        prop = Proposition.parse(token)
    except SgplanError:
        return None
    if prop.kind == "enter" and building.has_room(prop.uuid):
        return building.room(uuid=prop.uuid).name
    if prop.kind == "reach" and building.has_object(prop.uuid):
        return building.object(uuid=prop.uuid).name
    return None


def path_events(
    path: np.ndarray,
    costs_m: np.ndarray,
    labels: np.ndarray,
    automaton: Automaton,
    building: Building,
    descriptions: Mapping[str, str] | None = None,
    start_state: int | None = None,
) -> list[Event]:
    """The events of ``path`` in order (a proposition true at the start counts as becoming true there).

    Parameters
    ----------
    path:
        ``(n, 4)`` ``[row, col, floor, q]`` rows.
    costs_m:
        ``(n,)`` cumulative path cost at each row (metres, 0 at the start).
    labels:
        the ``(floors, rows, cols)`` label raster the path was planned with (bit ``i`` =
        ``automaton.aps[i]``).
    automaton:
        the mission DFA; its initial state precedes the start row.
    descriptions:
        proposition name -> token (``Mission.descriptions``); names are used as they are without it.
    start_state:
        the state before the start row for a path that resumes a mission (the state the robot was in
        there); default the automaton's initial state.
    """
    rows = np.asarray(path, dtype=np.int64)
    masks = labels[rows[:, 2], rows[:, 0], rows[:, 1]].astype(np.int64)
    previous_mask = np.concatenate([[0], masks[:-1]])
    before = automaton.initial if start_state is None else int(start_state)
    previous_q = np.concatenate([[before], rows[:-1, 3]])
    descriptions = descriptions or {}
    events = []
    for k in np.flatnonzero((masks & ~previous_mask) | (rows[:, 3] != previous_q)).tolist():
        row, col, floor, q = (int(v) for v in rows[k])
        cost_m = float(costs_m[k])
        new = int(masks[k] & ~previous_mask[k])
        for bit, ap in enumerate(automaton.aps):
            if new >> bit & 1:
                meaning = descriptions.get(ap, ap)
                events.append(
                    Event(
                        k, "proposition", cost_m, floor, row, col, proposition=ap, meaning=meaning,
                        entity=_entity_name(building, meaning),
                    )
                )
        if q != previous_q[k]:
            events.append(
                Event(
                    k, "state", cost_m, floor, row, col, from_state=int(previous_q[k]), to_state=q,
                    accepting=bool(automaton.accepting[q]),
                )
            )
    return events
