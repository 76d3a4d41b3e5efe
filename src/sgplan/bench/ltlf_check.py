"""A path planned under the ``authors`` profile, read again under ``ltlf``: where it breaks the mission.

Under ``authors`` (the authors' C++, docs/semantics.md) a label with no edge out of the automaton's state
keeps the state, and the start cell's label is not read. A mission's "always avoid" then holds only
where the automaton file happens to have the edge, so an optimal ``authors`` path may cross a room the
mission forbids. :func:`ltlf_reading` replays the path's labels on the ``ltlf`` automaton of the same file
(a missing edge rejects, the start is read) and names each place where that reading rejects.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from sgplan.logic.automaton import Automaton

MAX_VIOLATIONS = 10
"""At most this many violations are named per path (the first ones along it)."""


@dataclass(frozen=True)
class Violation:
    """One place where the ``ltlf`` reading rejects a path: the path row ``index``, its ``cell``
    ``(row, col, floor)``, the path cost there (metres), ``reason`` (``"start-label"``: the start cell's
    label, which ``authors`` does not read; ``"missing-edge"``: no edge for the label out of ``state``,
    which ``authors`` reads as staying), the places responsible, as phrases, and how many ``times`` the
    path breaks the mission in the same way (the first is described)."""

    index: int
    cell: tuple[int, int, int]
    cost_m: float
    reason: str
    state: int
    places: tuple[str, ...]
    times: int = 1

    def to_dict(self) -> dict[str, object]:
        return {"index": self.index, "cell": list(self.cell), "cost_m": self.cost_m, "reason": self.reason,
                "state": self.state, "places": list(self.places), "times": self.times}


def _culprits(ltlf: Automaton, live: np.ndarray, state: int, label: int) -> list[str]:
    """The propositions of ``label`` without which the step from ``state`` would stay live (all of them
    when none alone is to blame)."""
    true = [i for i in range(len(ltlf.aps)) if label >> i & 1]
    alone = [i for i in true if live[ltlf.table[state, label & ~(1 << i)]]]
    return [ltlf.aps[i] for i in (alone or true)]


def ltlf_reading(path: np.ndarray, path_labels: np.ndarray, costs_m: np.ndarray, authors: Automaton,
                 ltlf: Automaton, describe: Callable[[str], str]) -> tuple[bool, list[Violation]]:
    """Whether the ``authors`` path ``path`` (``(n, 4)`` rows ``[row, col, floor, q]``, ``q`` the
    ``authors`` state) satisfies the mission under ``ltlf``, and the places where it breaks it.

    ``path_labels`` are the label bits of its cells (the two automata share the file's proposition
    order), ``costs_m`` the path cost at each row, ``describe`` names a proposition
    (``the staircase (room_19, floor 1)``). A violation is a row whose label, read from the state the
    ``authors`` run is in, leads the ``ltlf`` automaton to a state that can no longer accept; a stretch
    of such rows with the same places and state counts once, and a later stretch like it adds to ``times``.
    """
    if tuple(authors.aps) != tuple(ltlf.aps):
        raise ValueError("the two readings must come from one automaton file (same propositions)")
    live = ltlf.live_states()
    q = ltlf.initial
    for label in path_labels.tolist():
        q = int(ltlf.table[q, label])
    found: dict[tuple[str, int, tuple[str, ...]], Violation] = {}
    previous: tuple[str, int, tuple[str, ...]] | None = None
    for k, label in enumerate(path_labels.tolist()):
        state = authors.initial if k == 0 else int(path[k - 1, 3])
        if live[ltlf.table[state, label]]:
            previous = None
            continue
        key = ("start-label" if k == 0 else "missing-edge", state,
               tuple(describe(p) for p in _culprits(ltlf, live, state, label)))
        if key == previous:
            continue
        previous = key
        if key in found:
            found[key] = replace(found[key], times=found[key].times + 1)
        elif len(found) < MAX_VIOLATIONS:
            row, col, floor = (int(v) for v in path[k, :3])
            found[key] = Violation(k, (row, col, floor), float(costs_m[k]), *key)
    return bool(ltlf.accepting[q]), list(found.values())
