"""DFA minimisation and products, vectorised over the transition table.

The work is done on :class:`Table` (a DFA over any set of columns), so that the LTLf builder can run it
over a compact alphabet (the labels that can occur, plus one column for all the others) and expand the
result to the dense ``2**len(aps)`` labels of an :class:`Automaton` once, at the end.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.logic.rows import unique_rows


class Table(NamedTuple):
    """A complete DFA over columns ``0 .. table.shape[1] - 1`` (labels, or classes of labels)."""

    table: np.ndarray
    """``(num_states, num_columns)`` next states."""
    initial: int
    accepting: np.ndarray
    """``(num_states,)`` bool."""


def _canonical_order(table: np.ndarray, initial: int) -> np.ndarray:
    """States reachable from ``initial`` in breadth-first order, successors taken by increasing column."""
    seen = np.zeros(table.shape[0], bool)
    seen[initial] = True
    order = [initial]
    head = 0
    while head < len(order):
        row = table[order[head]]
        head += 1
        _, first = np.unique(row, return_index=True)
        for r in row[np.sort(first)]:
            if not seen[r]:
                seen[r] = True
                order.append(int(r))
    return np.asarray(order, dtype=np.int64)


def _renumber(t: Table, order: np.ndarray) -> Table:
    """Keep the states ``order`` (closed under transitions), renumbered ``0..len(order)-1`` in that order."""
    new_id = np.full(t.table.shape[0], -1, np.int64)
    new_id[order] = np.arange(order.size)
    return Table(new_id[t.table[order]].astype(np.int32), int(new_id[t.initial]), t.accepting[order])


def minimal_table(t: Table) -> Table:
    """The minimal complete DFA of ``t``'s language, in canonical form (see :func:`minimize`)."""
    t = _renumber(t, _canonical_order(t.table, t.initial))
    classes = t.accepting.astype(np.int64)
    count = np.unique(classes).size
    while True:
        _, classes = unique_rows(np.column_stack([classes, classes[t.table]]))
        new_count = int(classes.max()) + 1
        if new_count == count:
            break
        count = new_count
    # One representative per class; its row, mapped to classes, is the quotient's row.
    _, representative = np.unique(classes, return_index=True)
    quotient = Table(classes[t.table[representative]], int(classes[t.initial]), t.accepting[representative])
    return _renumber(quotient, _canonical_order(quotient.table, quotient.initial))


def product_table(a: Table, b: Table, accept: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> Table:
    """The synchronous product of two DFAs over the same columns, minimised (see :func:`product`)."""
    nb = b.table.shape[0]
    table = a.table[:, None, :].astype(np.int64) * nb + b.table[None, :, :]
    accepting = accept(a.accepting[:, None], b.accepting[None, :])
    full = Table(table.reshape(-1, a.table.shape[1]), a.initial * nb + b.initial,
                 np.broadcast_to(accepting, (a.table.shape[0], nb)).ravel())
    return minimal_table(full)


def minimize(a: Automaton) -> Automaton:
    """The minimal complete DFA of ``a``'s language, in canonical form.

    Unreachable states are dropped, equivalent states merged (Moore partition refinement on the whole
    table at once) and states numbered in breadth-first order from the initial state (state 0), taking
    successors by increasing label. Two automata over the same ``aps`` accept the same language iff
    their minimised tables, initial states and accepting vectors are equal.
    """
    return Automaton(a.aps, *minimal_table(Table(a.table, a.initial, a.accepting)))


def product(a: Automaton, b: Automaton, accept: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> Automaton:
    """The synchronous product of two automata over the same ``aps``, minimised.

    State ``(p, q)`` accepts iff ``accept(a.accepting[p], b.accepting[q])`` (vectorised, e.g.
    ``np.logical_and`` for the intersection of the languages). Builds the full
    ``a.num_states * b.num_states`` table, so callers guard its size.
    """
    if a.aps != b.aps:
        raise ValueError("product needs automata over the same propositions; align them with with_aps")
    left, right = (Table(x.table, x.initial, x.accepting) for x in (a, b))
    return Automaton(a.aps, *product_table(left, right, accept))
