"""Deterministic finite automata over sets of atomic propositions.

A label is an integer bitmask over ``Automaton.aps``: bit ``i`` set means proposition ``aps[i]`` holds.
The transition table is complete: ``table[q, label]`` is the next state for every state and label.
A word (sequence of labels) is accepted iff running it from ``initial`` ends in an accepting state; the
empty word is accepted iff ``initial`` is accepting.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from sgplan.errors import AutomatonError

if TYPE_CHECKING:
    from scipy.sparse import csr_matrix


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

    Raises
    ------
    AutomatonError
        on construction, if the arrays do not have these shapes, types and ranges.
    """

    aps: tuple[str, ...]
    table: np.ndarray
    initial: int
    accepting: np.ndarray

    def __post_init__(self) -> None:
        self.aps = tuple(self.aps)
        self.table = np.ascontiguousarray(self.table, dtype=np.int32)
        self.accepting = np.asarray(self.accepting, dtype=bool)
        n = self.table.shape[0] if self.table.ndim == 2 else 0
        if len(set(self.aps)) != len(self.aps):
            raise AutomatonError(f"automaton propositions are not distinct: {self.aps}")
        if self.table.ndim != 2 or n == 0 or self.table.shape[1] != 1 << len(self.aps):
            raise AutomatonError(
                f"transition table has shape {self.table.shape}; expected (num_states >= 1, "
                f"{1 << len(self.aps)}) for {len(self.aps)} propositions"
            )
        if self.table.min() < 0 or self.table.max() >= n:
            raise AutomatonError(f"transition table has targets outside 0..{n - 1}")
        if self.accepting.shape != (n,):
            raise AutomatonError(f"accepting has shape {self.accepting.shape}; expected ({n},)")
        if not 0 <= int(self.initial) < n:
            raise AutomatonError(f"initial state {self.initial} is outside 0..{n - 1}")
        self.initial = int(self.initial)

    @classmethod
    def from_partial(
        cls, aps: Sequence[str], table: np.ndarray, initial: int, accepting: np.ndarray
    ) -> Automaton:
        """Complete a partial table (``-1`` = missing edge) by sending missing edges to a rejecting sink.

        The sink is appended as the last state, and only if some edge is missing.
        """
        table = np.asarray(table, dtype=np.int32)
        accepting = np.asarray(accepting, dtype=bool)
        missing = table < 0
        if missing.any():
            sink = table.shape[0]
            table = np.vstack([np.where(missing, sink, table), np.full((1, table.shape[1]), sink, np.int32)])
            accepting = np.append(accepting, False)
        return cls(tuple(aps), table, initial, accepting)

    @property
    def num_states(self) -> int:
        return int(self.table.shape[0])

    @property
    def num_labels(self) -> int:
        return int(self.table.shape[1])

    def label_of(self, props: Iterable[str]) -> int:
        """The label of a set of true propositions; names not in ``aps`` are ignored."""
        index = {name: i for i, name in enumerate(self.aps)}
        return sum(1 << index[p] for p in set(props) if p in index)

    def props_of(self, label: int) -> frozenset[str]:
        """The set of propositions true in ``label``."""
        return frozenset(name for i, name in enumerate(self.aps) if label >> i & 1)

    def step(self, state: int, label: int) -> int:
        """The next state after reading ``label`` in ``state``."""
        return int(self.table[state, label])

    def run(self, labels: Sequence[int], start: int | None = None) -> np.ndarray:
        """The ``len(labels) + 1`` states visited reading ``labels`` from ``start`` (default: initial)."""
        states = np.empty(len(labels) + 1, dtype=np.int32)
        q = self.initial if start is None else int(start)
        states[0] = q
        for t, label in enumerate(labels):
            q = self.table[q, label]
            states[t + 1] = q
        return states

    def accepts(self, labels: Sequence[int]) -> bool:
        """Whether the word ``labels`` is accepted."""
        return bool(self.accepting[self.run(labels)[-1]])

    def state_graph(self) -> csr_matrix:
        """Sparse ``(n, n)`` matrix with entry ``[q, r]`` = number of labels leading from ``q`` to ``r``."""
        from scipy.sparse import csr_matrix  # scipy.sparse is slow to import: only when used

        n = self.num_states
        rows = np.repeat(np.arange(n), self.num_labels)
        return csr_matrix((np.ones(rows.size, np.int32), (rows, self.table.ravel())), shape=(n, n))

    def reachable_states(self, labels: np.ndarray | None = None) -> np.ndarray:
        """``(n,)`` bool: the states some word leads to from the initial state; with ``labels`` (label
        values, or a ``(num_labels,)`` bool mask), some word of those labels only."""
        # A fixpoint over the dense table (a few hundred states at most): no scipy.sparse (slow to import,
        # and memory) for a graph this small.
        table = self.table if labels is None else self.table[:, np.asarray(labels)]
        mask = np.zeros(self.num_states, bool)
        mask[self.initial] = True
        frontier = np.array([self.initial])
        while frontier.size:
            successors = np.unique(table[frontier])
            frontier = successors[~mask[successors]]
            mask[frontier] = True
        return mask

    def live_states(self, labels: np.ndarray | None = None) -> np.ndarray:
        """``(n,)`` bool: the states from which some word reaches an accepting state; with ``labels``
        (label values, or a ``(num_labels,)`` bool mask), some word of those labels only (e.g. the label
        sets a scene can produce)."""
        table = self.table if labels is None else self.table[:, np.asarray(labels)]
        live = np.asarray(self.accepting, bool).copy()
        while True:  # a state is live when some label leads to a live state; at most n rounds
            grown = live | live[table].any(axis=1)
            if np.array_equal(grown, live):
                return live
            live = grown

    def sink_states(self) -> np.ndarray:
        """``(n,)`` bool: the states from which no accepting state can be reached (dead ends)."""
        return ~self.live_states()

    def with_aps(self, aps: Sequence[str]) -> Automaton:
        """The same language over another proposition order ``aps`` (a superset of ``self.aps``).

        Propositions of ``aps`` that the automaton does not use are ignored by the transitions.

        Raises
        ------
        AutomatonError
            ``aps`` lacks a proposition of ``self.aps``.
        """
        aps = tuple(aps)
        if aps == self.aps:
            return self
        missing = [p for p in self.aps if p not in aps]
        if missing:
            raise AutomatonError(
                f"cannot re-label the automaton: propositions {missing} are not in {list(aps)}"
            )
        new_labels = np.arange(1 << len(aps), dtype=np.int64)
        old_labels = np.zeros_like(new_labels)
        for i, name in enumerate(self.aps):
            old_labels |= ((new_labels >> aps.index(name)) & 1) << i
        return Automaton(aps, self.table[:, old_labels], self.initial, self.accepting.copy())
