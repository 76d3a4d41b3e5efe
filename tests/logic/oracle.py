"""Test oracles for the logic package, independent of its construction code.

- :func:`holds`: LTLf truth of a formula on a batch of equal-length words, straight from the textbook
  definitions (quantifiers over positions), vectorised over words only.
- :func:`random_formula` / :func:`formulas`: random formulas (plain ``random`` and hypothesis).
- :func:`run_words`: run a DFA over a batch of words.
- :func:`reference_minimize`: the minimal DFA in canonical numbering, by table filling.
"""

from __future__ import annotations

import random

import numpy as np
from hypothesis import strategies as st

from sgplan.logic import (
    FALSE,
    TRUE,
    Always,
    And,
    Atom,
    Automaton,
    Const,
    Equiv,
    Eventually,
    Formula,
    Implies,
    Next,
    Not,
    Or,
    Release,
    Until,
    WeakNext,
)


def holds(f: Formula, words: np.ndarray, aps: tuple[str, ...]) -> np.ndarray:
    """``(W,)`` bool: whether each word (row of ``words``, shape ``(W, T)``, labels over ``aps``)
    satisfies ``f`` at position 0. The empty word (``T == 0``) satisfies no formula."""
    if words.shape[1] == 0:
        return np.zeros(words.shape[0], bool)
    return _sat(f, words, aps)[:, 0]


def _sat(f: Formula, words: np.ndarray, aps: tuple[str, ...]) -> np.ndarray:
    """``(W, T)`` bool: truth of ``f`` at every position of every word."""
    num_words, length = words.shape
    if isinstance(f, Const):
        return np.full((num_words, length), f.value)
    if isinstance(f, Atom):
        return (words >> aps.index(f.name) & 1).astype(bool)
    subs = [_sat(c, words, aps) for c in f.children()]
    if isinstance(f, Not):
        return ~subs[0]
    if isinstance(f, And):
        return np.logical_and.reduce(subs)
    if isinstance(f, Or):
        return np.logical_or.reduce(subs)
    if isinstance(f, Implies):
        return ~subs[0] | subs[1]
    if isinstance(f, Equiv):
        return subs[0] == subs[1]
    out = np.zeros((num_words, length), bool)
    for i in range(length):
        if isinstance(f, Next):  # strong: a next position exists and f holds there
            out[:, i] = subs[0][:, i + 1] if i + 1 < length else False
        elif isinstance(f, WeakNext):
            out[:, i] = subs[0][:, i + 1] if i + 1 < length else True
        elif isinstance(f, Eventually):  # exists j >= i
            out[:, i] = subs[0][:, i:].any(axis=1)
        elif isinstance(f, Always):  # for all j >= i
            out[:, i] = subs[0][:, i:].all(axis=1)
        elif isinstance(f, Until):  # exists j >= i: right at j and left at all k in [i, j)
            a, b = subs
            out[:, i] = np.any([b[:, j] & a[:, i:j].all(axis=1) for j in range(i, length)], axis=0)
        elif isinstance(f, Release):  # for all j >= i: right at j or left at some k in [i, j)
            a, b = subs
            out[:, i] = np.all([b[:, j] | a[:, i:j].any(axis=1) for j in range(i, length)], axis=0)
        else:
            raise TypeError(f)
    return out


def run_words(a: Automaton, words: np.ndarray) -> np.ndarray:
    """``(W,)`` bool: acceptance of each row of ``words`` (labels over ``a.aps``)."""
    states = np.full(words.shape[0], a.initial)
    for t in range(words.shape[1]):
        states = a.table[states, words[:, t]]
    return a.accepting[states]


_UNARY = (Not, Next, WeakNext, Eventually, Always)
_BINARY = (Implies, Equiv, Until, Release)


def random_formula(rng: random.Random, aps: tuple[str, ...], depth: int) -> Formula:
    """A random formula of at most ``depth`` operator levels over ``aps``."""
    if depth == 0 or rng.random() < 0.25:
        return rng.choice([TRUE, FALSE]) if rng.random() < 0.05 else Atom(rng.choice(aps))
    kind = rng.random()
    if kind < 0.4:
        return rng.choice(_UNARY)(random_formula(rng, aps, depth - 1))
    left, right = random_formula(rng, aps, depth - 1), random_formula(rng, aps, depth - 1)
    if kind < 0.7:
        return (And if rng.random() < 0.5 else Or)((left, right))
    return rng.choice(_BINARY)(left, right)


def formulas(aps: tuple[str, ...], max_leaves: int = 8) -> st.SearchStrategy[Formula]:
    """Hypothesis strategy of formulas over ``aps`` with every operator of the syntax."""
    leaves = st.one_of(st.sampled_from([Atom(p) for p in aps]), st.sampled_from([TRUE, FALSE]))

    def extend(children: st.SearchStrategy[Formula]) -> st.SearchStrategy[Formula]:
        unary = st.builds(lambda op, x: op(x), st.sampled_from(_UNARY), children)
        junction = st.builds(lambda op, x, y: op((x, y)), st.sampled_from([And, Or]), children, children)
        binary = st.builds(lambda op, x, y: op(x, y), st.sampled_from(_BINARY), children, children)
        return st.one_of(unary, junction, binary)

    return st.recursive(leaves, extend, max_leaves=max_leaves)


def random_words(rng: np.random.Generator, num_aps: int, count: int, length: int) -> np.ndarray:
    """``(count, length)`` uniformly random labels over ``num_aps`` propositions."""
    return rng.integers(0, 1 << num_aps, size=(count, length))


def reference_minimize(a: Automaton) -> Automaton:
    """The minimal DFA of ``a`` in sgplan's canonical numbering (breadth-first from the initial state,
    successors by increasing label), by the textbook table-filling algorithm with plain loops: an
    independent check of :func:`sgplan.logic.minimize` (partition refinement over the whole table). For
    small automata only (quadratic in states, times labels)."""
    reachable = [a.initial]
    for q in reachable:  # grows while it is read
        for label in range(a.num_labels):
            if int(a.table[q, label]) not in reachable:
                reachable.append(int(a.table[q, label]))
    apart = {(p, q) for p in reachable for q in reachable if a.accepting[p] != a.accepting[q]}
    changed = True
    while changed:
        changed = False
        for p in reachable:
            for q in reachable:
                if (p, q) not in apart and any(
                    (int(a.table[p, label]), int(a.table[q, label])) in apart for label in range(a.num_labels)
                ):
                    apart.add((p, q))
                    changed = True
    first_equal = {q: next(p for p in reachable if (p, q) not in apart) for q in reachable}
    order = [first_equal[a.initial]]
    for q in order:
        for label in range(a.num_labels):
            r = first_equal[int(a.table[q, label])]
            if r not in order:
                order.append(r)
    number = {q: k for k, q in enumerate(order)}
    table = np.array([[number[first_equal[int(a.table[q, label])]] for label in range(a.num_labels)]
                      for q in order])
    return Automaton(a.aps, table, 0, a.accepting[order])
