"""The monitor's words: what is left of a mission in an automaton state, and what a step of the robot did.

Entities are named as the explainer names them (:mod:`sgplan.explain`: category, id, floor). What is left
in state ``q`` is read from the residual formula (:func:`sgplan.logic.progress` of the mission's formula
over a shortest word that leads to ``q``: every word leading there leaves the same language, because the
automaton is minimal) when its automaton is the mission's automaton started in ``q``; otherwise (a
mission without a formula, or an automaton read under the ``authors`` profile) from that automaton.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from sgplan.explain.patterns import pattern_clauses
from sgplan.explain.referents import Referent, referents_of
from sgplan.explain.render import explain_formula
from sgplan.logic.automaton import Automaton
from sgplan.logic.formula import And, Const, Formula
from sgplan.logic.ltlf import ltlf_to_dfa
from sgplan.logic.progression import progress
from sgplan.mission import Mission
from sgplan.scene.model import Building

ResidualMethod = Literal["patterns", "automaton", "nothing"]
_NUMBERED = re.compile(r"^\d+\. ")


@dataclass(frozen=True)
class Residual:
    """What a mission still asks in one automaton state, for any continuation of at least one cell.

    Attributes
    ----------
    formula:
        the residual formula (``None`` for a mission without one).
    parts:
        the residual in words: one clause per part (``go to the bedroom (room_11, floor 1)``), or the lines
        of its automaton's reading; empty when nothing is asked (``method == "nothing"``).
    method:
        ``"patterns"`` (read from ``formula``), ``"automaton"`` or ``"nothing"`` (every continuation
        satisfies the mission, or none does).
    """

    formula: Formula | None
    parts: tuple[str, ...]
    method: ResidualMethod

    def text(self) -> str:
        """The parts joined: ``go to the bedroom (...); never enter the kitchen (...)``; read from the
        automaton, ``as read from its automaton:`` and one line per part."""
        if self.method == "automaton":
            return "\n".join(["as read from its automaton:", *self.parts])
        return "; ".join(self.parts)


def _clause(sentence: str) -> str:
    """``2. Never enter the kitchen (...).`` -> ``never enter the kitchen (...)``."""
    text = _NUMBERED.sub("", sentence).rstrip(".")
    return text[:1].lower() + text[1:]


def started_in(automaton: Automaton, state: int) -> Automaton:
    """``automaton`` started in ``state`` for continuations of at least one letter: a fresh, rejecting
    initial state with ``state``'s edges (the language of a residual formula)."""
    table = np.vstack([automaton.table, automaton.table[state]])
    return Automaton(automaton.aps, table, automaton.num_states, np.append(automaton.accepting, False))


class MissionWords:
    """Says a mission's progress back in words; every reading is computed once per state and kept.

    Parameters
    ----------
    mission, building:
        the mission monitored and its scene (for the entities' names).
    realizable:
        ``(num_labels,)`` bool: the label sets the robot can produce (the monitor's own).
    progressions:
        the mission's formula progressed over words (label tuples), shared by the words of one mission in
        several scenes (a run's, as the building changes): progression reads no scene.
    """

    def __init__(self, mission: Mission, building: Building, realizable: np.ndarray,
                 progressions: dict[tuple[int, ...], Formula] | None = None) -> None:
        self.mission = mission
        self.progressions = {} if progressions is None else progressions
        self.automaton = mission.automaton
        self.realizable = realizable
        aps = self.automaton.aps
        self.entities: dict[str, Referent] = referents_of(list(aps), mission.propositions, building)
        rooms = [ap for ap in aps if mission.propositions[ap].kind == "enter"]
        self.exclusive = [rooms] if len(rooms) > 1 else []
        self._residuals: dict[int, Residual] = {}

    def residual(self, state: int) -> Residual:
        """What is left in ``state`` (see the module). Cost: a few automata the first time a state is
        asked (milliseconds to tens of milliseconds), a look-up afterwards."""
        known = self._residuals.get(state)
        if known is None:
            known = self._residuals[state] = self._read(state)
        return known

    def _read(self, state: int) -> Residual:
        formula = self.mission.formula
        word = self._word_to(state)
        residual = None
        if formula is not None and word is not None:
            residual = self.progressions.get(tuple(word))
            if residual is None:
                letters = [self.automaton.props_of(label) for label in word]
                residual = progress(formula, letters, exclusive=self.exclusive)
                self.progressions[tuple(word)] = residual
            if isinstance(residual, Const):
                return Residual(residual, (), "nothing")
        continuing = started_in(self.automaton, state)
        if not self.automaton.live_states(self.realizable)[state] or self._always_accepting(state):
            return Residual(residual, (), "nothing")
        explanation = explain_formula(residual, self.entities, automaton=continuing,
                                      realizable=self.realizable)
        lines = explanation.text.splitlines()[1:]  # after the header line: one line per part
        if explanation.method == "patterns":
            return Residual(residual, tuple(_clause(line) for line in lines), "patterns")
        return Residual(residual, tuple(lines), "automaton")

    def _always_accepting(self, state: int) -> bool:
        """Whether every word of realizable labels from ``state`` keeps the automaton accepting."""
        from_here = Automaton(self.automaton.aps, self.automaton.table, state, self.automaton.accepting)
        return bool(self.automaton.accepting[from_here.reachable_states(self.realizable)].all())

    def _word_to(self, state: int) -> list[int] | None:
        """A shortest word of realizable labels (else of any labels) from the initial state to ``state``."""
        for labels in (np.flatnonzero(self.realizable), np.arange(self.automaton.num_labels)):
            parent: dict[int, tuple[int, int]] = {}
            frontier = [self.automaton.initial]
            seen = {self.automaton.initial}
            while frontier and state not in seen:
                nxt = []
                for q in frontier:
                    for label in labels.tolist():
                        r = int(self.automaton.table[q, label])
                        if r not in seen:
                            seen.add(r)
                            parent[r] = (q, label)
                            nxt.append(r)
                frontier = nxt
            if state in seen:
                word = []
                while state != self.automaton.initial:
                    state, label = parent[state]
                    word.append(label)
                return word[::-1]
        return None

    # -- steps -------------------------------------------------------------------------------------------

    def places(self, label: int) -> str:
        """``in the kitchen (...) and within reach of the sink (...)`` for the propositions of ``label``."""
        said = [f"{'within reach of' if e.kind == 'object' else 'in'} {e.phrase()}"
                for e in self._of(label)]
        return " and ".join(said) if said else "in none of the places the mission names"

    def _of(self, label: int) -> list[Referent]:
        return [self.entities[ap] for i, ap in enumerate(self.automaton.aps) if label >> i & 1]

    def step(self, before: int, label: int) -> str:
        """What the robot did reading ``label`` after ``before`` (``-1``: it is the first cell read):
        ``entered the kitchen (room_4, floor 0)``, ``left ...``, ``came within reach of ...``."""
        if before < 0:
            return f"started {self.places(label)}"
        said = [f"{'went out of reach of' if e.kind == 'object' else 'left'} {e.phrase()}"
                for e in self._of(before & ~label)]
        said += [f"{'came within reach of' if e.kind == 'object' else 'entered'} {e.phrase()}"
                 for e in self._of(label & ~before)]
        return " and ".join(said) if said else f"went one cell further, {self.places(label)}"

    def breach(self, state: int, before: int, label: int) -> str:
        """Why reading ``label`` in ``state`` (after ``before``) left no way to complete the mission:
        ``entered the kitchen (...), which the mission forbids: never enter the kitchen (...)``."""
        broken = self.broken_parts(state, label)
        what = self.step(before, label)
        if broken:
            return f"{what}, which the mission forbids: {'; '.join(broken)}"
        return f"{what}, after which no way to complete the mission remains in this building"

    def broken_parts(self, state: int, label: int) -> list[str]:
        """The parts of what was left in ``state`` that ``label`` makes impossible on their own, in words
        (empty when only their combination is, or the residual is not read from a formula)."""
        residual = self.residual(state)
        if residual.method != "patterns" or residual.formula is None:
            return []
        parts: Sequence[Formula] = (residual.formula.args if isinstance(residual.formula, And)
                                    else (residual.formula,))
        letter = [self.automaton.props_of(label)]
        broken = []
        for part in parts:
            after = progress(part, letter, exclusive=self.exclusive)
            if after == Const(False) or not self._possible(after):
                clauses = pattern_clauses(part, self.entities.__getitem__)
                if clauses:
                    broken += [_clause(c) for c in clauses]
        return broken

    def _possible(self, formula: Formula) -> bool:
        """Whether some word of realizable labels satisfies ``formula``."""
        if isinstance(formula, Const):
            return formula.value
        dfa = ltlf_to_dfa(formula, aps=self.automaton.aps, exclusive=self.exclusive)
        return bool(dfa.live_states(self.realizable)[dfa.initial])
