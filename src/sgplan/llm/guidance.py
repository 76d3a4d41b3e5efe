"""Guidance (LLM call 3): move / reach calls per (room, automaton state), checked against the scene graph.

For every room (staircases included) and every reachable, non-accepting automaton state ``q`` with
something left to do, the model gets the building (attribute hierarchy with connections), the functions
``move(room_a, room_b)`` / ``reach(room_a, object_b)``, one worked example, the whole mission (when known),
the current room and the *remaining mission* of ``q``: the propositions to make true in order, read off a
shortest automaton path to acceptance (:func:`sgplan.logic.remaining_mission`), and the propositions that
every state of that path forbids. The reply's ``<command>`` elements are parsed as XML (a regex fallback
reads replies that are not well-formed XML) and every call is validated:

- ``move(a, b)``: ``a`` and ``b`` are rooms and the scene graph connects ``a`` to ``b``;
- ``reach(r, o)``: ``r`` is a room, ``o`` an object, and ``o`` lies in ``r``.

Invalid calls are dropped and counted (:class:`GuidanceReport`); kept calls that do not form one route
from the current room (:func:`route_break`) are counted too, but kept. The remaining mission's automaton
path avoids labels that cannot hold at one cell (:func:`label_costs`), so the model is never asked to be
in two rooms at once. Kept calls are stored in the authors' ``llm_heuristic.yaml`` form with bare
uuids: ``{room_uuid: {q: ["move(2, 9)", "reach(5, 21)"]}}``.
States that are sinks or need nothing made true get an empty list without any call; a failed call gives
an empty list too (h_LLM is then 0 there), is counted, and is not cached, so a re-run retries it.

:func:`generate_guidance` asks for every entry at once (with
:func:`~sgplan.llm.client.complete_many`'s concurrency limit; a hosted API's rate limit is the live
client's ``requests_per_minute``).
:class:`LLMGuide` has the same ``guide(building, automaton, ap_actions)`` contract as the offline
:class:`~sgplan.llm.offline.SymbolicGuide`.
"""

from __future__ import annotations

import re
import threading
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from sgplan.errors import LLMError, MissionError
from sgplan.llm.client import ChatBackend, ChatResult, complete_many
from sgplan.llm.config import one_line
from sgplan.llm.grounding import environment_text, with_environment
from sgplan.llm.prompts import load_prompt
from sgplan.llm.records import RunRecord
from sgplan.logic import Automaton, remaining_mission
from sgplan.logic.tokens import action_entity, canonical_action
from sgplan.scene.model import Building

Guidance = dict[int, dict[int, list[str]]]
"""``{room_uuid: {state: ["move(a, b)", "reach(r, o)", ...]}}`` with bare uuids (llm_heuristic.yaml)."""

DEFAULT_PARAMS: Mapping[str, Any] = {"temperature": 0.0, "max_tokens": 512}
"""Sampling parameters of guidance calls unless the caller gives others."""

_CALL = re.compile(
    r"^\s*(move|reach)\s*\(\s*((?:room_|object_)?\d+)\s*,\s*((?:room_|object_)?\d+)\s*\)\s*;?\s*$"
)
_COMMAND = re.compile(r"<command>(.*?)</command>", re.DOTALL)
_MAX_REASONS = 20


@dataclass
class GuidanceReport:
    """Counts of a guidance run (all counts are entries or calls, not tokens).

    ``asked``: entries sent to the model; ``skipped``: entries with nothing to do (no call made);
    ``failed``: entries whose call raised :class:`LLMError`; ``calls_kept`` / ``calls_dropped``: calls
    that passed / failed validation; ``routes_broken``: entries whose kept calls do not form one route
    (:func:`route_break`); ``reasons``: the first few drop, break or failure reasons.
    """

    asked: int = 0
    skipped: int = 0
    failed: int = 0
    calls_kept: int = 0
    calls_dropped: int = 0
    routes_broken: int = 0
    reasons: list[str] = field(default_factory=list)

    def note(self, reason: str) -> None:
        if len(self.reasons) < _MAX_REASONS:
            self.reasons.append(reason)


# -- the remaining mission --------------------------------------------------------------------------------


def _spoken(action: str) -> str:
    """``enter(room_5)`` -> ``enter room_5``, as the prompt's remaining mission reads."""
    return action.replace("(", " ").replace(")", "")


IMPLAUSIBLE_LABEL_COST = 1000.0
"""Automaton-path cost of a label the scene graph makes implausible (vs 1 for any other label): high
enough that a path using one is chosen only when no other path exists."""


def label_costs(
    automaton: Automaton, building: Building, ap_actions: Mapping[str, str] | None = None
) -> np.ndarray:
    """``(num_labels,)``: 1 per label, :data:`IMPLAUSIBLE_LABEL_COST` for a label that the scene graph
    makes implausible at one cell -- two rooms entered at once, or an object reached from a room that does
    not hold it (possible only across a wall within the reach radius)."""
    actions = dict(ap_actions or {})
    rooms: dict[int, int] = {}  # proposition index -> the room uuid it enters
    objects: dict[int, int] = {}  # proposition index -> the object uuid it reaches
    for i, ap in enumerate(automaton.aps):
        kind, _, number = (action_entity(actions.get(ap, ap)) or "").partition("_")
        if number.isdigit() and kind == "room":
            rooms[i] = int(number)
        elif number.isdigit() and kind == "object":
            objects[i] = int(number)
    labels = np.arange(automaton.num_labels)

    def holds(i: int) -> np.ndarray:
        return ((labels >> i) & 1).astype(bool)

    rooms_entered = np.zeros(len(labels), dtype=np.int64)
    for i in rooms:
        rooms_entered += holds(i)
    implausible = rooms_entered > 1
    for i, obj in objects.items():
        if building.has_object(obj):
            home = building.object(uuid=obj).room_uuid
            for j, room in rooms.items():
                if room != home:
                    implausible |= holds(i) & holds(j)
    return np.where(implausible, IMPLAUSIBLE_LABEL_COST, 1.0)


def remaining_text(automaton: Automaton, state: int, ap_actions: Mapping[str, str] | None = None,
                   weights: np.ndarray | None = None) -> str | None:
    """The remaining mission of ``state`` in words, or ``None`` when there is nothing to ask.

    Steps (what to make true, in order) and what to avoid throughout come from
    :func:`sgplan.logic.remaining_mission` (with ``weights`` per label, e.g. :func:`label_costs`). ``None``
    for sinks, accepting states, and states where nothing needs to be made true. ``ap_actions`` maps
    proposition names to action tokens (``{"p1": "enter(room_2)"}``).
    """
    remaining = remaining_mission(automaton, state, weights)
    if remaining is None or not remaining.to_make_true:
        return None
    actions = dict(ap_actions or {})

    def action(ap: str) -> str:
        return _spoken(canonical_action(actions.get(ap, ap)) or ap)

    steps = [" and ".join(sorted(action(ap) for ap in props)) for props in remaining.to_make_true]
    text = "; ".join(f"{k}. {s}" for k, s in enumerate(steps, start=1)) + "."
    avoid = [ap for ap in automaton.aps if ap in remaining.to_keep_false]
    if avoid:
        text += " Throughout: never " + ", never ".join(action(ap) for ap in avoid) + "."
    return text


# -- replies ----------------------------------------------------------------------------------------------


def parse_commands(reply: str) -> list[str]:
    """The texts of the ``<command>`` elements of a reply, in order.

    The reply is wrapped in ``<response>...</response>`` and parsed as XML; if that fails (prose with a
    stray ``&`` or ``<``), the ``<command>...</command>`` spans are read with a regular expression.
    """
    try:
        root = ET.fromstring(f"<response>{reply}</response>")
    except ET.ParseError:
        return [m.strip() for m in _COMMAND.findall(reply)]
    return [(element.text or "").strip() for element in root.iter("command")]


def _entity(text: str, building: Building) -> tuple[str, int] | None:
    """``("room" | "object", uuid)`` of ``room_5`` / ``object_21`` / a bare uuid, if the building has it."""
    kind, _, number = text.rpartition("_")
    uuid = int(number)
    if kind in ("", "room") and building.has_room(uuid):
        return "room", uuid
    if kind in ("", "object") and building.has_object(uuid):
        return "object", uuid
    return None


def validate_call(text: str, building: Building) -> tuple[str | None, str]:
    """``(canonical call, "")`` for a valid call, else ``(None, reason)``.

    The canonical form is the authors' ``move(2, 9)`` / ``reach(5, 21)`` with bare uuids; the model may
    write ``room_2`` / ``object_21`` or bare uuids.
    """
    match = _CALL.match(text)
    if match is None:
        return None, f"{one_line(text, 60)!r} is not move(room, room) or reach(room, object)"
    kind, a_text, b_text = match.groups()
    a, b = _entity(a_text, building), _entity(b_text, building)
    if a is None or a[0] != "room":
        return None, f"{text.strip()}: {a_text} is not a room of the building"
    want = "room" if kind == "move" else "object"
    if b is None or b[0] != want:
        return (
            None,
            f"{text.strip()}: {b_text} is not {'a room' if want == 'room' else 'an object'} of the building",
        )
    room = building.room(uuid=a[1])
    if kind == "move" and b[1] not in room.connected_room_uuids:
        return None, f"{text.strip()}: room_{a[1]} does not connect to room_{b[1]}"
    if kind == "reach" and building.object(uuid=b[1]).room_uuid != room.uuid:
        return None, f"{text.strip()}: object_{b[1]} is not in room_{a[1]}"
    return f"{kind}({a[1]}, {b[1]})", ""


_CANONICAL = re.compile(r"^(move|reach)\((\d+), (\d+)\)$")


def route_break(calls: list[str], room_uuid: int) -> str:
    """Why canonical ``calls`` do not form one route from room ``room_uuid`` (``""`` if they do).

    A route's first call starts in ``room_uuid``, each next one where the previous ended (``move(a, b)``
    ends in ``b``, ``reach(r, o)`` in ``r``). A break is reported, not repaired: measured on GPT-4's
    guidance (benchmarks/guidance_route_rule.py), cutting lists at the break made h_LLM weaker, not better.
    """
    here = room_uuid
    for k, call in enumerate(calls):
        match = _CANONICAL.match(call)
        if match is None:
            raise ValueError(f"{call!r} is not a canonical call (see validate_call)")
        kind, start, end = match.group(1), int(match.group(2)), int(match.group(3))
        if start != here:
            where = "the current room" if k == 0 else f"where {calls[k - 1]} ended"
            return f"{call} starts in room_{start}, not in {where} (room_{here})"
        here = end if kind == "move" else start
    return ""


# -- asking -----------------------------------------------------------------------------------------------


class _Asker:
    """Prompts for (room, state) entries and the handling of their replies, shared by batch and lazy use."""

    def __init__(
        self,
        building: Building,
        automaton: Automaton,
        backend: ChatBackend,
        record: RunRecord,
        *,
        ap_actions: Mapping[str, str] | None,
        mission_text: str | None,
        params: Mapping[str, Any],
    ) -> None:
        self.building = building
        self.automaton = automaton
        self.backend = backend
        self.record = record
        self.params = dict(params)
        self.report = GuidanceReport()
        self._lock = threading.Lock()
        self._prompt = load_prompt("guidance")
        self._version = with_environment(self._prompt.version)
        self._environment = environment_text(building)
        self._context = (f"The whole mission is: {mission_text.strip()} Part of it may already be done."
                         if mission_text else "")
        reachable = automaton.reachable_states()
        self.states = [q for q in range(automaton.num_states) if reachable[q] and not automaton.accepting[q]]
        self._check_actions(ap_actions or {})
        costs = label_costs(automaton, building, ap_actions)
        self._remaining = {q: remaining_text(automaton, q, ap_actions, costs) for q in self.states}

    def _check_actions(self, ap_actions: Mapping[str, str]) -> None:
        for ap in self.automaton.aps:
            key = action_entity(ap_actions.get(ap, ap))
            if key is None:
                raise MissionError(
                    f"automaton proposition {ap!r} has no action enter(room_<id>)/reach(object_<id>)"
                )

    def messages(self, room_uuid: int, q: int) -> list[dict[str, str]] | None:
        """The chat for entry (room, q), or ``None`` (counted as skipped) when nothing is left to do."""
        remaining = self._remaining.get(q)
        if remaining is None:
            with self._lock:
                self.report.skipped += 1
            return None
        return self._prompt.messages(environment=self._environment, mission_context=self._context,
                                     room=f"room_{room_uuid}", remaining=remaining)

    def accept(
        self, room_uuid: int, q: int, messages: list[dict[str, str]], outcome: ChatResult | LLMError
    ) -> list[str]:
        """Record the call, then parse and validate its reply; the valid calls of the entry."""
        context = {"room": room_uuid, "state": q}
        index = self.record.add_call(self.backend, messages, self.params, outcome, step="guidance",
                                     prompt_version=self._version, context=context)
        with self._lock:
            self.report.asked += 1
            if isinstance(outcome, LLMError):
                self.report.failed += 1
                self.report.note(f"room_{room_uuid}, state {q}: {one_line(outcome, 200)}")
                return []
        calls, dropped = [], []
        for text in parse_commands(outcome.content):
            call, reason = validate_call(text, self.building)
            if call is None:
                dropped.append(reason)
            else:
                calls.append(call)
        broken = route_break(calls, room_uuid)
        if outcome.finish_reason == "length":  # cut off by max_tokens: the route may be incomplete
            self.record.event("guidance-reply-truncated", call=index, room=room_uuid, state=q)
        with self._lock:
            self.report.calls_kept += len(calls)
            self.report.calls_dropped += len(dropped)
            self.report.routes_broken += bool(broken)
            for reason in dropped:
                self.report.note(f"room_{room_uuid}, state {q}: {reason}")
            if broken:
                self.report.note(f"room_{room_uuid}, state {q}: route broken (calls kept): {broken}")
        if dropped or not calls or broken:
            self.record.event("guidance-calls-dropped", call=index, room=room_uuid, state=q, kept=len(calls),
                              dropped=dropped, route_break=broken or None)
        return calls


def generate_guidance(
    building: Building,
    automaton: Automaton,
    backend: ChatBackend,
    record: RunRecord,
    *,
    ap_actions: Mapping[str, str] | None = None,
    mission_text: str | None = None,
    params: Mapping[str, Any] = DEFAULT_PARAMS,
    max_concurrency: int = 4,
) -> tuple[Guidance, GuidanceReport]:
    """Guidance for every room x reachable non-accepting state, asked in one batch.

    Parameters
    ----------
    ap_actions:
        Proposition name -> action token, for automata over ``p1..pN`` (``Mission.descriptions``).
    mission_text:
        The (grounded) mission, shown to the model as context.
    max_concurrency:
        Calls in flight at once.

    Returns
    -------
    (Guidance, GuidanceReport)
        Every room has an entry for every reachable non-accepting state.

    Raises
    ------
    LLMError
        Every call that was made failed (the first failure is reported); partial failures are counted.
    """
    asker = _Asker(building, automaton, backend, record, ap_actions=ap_actions, mission_text=mission_text,
                   params=params)
    guidance: Guidance = {room.uuid: {} for room in building.rooms()}
    pending = []
    for room in building.rooms():
        for q in asker.states:
            messages = asker.messages(room.uuid, q)
            if messages is None:
                guidance[room.uuid][q] = []
            else:
                pending.append((room.uuid, q, messages))
    outcomes = complete_many(
        backend, [(m, asker.params) for _, _, m in pending], max_concurrency=max_concurrency
    )
    for (room_uuid, q, messages), outcome in zip(pending, outcomes):
        guidance[room_uuid][q] = asker.accept(room_uuid, q, messages, outcome)
    report = asker.report
    record.event(
        "guidance", asked=report.asked, skipped=report.skipped, failed=report.failed,
        calls_kept=report.calls_kept, calls_dropped=report.calls_dropped, routes_broken=report.routes_broken,
    )
    if pending and report.failed == len(pending):
        first = next(o for o in outcomes if isinstance(o, LLMError))
        raise LLMError(f"all {len(pending)} guidance calls failed; the first: {first}")
    return guidance, report


class LLMGuide:
    """Batch guidance from a language model, with the offline guide's ``guide(...)`` contract.

    The report of the last run is :attr:`report`; calls go to :attr:`record`.
    """

    def __init__(
        self,
        backend: ChatBackend,
        *,
        record: RunRecord | None = None,
        mission_text: str | None = None,
        params: Mapping[str, Any] = DEFAULT_PARAMS,
        max_concurrency: int = 4,
    ) -> None:
        self.backend = backend
        self.record = record if record is not None else RunRecord(backend.label)
        self.mission_text = mission_text
        self.params = dict(params)
        self.max_concurrency = max_concurrency
        self.report = GuidanceReport()

    @property
    def name(self) -> str:
        return f"llm:{self.backend.model}"

    def guide(
        self, building: Building, automaton: Automaton, ap_actions: Mapping[str, str] | None = None
    ) -> Guidance:
        """``{room_uuid: {q: [calls]}}`` for every room and reachable non-accepting state; see
        :func:`generate_guidance`."""
        guidance, self.report = generate_guidance(
            building, automaton, self.backend, self.record, ap_actions=ap_actions,
            mission_text=self.mission_text, params=self.params, max_concurrency=self.max_concurrency,
        )
        return guidance
