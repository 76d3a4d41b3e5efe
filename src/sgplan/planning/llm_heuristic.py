"""h_LLM: the inadmissible heuristic from LLM guidance (reference-algorithm.md §5, made robust).

Guidance is the authors' ``llm_heuristic.yaml`` content: ``{room_uuid: {q: ["move(a, b)" |
"reach(r, o)", ...]}}`` -- for an agent in room ``room_uuid`` with the automaton in state ``q``, the
calls that finish the mission. ``move(a, b)`` goes from room uuid ``a`` to room uuid ``b``;
``reach(r, o)`` reaches object uuid ``o`` in room uuid ``r``. The authors' cost model is kept:

    h_LLM(cell, q) = |xyz(cell) - centre(target of call 1)| + sum over calls 2..n of |centre(a) - centre(b)|

(centres are the scene graph's 3-D ``location_m``; for ``reach`` the pair is room -> object). Accepting q
gives 0. Unlike the authors' code nothing crashes: an empty list gives 0, and a call that does not parse
or names an unknown id or an id of the wrong kind is skipped (the remaining calls are used) and counted
in :class:`GuidanceStats`. h_LLM is never used by the anchor queue, so it cannot affect optimality.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from sgplan.scene.model import Building

_CALL = re.compile(r"^\s*(move|reach)\s*\(\s*(\d+)\s*,\s*(\d+)\s*\)\s*$")


@dataclass
class GuidanceStats:
    """What was used and what was skipped while reading guidance (counts)."""

    entries: int = 0
    calls_used: int = 0
    calls_skipped: int = 0
    entries_skipped: int = 0
    reasons: list[str] = field(default_factory=list)
    """The first few skip reasons, for messages."""

    def skip(self, reason: str, *, entry: bool = False) -> None:
        if entry:
            self.entries_skipped += 1
        else:
            self.calls_skipped += 1
        if len(self.reasons) < 10:
            self.reasons.append(reason)


@dataclass(eq=False)
class LlmHeuristic:
    """Tabulated guidance per (room index, automaton state).

    ``leg_sum[r, q]`` metres of calls 2..n; ``target[r, q]`` the 3-D point of call 1's target;
    ``has_target[r, q]`` False where no usable call exists (then h = 0).
    """

    leg_sum: np.ndarray
    target: np.ndarray
    has_target: np.ndarray
    stats: GuidanceStats


def build_llm_heuristic(
    guidance: Mapping | None, building: Building, room_uuids: list[int], num_states: int
) -> LlmHeuristic:
    """Read ``guidance`` for the rooms ``room_uuids`` (room index -> uuid) and states ``0..num_states-1``.

    Never raises on bad guidance content: everything unusable is skipped and counted.
    """
    rooms = len(room_uuids)
    leg_sum = np.zeros((rooms, num_states))
    target = np.zeros((rooms, num_states, 3))
    has_target = np.zeros((rooms, num_states), dtype=bool)
    stats = GuidanceStats()
    index = {uuid: i for i, uuid in enumerate(room_uuids)}
    if not isinstance(guidance, Mapping):
        if guidance is not None:
            stats.skip(f"guidance is a {type(guidance).__name__}, not a mapping", entry=True)
        return LlmHeuristic(leg_sum, target, has_target, stats)
    legs_of: dict[object, tuple[np.ndarray, np.ndarray, float]] = {}  # a call recurs across entries
    for room_key, per_state in guidance.items():
        room_uuid = _as_int(room_key)
        if room_uuid not in index or not isinstance(per_state, Mapping):
            stats.skip(f"room key {room_key!r} is not a room uuid with a state mapping", entry=True)
            continue
        for q_key, calls in per_state.items():
            q = _as_int(q_key)
            if q is None or not 0 <= q < num_states or not isinstance(calls, (list, tuple)):
                stats.skip(
                    f"room {room_uuid}: state key {q_key!r} is not a state with a call list", entry=True
                )
                continue
            stats.entries += 1
            legs = []
            for call in calls:
                leg = legs_of.get(call) if isinstance(call, str) else None
                if leg is None:  # not seen yet, or unusable (read again: each use is counted)
                    leg = _leg(call, building, stats)
                    if leg is not None:
                        legs_of[call] = leg
                if leg is not None:
                    legs.append(leg)
            if legs:
                r = index[room_uuid]
                target[r, q] = legs[0][1]
                has_target[r, q] = True
                leg_sum[r, q] = sum(length for _, _, length in legs[1:])
                stats.calls_used += len(legs)
    return LlmHeuristic(leg_sum, target, has_target, stats)


def _as_int(value: object) -> int | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, str) and value.strip().isdigit():
        return int(value)
    return None


def _leg(call: object, building: Building, stats: GuidanceStats
         ) -> tuple[np.ndarray, np.ndarray, float] | None:
    """The (from, to) centres of one call and the metres between them, or None (counted) if it is
    unusable."""
    match = _CALL.match(call) if isinstance(call, str) else None
    if match is None:
        stats.skip(f"call {call!r} is not move(room, room) or reach(room, object)")
        return None
    kind, a, b = match.group(1), int(match.group(2)), int(match.group(3))
    if not building.has_room(a):
        stats.skip(f"call {call!r}: {a} is not a room uuid")
        return None
    if kind == "move" and not building.has_room(b):
        stats.skip(f"call {call!r}: {b} is not a room uuid")
        return None
    if kind == "reach" and not building.has_object(b):
        stats.skip(f"call {call!r}: {b} is not an object uuid")
        return None
    start = np.asarray(building.room(uuid=a).location_m, dtype=np.float64)
    end = building.room(uuid=b).location_m if kind == "move" else building.object(uuid=b).location_m
    end = np.asarray(end, dtype=np.float64)
    return start, end, float(np.linalg.norm(end - start))
