"""A mission: its text, grounded text, formula, automaton, propositions and LLM guidance.

:func:`compile_mission` makes one from a formula (its minimal DFA, LTLf); the authors' mission folders are
read and written by :mod:`sgplan.mission.folder`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from sgplan.errors import FormulaError, MissionError
from sgplan.logic import Automaton, Formula, atoms, ltlf_to_dfa, parse_infix, parse_prefix, parse_tokens
from sgplan.scene.labels import Proposition, label_raster
from sgplan.scene.model import Building
from sgplan.scene.reach import DEFAULT_REACH_MODEL

Guidance = Mapping[Any, Mapping[Any, Sequence[str]]]
"""LLM guidance: ``{room_uuid: {automaton state: ["move(a, b)" | "reach(r, o)", ...]}}``."""

@dataclass(eq=False)
class Mission:
    """A mission ready to plan.

    ``propositions`` maps every proposition name of ``automaton.aps`` (e.g. ``p1`` in the authors'
    folders, or the action token ``enter(room_2)`` itself) to what it means in the scene.
    """

    automaton: Automaton
    propositions: dict[str, Proposition]
    formula: Formula | None = None
    text: str | None = None
    grounded_text: str | None = None
    guidance: Guidance | None = None
    source: Path | None = None
    notes: list[str] = field(default_factory=list)
    """Non-fatal remarks found while loading (e.g. unused propositions)."""
    set_aside: tuple[str, ...] = ()
    """Words of the mission text the translator did not read because they ask nothing (*We're hosting dinner
    tonight.*), as typed: the explanation says them back as not part of the mission."""

    def __post_init__(self) -> None:
        missing = [ap for ap in self.automaton.aps if ap not in self.propositions]
        if missing:
            raise MissionError(
                f"the automaton's propositions {', '.join(missing)} have no meaning (enter/reach) given",
                self.source,
            )

    @property
    def ordered_propositions(self) -> list[Proposition]:
        """The propositions in label-bit order (``automaton.aps``)."""
        return [self.propositions[ap] for ap in self.automaton.aps]

    @property
    def descriptions(self) -> dict[str, str]:
        """Proposition name -> action token, e.g. ``{"p1": "enter(room_2)"}``."""
        return {ap: self.propositions[ap].name for ap in self.automaton.aps}

    def check_scene(self, building: Building) -> None:
        """Raise :class:`MissionError` naming every proposition whose room/object the building lacks."""
        bad = [
            p.name if ap == p.name else f"{ap} = {p.name}"
            for ap, p in self.propositions.items()
            if ap in self.automaton.aps
            and not (building.has_room(p.uuid) if p.kind == "enter" else building.has_object(p.uuid))
        ]
        if bad:
            rooms = ", ".join(room.key for room in building.rooms())
            raise MissionError(
                f"mission propositions name entities that building {building.name!r} does not have: "
                f"{'; '.join(bad)} (its rooms: {rooms}; `sgplan inspect` lists them with their objects)",
                self.source,
            )

    def labels(self, building: Building, reach_radius_m: float | None = None,
               reach_model: str = DEFAULT_REACH_MODEL) -> np.ndarray:
        """``(floors, rows, cols)`` label bitmasks in the automaton's proposition order, objects reached
        under ``reach_model`` (:mod:`sgplan.scene.reach`)."""
        self.check_scene(building)
        return label_raster(building, self.ordered_propositions, reach_radius_m, reach_model)


def parse_formula(text: str | Sequence[str], known: set[str] | None = None) -> Formula:
    """Parse a formula given as an LLM token list (or its repr), Spot infix, or LBT prefix.

    A string starting with ``[`` is a token list; otherwise infix is tried, then prefix (a text valid
    in both reads the same way in both, since binary operators cannot be placed alike).
    """
    if not isinstance(text, str) or text.lstrip().startswith("["):
        return parse_tokens(text, known=known)
    try:
        return parse_infix(text)
    except FormulaError as infix_error:
        try:
            return parse_prefix(text)
        except FormulaError:
            raise infix_error from None


def compile_mission(
    formula: Formula | str | Sequence[str],
    propositions: Mapping[str, Proposition] | None = None,
    *,
    text: str | None = None,
    grounded_text: str | None = None,
    guidance: Guidance | None = None,
    set_aside: Sequence[str] = (),
) -> Mission:
    """A mission whose automaton is the minimal DFA of ``formula`` (LTLf), compiled here; the public
    :func:`sgplan.mission_from_formula` builds on it (it also reads an ``ap_desc.yaml`` and checks the scene).

    Proposition names are either action tokens (``enter(room_2)``, then ``propositions`` may be
    omitted) or names given a meaning by ``propositions`` (e.g. ``p1`` from an ap_desc.yaml). ``set_aside``:
    words of ``text`` a translator did not read (:attr:`Mission.set_aside`).
    At most one ``enter(room)`` proposition holds at a cell, so those labels are pruned.
    """
    if not isinstance(formula, Formula):
        formula = parse_formula(formula)
    meaning = dict(propositions or {})
    for name in atoms(formula):
        if name not in meaning:
            try:
                meaning[name] = Proposition.parse(name)
            except FormulaError:
                raise MissionError(
                    f"proposition {name!r} is neither enter(room_<uuid>) / reach(object_<uuid>) nor given a "
                    "meaning (pass an ap_desc.yaml with --aps)"
                ) from None
    aps = tuple(atoms(formula))
    rooms = [ap for ap in aps if meaning[ap].kind == "enter"]
    automaton = ltlf_to_dfa(formula, aps=aps, exclusive=[rooms] if len(rooms) > 1 else ())
    return Mission(
        automaton=automaton,
        propositions={ap: meaning[ap] for ap in aps},
        formula=formula,
        text=text,
        grounded_text=grounded_text,
        guidance=guidance,
        set_aside=tuple(set_aside),
    )
