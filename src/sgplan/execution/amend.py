"""Amendments: "from now on, also avoid the bedroom" joins what is left of a running mission.

The amendment is a mission of its own (text through the translator, or a formula). Its automaton starts
at the robot's position -- it reads the label of the cell the robot stands on, as a new mission would --
and runs in product with the mission's automaton started in the robot's automaton state: the amended
mission is accepted when both are. The product is minimised; its initial state is where the robot is now,
having read its cell.

Before it takes effect the amendment is said back in words and checked against the scene from the robot's
position (:func:`sgplan.explain.checks.check_mission_in_scene`); the run then plans with it, and refuses it
-- the current mission stays -- when no path satisfies the amended rest.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from sgplan.errors import FormulaError, MissionError
from sgplan.logic.automaton import Automaton
from sgplan.logic.formula import And, Formula, rename_atoms
from sgplan.logic.ltlf import MAX_TABLE_ENTRIES
from sgplan.logic.minimize import product
from sgplan.logic.progression import progress
from sgplan.mission import Mission
from sgplan.scene.labels import Proposition
from sgplan.scene.model import Building

_LEAD_INS = ("from now on,", "from now on", "also,", "also", "and")


def amendment_text(text: str) -> str:
    """``text`` without the lead-ins that only say *when* an amendment applies (``from now on``,
    ``also``): an amendment always applies from the robot's position on."""
    rest = " ".join(text.split())
    changed = True
    while changed:
        changed = False
        for lead in _LEAD_INS:
            if rest.lower().startswith(lead + " ") or rest.lower() == lead:
                rest, changed = rest[len(lead):].lstrip(" ,"), True
    return rest[:1].upper() + rest[1:] if rest else rest


def _by_token(mission: Mission) -> tuple[Automaton, dict[str, Proposition]]:
    """The mission's automaton over proposition tokens (``enter(room_2)``) instead of its own names."""
    tokens = [mission.propositions[ap].name for ap in mission.automaton.aps]
    meaning = {mission.propositions[ap].name: mission.propositions[ap] for ap in mission.automaton.aps}
    a = mission.automaton
    return Automaton(tuple(tokens), a.table, a.initial, a.accepting), meaning


def combine(mission: Mission, state: int, amendment: Mission, cell_label: Mapping[str, bool],
            residual: Formula | None) -> Mission:
    """The mission that is left once ``amendment`` joins ``mission`` with the robot in automaton state
    ``state`` on a cell where the propositions ``cell_label`` hold (token -> truth; those of the
    amendment are read). Its automaton's initial state is the robot's state now; ``residual`` (what is
    left of the mission's formula, if known) and the amendment's formula make its formula.

    Raises
    ------
    MissionError
        when the propositions of the two missions give one token two meanings (two reach radii), or the
        joined automaton would exceed :data:`~sgplan.logic.ltlf.MAX_TABLE_ENTRIES`.
    """
    left, left_meaning = _by_token(mission)
    right, right_meaning = _by_token(amendment)
    for token, prop in right_meaning.items():
        if token in left_meaning and left_meaning[token] != prop:
            raise MissionError(f"the amendment's {token} means {prop}, the mission's {left_meaning[token]}")
    aps = tuple(dict.fromkeys(left.aps + right.aps))
    entries = (left.num_states * right.num_states) << len(aps)  # the product before it is minimised
    if entries > MAX_TABLE_ENTRIES:
        raise MissionError(
            f"the mission with the amendment would need {left.num_states} x {right.num_states} states x "
            f"{1 << len(aps):,} labels = {entries:,} table entries, more than the {MAX_TABLE_ENTRIES:,} an "
            f"automaton may hold; amend with fewer new rooms or objects, or plan a new mission"
        )
    left, right = left.with_aps(aps), right.with_aps(aps)
    label = right.label_of(token for token, holds in cell_label.items() if holds)
    now = Automaton(aps, left.table, state, left.accepting)
    entered = Automaton(aps, right.table, right.step(right.initial, label), right.accepting)
    combined = product(now, entered, np.logical_and)
    formula = None
    if residual is not None and amendment.formula is not None:
        # The amendment's word starts on the robot's cell, which the combined state has read already.
        true = {token for token, holds in cell_label.items() if holds}
        here = [ap for ap in amendment.automaton.aps if amendment.propositions[ap].name in true]
        tokens = {ap: mission.propositions[ap].name for ap in mission.automaton.aps}
        own = {ap: amendment.propositions[ap].name for ap in amendment.automaton.aps}
        formula = And((rename_atoms(residual, tokens),
                       rename_atoms(progress(amendment.formula, [here]), own)))
    texts = [t for t in (mission.text, amendment.text) if t]
    return Mission(
        automaton=combined, propositions={**left_meaning, **right_meaning}, formula=formula,
        text=" ".join(texts) if texts else None, notes=list(mission.notes) + list(amendment.notes),
    )


def amendment_mission(text: str, building: Building, llm: str = "offline", **llm_options: Any) -> Mission:
    """The amendment as a mission of its own: ``text`` read as a formula over ``enter(room_N)`` /
    ``reach(object_N)`` when it parses as one, else translated from natural language (by ``llm``, as
    :func:`sgplan.mission_from_text`; lead-ins such as "from now on, also" dropped first).

    Raises
    ------
    MissionError, FormulaError, LLMError
        a reference the building does not resolve (with the candidates), a failed translation.
    """
    from sgplan.api import mission_from_formula, mission_from_text

    try:
        return mission_from_formula(text, building)
    except FormulaError:
        return mission_from_text(amendment_text(text), building, llm=llm, **llm_options)
