"""Explain a mission in plain English: :func:`explain_mission` and :func:`explain_formula`.

The text is derived from the formula's structure (:mod:`sgplan.explain.patterns`) when every part of
it has a reading, else from the automaton (:mod:`sgplan.explain.stages`); never from the user's text.
Every entity is named by category, id and floor, so a misread reference (the bathroom grounded where the
kitchen was meant) shows on screen before anything is planned; words of the text that the translator set
aside unread (*We're hosting dinner tonight.*) are said back as not part of the mission.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from sgplan.errors import SgplanError
from sgplan.explain.patterns import pattern_clauses
from sgplan.explain.referents import Referent, referents_of
from sgplan.explain.scene_labels import realizable_labels
from sgplan.explain.stages import restricted, stage_lines
from sgplan.logic.automaton import Automaton
from sgplan.logic.equivalence import equivalent
from sgplan.logic.formula import MAX_NESTING, Formula, atoms, depth
from sgplan.logic.ltlf import ltlf_to_dfa, possible_labels
from sgplan.mission import Mission
from sgplan.scene.labels import Proposition
from sgplan.scene.model import Building
from sgplan.scene.reach import DEFAULT_REACH_MODEL

Method = Literal["patterns", "automaton"]

HEADER = "The mission, as it will be planned:"
AUTOMATON_HEADER = "The mission, as it will be planned (read from its automaton; it has no simpler reading):"
SET_ASIDE = "Not part of the mission:"
"""Before each part of the mission's text that its translator set aside unread (:attr:`Mission.set_aside`)."""
DIFFERS_HEADER = (
    "The mission, as it will be planned (read from its automaton, which accepts other paths than its "
    "formula, e.g. under the authors' semantics):"
)


@dataclass(frozen=True)
class Explanation:
    """A mission in plain English.

    Attributes
    ----------
    text:
        the full multi-line explanation (header line, then one line per part).
    method:
        ``"patterns"`` (read from the formula's structure) or ``"automaton"`` (read from the automaton).
    """

    text: str
    method: Method

    def __str__(self) -> str:
        return self.text

    def to_dict(self) -> dict[str, Any]:
        """``{"text": ..., "method": ...}`` for JSON records."""
        return {"text": self.text, "method": self.method}


def _numbered(clauses: list[str]) -> list[str]:
    if len(clauses) == 1:
        return clauses
    return [f"{k}. {c}" for k, c in enumerate(clauses, start=1)]


def explain_formula(
    formula: Formula | None,
    describe: Callable[[str], Referent] | Mapping[str, Referent],
    *,
    automaton: Automaton | None = None,
    realizable: np.ndarray | None = None,
) -> Explanation:
    """Explain ``formula`` (or, when it is ``None`` or has no structural reading, ``automaton``).

    Parameters
    ----------
    formula:
        the mission formula; ``None`` to explain ``automaton`` alone.
    describe:
        proposition name -> :class:`Referent` (a mapping or a function).
    automaton:
        the DFA actually planned with; default ``ltlf_to_dfa(formula)``. When both are given and differ
        on the ``realizable`` labels, the automaton is explained (it is what gets planned).
    realizable:
        ``(2**len(automaton.aps),)`` bool, the label sets the scene can produce; default: every label.

    Raises
    ------
    SgplanError
        neither a formula nor an automaton is given.
    """
    lookup = describe.__getitem__ if isinstance(describe, Mapping) else describe
    if formula is None and automaton is None:
        raise SgplanError("explain_formula needs a formula or an automaton")
    if automaton is None:
        automaton = ltlf_to_dfa(formula)  # type: ignore[arg-type]
    if realizable is None:
        realizable = np.ones(automaton.num_labels, bool)
    # A formula nested deeper than automata are built for (a chain of thousands of NOTs) is read from its
    # automaton: the structural reading recurses over the formula as written.
    same = formula is not None and depth(formula) <= MAX_NESTING and _reads_as(formula, automaton, realizable)
    if same and formula is not None:
        clauses = pattern_clauses(formula, lookup)
        if clauses is not None:
            return Explanation("\n".join([HEADER, *_numbered(clauses)]), "patterns")
    entities = {p: lookup(p) for p in automaton.aps}
    header = AUTOMATON_HEADER if formula is None or same else DIFFERS_HEADER
    return Explanation("\n".join([header, *stage_lines(automaton, entities, realizable)]), "automaton")


def _reads_as(formula: Formula, automaton: Automaton, realizable: np.ndarray) -> bool:
    """Whether ``formula`` and ``automaton`` accept the same words over the realizable labels."""
    if any(p not in automaton.aps for p in atoms(formula)) or not realizable.any():
        return False
    own = ltlf_to_dfa(formula, aps=automaton.aps, possible=realizable)
    return equivalent(restricted(own, realizable), restricted(automaton, realizable))


def explain_mission(
    mission: Mission, building: Building, *, reach_radius_m: float | None = None,
    reach_model: str | None = None,
    cells: Callable[[Proposition, float, str], np.ndarray] | None = None,
) -> Explanation:
    """Explain ``mission`` over ``building`` (see the module docstring).

    Parameters
    ----------
    mission:
        any mission (from text, a formula or a folder); its automaton is what gets planned.
    building:
        the scene whose categories, floors and ids name the entities; its grid decides which label sets
        occur (rooms exclusive, objects reached only near them).
    reach_radius_m:
        the object reach radius (metres); default the scene's, else sgplan's default.
    reach_model:
        where an object counts as reached (:mod:`sgplan.scene.reach`): ``"visible"`` or ``"box"``;
        default (``None``) sgplan's, ``"visible"``.
    cells:
        where each proposition holds at a reach radius and model (flat cell indices, e.g.
        :meth:`sgplan.Session.proposition_cells`, kept for the plan); default
        :func:`sgplan.scene.labels.proposition_cells`.

    Returns
    -------
    Explanation
        deterministic: the same mission and scene always give the same text.
    """
    automaton = mission.automaton
    extra = (
        [p for p in atoms(mission.formula) if p not in automaton.aps] if mission.formula is not None else []
    )
    if extra:  # propositions the automaton ignores (e.g. an authors' HOA dropped them): read them too
        automaton = automaton.with_aps((*automaton.aps, *extra))
    entities = referents_of(list(automaton.aps), mission.propositions, building)
    props = [mission.propositions.get(p) for p in automaton.aps]
    realizable: np.ndarray | None = None
    if all(p is not None for p in props):
        try:
            realizable = realizable_labels(props, building, reach_radius_m,  # type: ignore[arg-type]
                                           reach_model=reach_model or DEFAULT_REACH_MODEL, cells=cells)
        except SgplanError:
            realizable = None  # entities the scene lacks: their phrases say so
    if realizable is None:
        rooms = [p for p, prop in zip(automaton.aps, props) if prop is not None and prop.kind == "enter"]
        realizable = possible_labels(automaton.aps, [rooms])
    explained = explain_formula(mission.formula, entities, automaton=automaton, realizable=realizable)
    if not mission.set_aside:
        return explained
    aside = [f"{SET_ASIDE} '{said}'" for said in mission.set_aside]
    return Explanation("\n".join([explained.text, *aside]), explained.method)
