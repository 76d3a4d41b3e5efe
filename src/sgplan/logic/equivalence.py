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
from sgplan.logic.ltlf import ltlf_to_dfa

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
    nb, num_labels = b.num_states, a.num_labels
    parent = np.full(a.num_states * nb, -2, np.int64)  # -2 = unseen, -1 = the start pair
    via = np.zeros(a.num_states * nb, np.int64)
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
    labels = []
    while parent[found] != -1:
        labels.append(int(via[found]))
        found = int(parent[found])
    return tuple(a.props_of(label) for label in reversed(labels))


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
