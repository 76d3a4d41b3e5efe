"""The fallback explanation: a mission read off its automaton, in stages.

Used when the formula has no structural reading (:mod:`sgplan.explain.patterns`). The automaton is
restricted to the label sets the scene can produce (one room at a time; an object only where its reach
covers), minimised and numbered canonically, and told in three parts:

- a few shortest ways to complete the mission (sequences of places, one per step that changes stage);
- what is forbidden outright (a place whose every visit makes the mission impossible);
- every stage with where each place leads (complete and exact: two missions that differ on some
  realizable path get different stage lists).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from sgplan.explain.referents import Referent
from sgplan.logic.automaton import Automaton
from sgplan.logic.minimize import Table, minimal_table

MAX_WAYS = 3
"""How many shortest ways to complete the mission are listed."""


def restricted(automaton: Automaton, realizable: np.ndarray) -> Automaton:
    """The minimal canonical DFA of ``automaton``'s language over the ``realizable`` labels only.

    Unrealizable labels are sent where the first realizable label goes, so they cannot distinguish
    states; minimising then gives a form that depends only on the language over realizable labels.
    """
    labels = np.flatnonzero(realizable)
    # Minimised over the realizable columns only (breadth-first numbering by increasing label is the
    # same there), then every unrealizable label copies the first realizable one's column.
    small = minimal_table(Table(automaton.table[:, labels], automaton.initial, automaton.accepting))
    column = np.zeros(automaton.num_labels, np.int64)
    column[labels] = np.arange(labels.size)
    return Automaton(automaton.aps, small.table[:, column], small.initial, small.accepting)


def _steps_to_accept(a: Automaton, labels: np.ndarray) -> np.ndarray:
    """``(n,)`` fewest realizable letters from each state to acceptance (``inf`` for dead states)."""
    dist = np.where(a.accepting, 0.0, np.inf)
    successors = a.table[:, labels]
    while True:
        better = np.minimum(dist, 1.0 + dist[successors].min(axis=1))
        if np.array_equal(better, dist):
            return dist
        dist = better


class _Words:
    def __init__(self, entities: Mapping[str, Referent], aps: tuple[str, ...]) -> None:
        self.entities = [entities[p] for p in aps]

    def label(self, label: int) -> str:
        """``in the kitchen (...) and within reach of the sink (...)``; ``none of these places`` for 0."""
        parts = []
        for i, e in enumerate(self.entities):
            if label >> i & 1:
                parts.append(f"{'within reach of' if e.kind == 'object' else 'in'} {e.phrase()}")
        return " and ".join(parts) if parts else "in none of these places"


def _shortest_ways(a: Automaton, labels: np.ndarray, dist: np.ndarray) -> list[list[int]]:
    """Up to :data:`MAX_WAYS` shortest accepted words, one simplest label per change of stage."""
    ways: list[list[int]] = []

    def extend(q: int, word: list[int]) -> None:
        if len(ways) >= MAX_WAYS:
            return
        if a.accepting[q]:
            ways.append(list(word))
            return
        best: dict[int, int] = {}
        for label in sorted((int(x) for x in labels), key=lambda x: (x.bit_count(), x)):
            r = int(a.table[q, label])
            if dist[r] == dist[q] - 1 and r not in best:
                best[r] = label
        for r, label in best.items():
            extend(r, [*word, label])

    if np.isfinite(dist[a.initial]):
        extend(a.initial, [])
    return ways


def _irrelevant(a: Automaton, realizable: np.ndarray) -> list[int]:
    """Bits whose value never changes a transition between realizable labels."""
    out = []
    labels = np.arange(a.num_labels)
    for i in range(len(a.aps)):
        flipped = labels ^ (1 << i)
        both = realizable & realizable[flipped]
        if np.array_equal(a.table[:, both], a.table[:, flipped[both]]):
            out.append(i)
    return out


def forbidden_bits(a: Automaton, labels: np.ndarray) -> list[int]:
    """The propositions (bit indices) whose truth ends the mission: some label of ``labels`` has them,
    and from every live reachable state every such label leads to a dead state."""
    live = a.live_states()
    states = np.flatnonzero(live & a.reachable_states())
    out = []
    for i in range(len(a.aps)):
        having = labels[(labels >> i) & 1 == 1]
        if having.size and not live[a.table[np.ix_(states, having)]].any():
            out.append(i)
    return out


def stage_lines(automaton: Automaton, entities: Mapping[str, Referent], realizable: np.ndarray | None = None
                ) -> list[str]:
    """The automaton explanation as lines of text (see the module docstring).

    ``realizable``: ``(num_labels,)`` bool, the label sets the scene can produce; default all.
    """
    if realizable is None or not realizable.any():
        realizable = np.ones(automaton.num_labels, bool)
    a = restricted(automaton, realizable)
    labels = np.flatnonzero(realizable)
    words = _Words(entities, a.aps)
    dist = _steps_to_accept(a, labels)
    unused = set(_irrelevant(a, realizable))
    mentions = [entities[p].phrase() + (" (never matters by itself here)" if i in unused else "")
                for i, p in enumerate(a.aps)]
    lines = [f"It mentions {'; '.join(mentions)}." if mentions else "It mentions no place."]
    if not np.isfinite(dist[a.initial]):
        return [*lines, "No path can complete it: its automaton accepts nothing that this scene allows."]
    lines.append("Shortest ways to complete it:")
    for word in _shortest_ways(a, labels, dist):
        steps = ", then ".join(f"be {words.label(label)}" for label in word)
        lines.append(f"- {steps or 'nothing: it is complete as soon as it starts'}.")
    live = np.isfinite(dist)
    forbidden = forbidden_bits(a, labels)
    if forbidden:
        lines.append("Forbidden at every moment (the mission fails): "
                     + "; ".join(words.label(1 << i) for i in forbidden) + ".")
    stage = {int(q): k + 1 for k, q in enumerate(np.flatnonzero(live))}
    lines.append("In full, read cell by cell from the start (a path may end in a stage marked complete):")
    for q in np.flatnonzero(live):
        moves: dict[int, list[int]] = {}
        for label in labels:
            r = int(a.table[q, label])
            if r != q:
                moves.setdefault(r, []).append(int(label))
        said = [
            f"{' or '.join(words.label(label) for label in group)} -> "
            + (f"stage {stage[r]}" if r in stage else "the mission fails")
            for r, group in moves.items()
        ]
        start, complete = " (start)" if q == a.initial else "", " (complete)" if a.accepting[q] else ""
        head = f"- stage {stage[int(q)]}{start}{complete}"
        lines.append(f"{head}: {'; '.join(said) + '; otherwise stay' if said else 'stay whatever happens'}.")
    return lines
