"""Scoring a mission translator on a set of missions with gold formulas, by automaton equivalence.

A mission (:class:`EvalMission`, read from a JSONL set by :func:`sgplan.llm.evaluate.load_jsonl_set`) has a
scene, a text and either a gold formula (infix, with the shorthand ``r2`` = ``"enter(room_2)"``, ``o27`` =
``"reach(object_27)"``) or the fragment of the error the translator must raise. A translation is right
when its LTLf automaton accepts exactly the gold's words among the words with at most one room per cell
(the only ones a robot can produce) and, given the scene, with every object reached only from its room,
or when it raises the expected error.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from sgplan.errors import AutomatonError, MissionError
from sgplan.logic import (
    Always,
    Atom,
    Formula,
    Implies,
    atoms,
    compact_difference_word,
    ltlf_to_compact_dfa,
    possible_labels,
)
from sgplan.logic.tokens import action_entity
from sgplan.scene.model import Building

if TYPE_CHECKING:
    from sgplan.llm.protocols import MissionTranslator

Outcome = Literal["right", "refused", "wrong"]

_SHORTHAND = re.compile(r"\b([ro])(\d+)\b")


@dataclass(frozen=True)
class EvalMission:
    """One mission of the set; exactly one of ``gold`` and ``expect_error`` is set; ``start_floor`` is the
    robot's start floor when the mission gives it."""

    id: str
    scene: str
    text: str
    gold: Formula | None
    expect_error: str | None
    must_pass: bool
    paper: bool
    note: str
    start_floor: int | None = None


@dataclass(frozen=True)
class EvalResult:
    """How a translator did on one mission: ``right``, ``refused`` (a MissionError where a formula was
    expected) or ``wrong`` (a formula not equivalent to the gold, or the wrong error or none);
    ``detail`` says what happened (the error, or a word on which translation and gold disagree);
    ``formula`` is the translation (``None`` when the translator raised)."""

    mission: EvalMission
    outcome: Outcome
    detail: str
    formula: Formula | None = None


def expand_shorthand(text: str) -> str:
    """``F(r2 & o27)`` -> ``F("enter(room_2)" & "reach(object_27)")``."""
    return _SHORTHAND.sub(
        lambda m: f'"enter(room_{m.group(2)})"' if m.group(1) == "r" else f'"reach(object_{m.group(2)})"',
        text
    )


def scene_facts(propositions: Iterable[str], building: Building) -> list[Formula]:
    """What the scene makes true of every path, for the objects among ``propositions``: each
    ``reach(object_u)`` holds only in its room (``G(reach(object_u) -> enter(room_r))``).

    Raises :class:`MissionError` for an ``enter(...)`` / ``reach(...)`` proposition naming no room or object
    of ``building``."""
    placed = rooms_of_objects(propositions, building)
    return [Always(Implies(Atom(p), Atom(room))) for p, room in placed.items()]


def rooms_of_objects(propositions: Iterable[str], building: Building) -> dict[str, str]:
    """``reach(object_u)`` -> ``enter(room_r)`` (its room) for the objects among ``propositions``.

    Raises :class:`MissionError` for an ``enter(...)`` / ``reach(...)`` proposition naming no room or object
    of ``building``."""
    rooms = {room.key for room in building.rooms()}
    room_of = {obj.key: room.key for room in building.rooms() for obj in room.objects.values()}
    found: dict[str, str] = {}
    for p in propositions:
        key = action_entity(p)
        if key in room_of:
            found[p] = f"enter({room_of[key]})"
        elif key not in rooms:
            raise MissionError(f"proposition {p!r} names no room or object of the scene {building.name!r}")
    return found


MAX_COMPARED_APS = 24
"""At most this many propositions in a comparison (its label arrays hold ``2**n`` entries)."""


def same_language(a: Formula, b: Formula, building: Building | None = None) -> tuple[bool, str]:
    """Whether ``a`` and ``b`` accept the same finite words with at most one room per letter (and, given
    ``building``, with every object reached only from its room, see :func:`scene_facts`); if not, a
    shortest such word on which they differ, as text.

    The automata are built over the possible letters only (:func:`~sgplan.logic.ltlf_to_compact_dfa`),
    so a mission over many rooms compares cheaply. Raises :class:`AutomatonError` when they are too large
    to build, or name more than :data:`MAX_COMPARED_APS` propositions."""
    union = list(dict.fromkeys(atoms(a) + atoms(b)))
    room_of = rooms_of_objects(union, building) if building is not None else {}
    union = list(dict.fromkeys(union + list(room_of.values())))
    if len(union) > MAX_COMPARED_APS:
        raise AutomatonError(f"{len(union)} propositions, more than the {MAX_COMPARED_APS} compared")
    possible = _possible_letters(union, room_of)
    word = compact_difference_word(ltlf_to_compact_dfa(a, union, possible),
                                   ltlf_to_compact_dfa(b, union, possible))
    if word is None:
        return True, ""
    shown = " ".join("{" + ", ".join(sorted(letter)) + "}" for letter in word) or "the empty word"
    return False, f"they differ on {shown}"


def _possible_letters(aps: list[str], room_of: dict[str, str]) -> np.ndarray:
    """``(2**len(aps),)`` bool: the labels with at most one room, in which each proposition of ``room_of``
    holds only with its room's."""
    possible = possible_labels(aps, [[p for p in aps if p.startswith("enter(")]])
    labels = np.arange(possible.size, dtype=np.int64)
    def holds(p: str) -> np.ndarray:
        return (labels >> aps.index(p) & 1).astype(bool)

    for p, room in room_of.items():
        possible &= ~(holds(p) & ~holds(room))
    return possible


def evaluate(
    translator: MissionTranslator, missions: Iterable[EvalMission], building_of: Callable[[str], Building]
) -> list[EvalResult]:
    """Translate every mission with ``translator`` and classify the outcome (see :class:`EvalResult`).

    Formulas are compared under the scene's facts (:func:`same_language` with the mission's building).
    Errors other than :class:`MissionError` propagate: they are bugs (or a failing language-model
    server), not refusals.
    """
    results = []
    for m in missions:
        building = building_of(m.scene)
        backend = translator.starting_on(m.start_floor) if m.start_floor is not None else translator
        try:
            formula = backend.translate(m.text, building).formula
        except MissionError as exc:
            message = str(exc)
            if m.expect_error is not None:
                ok = m.expect_error in message
                results.append(EvalResult(m, "right" if ok else "wrong", message))
            else:
                results.append(EvalResult(m, "refused", message))
            continue
        if m.gold is None:
            results.append(EvalResult(m, "wrong",
                                      f"expected an error containing {m.expect_error!r}, got {formula}",
                                      formula))
            continue
        try:
            same, why = same_language(formula, m.gold, building)
        except AutomatonError as exc:  # too large to compare: not shown to mean the gold
            same, why = False, f"cannot be compared with the gold ({exc})"
        results.append(EvalResult(m, "right" if same else "wrong",
                                  f"got {formula}" + ("" if same else f"; {why}"),
                                  formula))
    return results
