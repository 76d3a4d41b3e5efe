"""Language equivalence and inclusion of automata or formulas, with a shortest counterexample word.

Both sides are aligned on the union of their propositions (a proposition one side does not use is
irrelevant to it), the synchronous product is explored breadth-first from the pair of initial states,
and the first pair whose acceptance is "bad" gives the counterexample by walking back the BFS tree.
A word is a tuple of sets of true propositions, one per cell; ``()`` is the empty word.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.logic.formula import Formula, atoms
from sgplan.logic.ltlf import CompactDfa, ltlf_to_dfa
from sgplan.logic.minimize import Table

Word = tuple[frozenset[str], ...]
Language = Automaton | Formula


def _aligned(a: Language, b: Language) -> tuple[Automaton, Automaton]:
    def names(x: Language) -> tuple[str, ...]:
        return x.aps if isinstance(x, Automaton) else atoms(x)

    union = list(names(a))
    union += [p for p in names(b) if p not in union]

    def build(x: Language) -> Automaton:
        return x.with_aps(union) if isinstance(x, Automaton) else ltlf_to_dfa(x, aps=union)

    return build(a), build(b)


def _search(a: Automaton, b: Automaton, bad: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> Word | None:
    """Shortest word leading the product to a pair ``(p, q)`` with ``bad(acc_a[p], acc_b[q])``."""
    def table(x: Automaton) -> Table:
        return Table(x.table, x.initial, x.accepting)

    columns = _search_tables(table(a), table(b), bad)
    return None if columns is None else tuple(a.props_of(label) for label in columns)


def compact_difference_word(a: CompactDfa, b: CompactDfa) -> Word | None:
    """:func:`difference_word` of two automata of :func:`~sgplan.logic.ltlf.ltlf_to_compact_dfa` built with
    the same propositions and possible labels (so with the same columns)."""
    if a.aps != b.aps or not np.array_equal(a.column_labels, b.column_labels):
        raise ValueError("compact automata over different propositions or labels cannot be compared")
    columns = _search_tables(a.table, b.table, np.not_equal)
    return None if columns is None else tuple(
        frozenset(name for i, name in enumerate(a.aps) if int(a.column_labels[c]) >> i & 1) for c in columns)


def _search_tables(a: Table, b: Table,
                   bad: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> list[int] | None:
    """The columns of a shortest word leading the product of ``a`` and ``b`` (over the same columns) to a
    pair ``(p, q)`` with ``bad(a.accepting[p], b.accepting[q])``; ``None`` when no such pair is reachable."""
    nb, num_labels = b.table.shape[0], a.table.shape[1]
    parent = np.full(a.table.shape[0] * nb, -2, np.int64)  # -2 = unseen, -1 = the start pair
    via = np.zeros(a.table.shape[0] * nb, np.int64)
    start = a.initial * nb + b.initial
    parent[start] = -1
    frontier = np.array([start], np.int64)
    found = None
    while frontier.size and found is None:
        pa, pb = np.divmod(frontier, nb)
        hits = np.flatnonzero(bad(a.accepting[pa], b.accepting[pb]))
        if hits.size:
            found = int(frontier[hits[0]])
            break
        successors = (a.table[pa].astype(np.int64) * nb + b.table[pb]).ravel()
        fresh = parent[successors] == -2
        targets, first = np.unique(successors[fresh], return_index=True)
        sources = np.flatnonzero(fresh)[first]
        parent[targets] = frontier[sources // num_labels]
        via[targets] = sources % num_labels
        frontier = targets
    if found is None:
        return None
    columns = []
    while parent[found] != -1:
        columns.append(int(via[found]))
        found = int(parent[found])
    return columns[::-1]


def difference_word(a: Language, b: Language) -> Word | None:
    """A shortest word accepted by exactly one of ``a`` and ``b``; ``None`` if the languages are equal.

    Formulas are translated with :func:`ltlf_to_dfa` over the union of both sides' propositions.
    """
    return _search(*_aligned(a, b), np.not_equal)


def inclusion_counterexample(a: Language, b: Language) -> Word | None:
    """A shortest word accepted by ``a`` and rejected by ``b``; ``None`` if L(a) is a subset of L(b)."""
    return _search(*_aligned(a, b), lambda x, y: x & ~y)


def equivalent(a: Language, b: Language) -> bool:
    """Whether ``a`` and ``b`` accept the same finite words."""
    return difference_word(a, b) is None


def included(a: Language, b: Language) -> bool:
    """Whether every finite word accepted by ``a`` is accepted by ``b``."""
    return inclusion_counterexample(a, b) is None
