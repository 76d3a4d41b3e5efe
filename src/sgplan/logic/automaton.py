"""Deterministic finite automata over sets of atomic propositions.

A label is an integer bitmask over ``Automaton.aps``: bit ``i`` set means proposition ``aps[i]`` holds.
The transition table is complete: ``table[q, label]`` is the next state for every state and label.
A word (sequence of labels) is accepted iff running it from ``initial`` ends in an accepting state.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(eq=False)
class Automaton:
    """A complete DFA over labels ``0 .. 2**len(aps) - 1``.

    Attributes
    ----------
    aps:
        proposition names; label bit ``i`` is ``aps[i]``.
    table:
        ``(num_states, 2**len(aps))`` int32 next-state table, every entry a valid state.
    initial:
        the initial state.
    accepting:
        ``(num_states,)`` bool.
    """

    aps: tuple[str, ...]
    table: np.ndarray
    initial: int
    accepting: np.ndarray

    @property
    def num_states(self) -> int:
        return int(self.table.shape[0])

    @property
    def num_labels(self) -> int:
        return int(self.table.shape[1])
