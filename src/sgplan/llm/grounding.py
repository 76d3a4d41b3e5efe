"""Grounding (LLM call 1): rewrite a mission so every room/object reference is its unique ID.

The model receives the attribute hierarchy (floors -> rooms with their connections -> objects, every entity
tagged ``room_<uuid>`` / ``object_<uuid>``) and the mission, and answers one JSON object::

    {"grounded": "Wash your hands at object_12 in room_3, ...",
     "problems": [{"phrase": "the bathroom", "kind": "ambiguous", "candidates": ["room_3", "room_5"]}]}

The reply is checked: it must be that JSON object, and every ID in it must exist in the building. A reply
failing a check is sent back with the precise reason, a bounded number of times. References the model
reports as unresolved or ambiguous are never guessed: they end the pipeline with a :class:`RephraseError`
that names each phrase and its candidates, so the user can say which one is meant.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal

from sgplan.errors import MissionError
from sgplan.llm.client import ChatBackend
from sgplan.llm.config import one_line
from sgplan.llm.prompts import load_prompt
from sgplan.llm.records import RunRecord
from sgplan.scene.hierarchy import attribute_hierarchy
from sgplan.scene.model import Building

ID_PATTERN = re.compile(r"\b(room|object)_(\d+)\b")
"""A unique ID in grounded text: ``room_<uuid>`` or ``object_<uuid>``."""

DEFAULT_PARAMS: Mapping[str, Any] = {"temperature": 0.0}
"""Sampling parameters of the grounding and translation calls unless the caller gives others."""


class RephraseError(MissionError):
    """The mission cannot be translated as written; the user must rephrase it.

    ``problems`` lists the references at fault (empty when the cause is repeated invalid replies).
    """

    def __init__(self, message: str, problems: Sequence[ReferenceProblem] = ()) -> None:
        super().__init__(message)
        self.problems = tuple(problems)


@dataclass(frozen=True)
class ReferenceProblem:
    """A phrase of the mission the model could not ground: no match, or several with no way to choose.

    ``candidates`` are IDs of the building (IDs the model invented are dropped).
    """

    phrase: str
    kind: Literal["unresolved", "ambiguous"]
    candidates: tuple[str, ...]


@dataclass(frozen=True)
class Grounding:
    """A grounded mission: ``grounded_text`` with IDs, and ``ids`` found in it (in order of appearance)."""

    text: str
    grounded_text: str
    ids: tuple[str, ...]


class ReplyError(ValueError):
    """A model reply that fails a check; the message is sent back to the model for a corrected reply."""


def extract_ids(text: str) -> tuple[str, ...]:
    """The distinct ``room_<n>`` / ``object_<n>`` IDs of ``text`` in order of first appearance.

    >>> extract_ids("Visit room_2, then reach object_27 in room_2.")
    ('room_2', 'object_27')
    """
    return tuple(dict.fromkeys(m.group(0) for m in ID_PATTERN.finditer(text)))


def building_ids(building: Building) -> frozenset[str]:
    """Every entity ID of ``building`` (``room_<uuid>`` and ``object_<uuid>``)."""
    return frozenset([r.key for r in building.rooms()] + [o.key for o in building.objects()])


def environment_text(building: Building) -> str:
    """The building as given to the model: the hierarchy preamble and the attribute hierarchy with
    connections."""
    return load_prompt("hierarchy").text(hierarchy=attribute_hierarchy(building, connections=True).rstrip())


def with_environment(version: str) -> str:
    """The version recorded for a prompt that embeds :func:`environment_text`, e.g.
    ``grounding/1+hierarchy/1``."""
    return f"{version}+{load_prompt('hierarchy').version}"


def describe_id(building: Building, key: str) -> str:
    """``room_5 (bathroom, floor 0)`` / ``object_21 (sink in room_5, floor 0)``, for messages."""
    kind, uuid = key.split("_")
    if kind == "room":
        room = building.room(uuid=int(uuid))
        return f"{key} ({room.name}, floor {room.floor})"
    obj = building.object(uuid=int(uuid))
    return f"{key} ({obj.name} in room_{obj.room_uuid}, floor {building.floor_of_object(obj)})"


def strip_fences(reply: str) -> str:
    """The reply without a surrounding Markdown code fence (models often add one)."""
    text = reply.strip()
    fence = re.fullmatch(r"```[\w-]*\s*\n?(.*?)\n?```", text, flags=re.DOTALL)
    return fence.group(1).strip() if fence else text


def parse_grounding_reply(reply: str, known: frozenset[str]) -> tuple[str, list[ReferenceProblem]]:
    """The grounded text and the reported problems of a grounding reply.

    Raises
    ------
    ReplyError
        not one JSON object with a string ``grounded`` and a list ``problems`` of ``{phrase, kind,
        candidates}``; or the grounded text names an ID outside ``known``.
    """
    text = strip_fences(reply)
    start, end = text.find("{"), text.rfind("}")
    if start < 0 or end < start:
        raise ReplyError("it contains no JSON object")
    try:
        data = json.loads(text[start : end + 1])
    except ValueError as exc:
        raise ReplyError(f"it is not valid JSON ({one_line(exc)})") from None
    grounded = data.get("grounded") if isinstance(data, dict) else None
    problems = data.get("problems", []) if isinstance(data, dict) else None
    if not isinstance(grounded, str) or not grounded.strip() or not isinstance(problems, list):
        raise ReplyError('it needs a non-empty string "grounded" and a list "problems"')
    invented = [key for key in extract_ids(grounded) if key not in known]
    if invented:
        raise ReplyError(
            f"{', '.join(invented)} {'is' if len(invented) == 1 else 'are'} not an ID of this building"
        )
    found = []
    for item in problems:
        if not isinstance(item, dict) or not isinstance(item.get("phrase"), str):
            raise ReplyError('each entry of "problems" needs a "phrase" string')
        kind = item.get("kind", "unresolved")
        candidates = item.get("candidates") or []
        if kind not in ("unresolved", "ambiguous") or not isinstance(candidates, list):
            raise ReplyError('each problem needs "kind" "unresolved" or "ambiguous" and a list "candidates"')
        real = tuple(dict.fromkeys(str(c) for c in candidates if str(c) in known))
        found.append(ReferenceProblem(item["phrase"], kind, real))
    return grounded.strip(), found


def rephrase_message(text: str, problems: Sequence[ReferenceProblem], building: Building) -> str:
    """One or two sentences naming each problem phrase and its candidates, asking for a rephrased mission."""
    parts = []
    for p in problems:
        if p.kind == "ambiguous" and p.candidates:
            listed = ", ".join(describe_id(building, c) for c in p.candidates)
            parts.append(f"{p.phrase!r} could be any of {listed}")
        else:
            parts.append(f"{p.phrase!r} matches no room or object of building {building.name!r}")
    return (
        f"cannot ground the mission {one_line(text, 120)!r}: {'; '.join(parts)}. "
        "Rephrase it so that each reference names exactly one room or object (e.g. add the floor or the "
        "room)."
    )


def ground_mission(
    text: str,
    building: Building,
    backend: ChatBackend,
    record: RunRecord,
    *,
    max_repairs: int = 2,
    params: Mapping[str, Any] = DEFAULT_PARAMS,
) -> Grounding:
    """Ask ``backend`` to ground ``text`` against ``building``; every call goes into ``record``.

    Parameters
    ----------
    max_repairs:
        How many times an unusable reply (see :func:`parse_grounding_reply`) is sent back with the reason.

    Raises
    ------
    RephraseError
        The model reports unresolved or ambiguous references; the grounded text names no room or object;
        or every reply was unusable.
    LLMError
        The backend failed (network, server, replay miss).
    """
    if not text.strip():
        raise RephraseError("the mission text is empty; say what the robot should do")
    prompt, repair = load_prompt("grounding"), load_prompt("grounding_repair")
    known = building_ids(building)
    messages = prompt.messages(environment=environment_text(building), mission=text.strip())
    version = with_environment(prompt.version)
    last_error = ""
    for attempt in range(max_repairs + 1):
        index, result = record.complete(backend, messages, params, step="grounding", prompt_version=version,
                                        context={"attempt": attempt})
        try:
            grounded, problems = parse_grounding_reply(result.content, known)
        except ReplyError as exc:
            last_error = str(exc)
            record.event("grounding-reply-rejected", call=index, reason=last_error)
            messages = [*messages, {"role": "assistant", "content": result.content},
                        *repair.messages(error=last_error)]
            version = with_environment(repair.version)
            continue
        if problems:
            record.event("grounding-problems", call=index,
                         problems=[{"phrase": p.phrase, "kind": p.kind, "candidates": list(p.candidates)}
                                   for p in problems])
            raise RephraseError(rephrase_message(text, problems, building), problems)
        ids = extract_ids(grounded)
        if not ids:
            record.event("grounding-empty", call=index)
            raise RephraseError(
                f"the mission {one_line(text, 120)!r} names no room or object of building {building.name!r}; "
                "rephrase it with the rooms and objects the robot should visit or avoid"
            )
        record.event("grounded", call=index, grounded_text=grounded, ids=list(ids))
        return Grounding(text.strip(), grounded, ids)
    raise RephraseError(
        f"the model gave no usable grounding of {one_line(text, 120)!r} in {max_repairs + 1} attempts "
        f"(last problem: {last_error}); rephrase the mission in simpler sentences or use another model"
    )
