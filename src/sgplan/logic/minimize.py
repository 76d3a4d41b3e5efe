"""DFA minimisation and products, vectorised over the dense transition table."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from sgplan.logic.automaton import Automaton


def _canonical_order(table: np.ndarray, initial: int) -> np.ndarray:
    """States reachable from ``initial`` in breadth-first order, successors taken by increasing label."""
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


def _renumber(a: Automaton, order: np.ndarray) -> Automaton:
    """Keep the states ``order`` (closed under transitions), renumbered ``0..len(order)-1`` in that order."""
    new_id = np.full(a.num_states, -1, np.int64)
    new_id[order] = np.arange(order.size)
    return Automaton(a.aps, new_id[a.table[order]], int(new_id[a.initial]), a.accepting[order])


def minimize(a: Automaton) -> Automaton:
    """The minimal complete DFA of ``a``'s language, in canonical form.

    Unreachable states are dropped, equivalent states merged (Moore partition refinement on the whole
    table at once) and states numbered in breadth-first order from the initial state (state 0), taking
    successors by increasing label. Two automata over the same ``aps`` accept the same language iff
    their minimised tables, initial states and accepting vectors are equal.
    """
    a = _renumber(a, _canonical_order(a.table, a.initial))
    classes = a.accepting.astype(np.int64)
    count = np.unique(classes).size
    while True:
        signature = np.column_stack([classes, classes[a.table]])
        _, classes = np.unique(signature, axis=0, return_inverse=True)
        classes = classes.ravel()
        new_count = int(classes.max()) + 1
        if new_count == count:
            break
        count = new_count
    # One representative per class; its row, mapped to classes, is the quotient's row.
    _, representative = np.unique(classes, return_index=True)
    quotient = Automaton(a.aps, classes[a.table[representative]], int(classes[a.initial]),
                         a.accepting[representative])
    return _renumber(quotient, _canonical_order(quotient.table, quotient.initial))


def product(a: Automaton, b: Automaton, accept: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> Automaton:
    """The synchronous product of two automata over the same ``aps``, minimised.

    State ``(p, q)`` accepts iff ``accept(a.accepting[p], b.accepting[q])`` (vectorised, e.g.
    ``np.logical_and`` for the intersection of the languages). Builds the full
    ``a.num_states * b.num_states`` table, so callers guard its size.
    """
    if a.aps != b.aps:
        raise ValueError("product needs automata over the same propositions; align them with with_aps")
    nb = b.num_states
    table = a.table[:, None, :].astype(np.int64) * nb + b.table[None, :, :]
    accepting = accept(a.accepting[:, None], b.accepting[None, :])
    full = Automaton(a.aps, table.reshape(-1, a.num_labels), a.initial * nb + b.initial,
                     np.broadcast_to(accepting, (a.num_states, nb)).ravel())
    return minimize(full)
