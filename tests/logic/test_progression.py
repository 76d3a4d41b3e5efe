"""LTLf progression: the residual formula after a prefix, checked against the textbook semantics and
against the automaton started in the state the prefix leads to."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.logic import Automaton, equivalent, ltlf_to_dfa, parse_infix, possible_labels, progress, to_infix
from tests.logic.oracle import formulas, holds, random_words

APS = ("p0", "p1", "p2")
CONTINUATIONS = 200
MAX_CONTINUATION = 6


def letters(word: np.ndarray, aps: tuple[str, ...]) -> list[set[str]]:
    return [{p for i, p in enumerate(aps) if label >> i & 1} for label in word.tolist()]


def residual_automaton(a: Automaton, state: int) -> Automaton:
    """``a`` started in ``state``, restricted to non-empty continuations: a fresh, rejecting initial state
    with ``state``'s edges (the language a progressed formula must have)."""
    table = np.vstack([a.table, a.table[state]])
    return Automaton(a.aps, table, a.num_states, np.append(a.accepting, False))


@pytest.mark.parametrize(("formula", "word", "expected"), [
    ("F(a & F b) & G !c", [{"a"}], "F b & G !c"),
    ("F(a & F b) & G !c", [{"a"}, {"b"}], "G !c"),
    ("F(a & F b) & G !c", [{"c"}], "false"),
    ("F(a & F(b & F c))", [{"a"}, {"b"}], "F c"),
    ("F(a & F(b & F c))", [{"b"}, {"a"}], "F(b & F c)"),
    ("!a U b", [set()], "!a U b"),
    ("!a U b", [{"b"}], "true"),
    ("G(a -> F b)", [{"a"}], "F b & G(a -> F b)"),
    ("X a", [set()], "a"),
    ("a", [{"a"}], "true"),
    ("F a | F b", [set()], "F a | F b"),
])
def test_known_residuals(formula, word, expected):
    assert to_infix(progress(parse_infix(formula), word)) == expected


def test_without_simplification_only_constants_are_folded():
    residual = progress(parse_infix("F(a & F b) & G !c"), [{"a"}], simplify=False)
    assert to_infix(residual) == "(F b | F(a & F b)) & G !c"


def test_exclusive_groups_decide_the_simplification():
    # Two rooms: being in a means not being in b, so "F(a & !b)" is "F a".
    formula = parse_infix("F(a & !b) | F a")
    assert to_infix(progress(formula, [], exclusive=[["a", "b"]])) == "F(a & !b)"
    assert to_infix(progress(formula, [])) == "F a"


@settings(max_examples=200, deadline=None)
@given(formula=formulas(APS, max_leaves=8), seed=st.integers(0, 2**32 - 1), length=st.integers(0, 4),
       simplify=st.booleans())
def test_residual_agrees_with_the_textbook_semantics(formula, seed, length, simplify):
    rng = np.random.default_rng(seed)
    prefix = random_words(rng, len(APS), 1, length)[0]
    residual = progress(formula, letters(prefix, APS), simplify=simplify)
    for size in range(1, MAX_CONTINUATION + 1):
        rest = random_words(rng, len(APS), CONTINUATIONS, size)
        whole = np.hstack([np.tile(prefix, (CONTINUATIONS, 1)), rest])
        assert np.array_equal(holds(formula, whole, APS), holds(residual, rest, APS)), (
            f"{formula} after {prefix.tolist()}: residual {residual}"
        )


@settings(max_examples=200, deadline=None)
@given(formula=formulas(APS, max_leaves=8), seed=st.integers(0, 2**32 - 1), length=st.integers(0, 5))
def test_residual_is_the_automaton_started_in_the_reached_state(formula, seed, length):
    dfa = ltlf_to_dfa(formula, aps=APS)
    prefix = random_words(np.random.default_rng(seed), len(APS), 1, length)[0]
    state = int(dfa.run(prefix.tolist())[-1])
    residual = progress(formula, letters(prefix, APS))
    assert equivalent(ltlf_to_dfa(residual, aps=APS), residual_automaton(dfa, state)), (
        f"{formula} after {prefix.tolist()}: residual {residual}"
    )


@settings(max_examples=100, deadline=None)
@given(formula=formulas(APS, max_leaves=8), seed=st.integers(0, 2**32 - 1), length=st.integers(0, 5))
def test_residual_within_exclusive_groups(formula, seed, length):
    """With p0 and p1 exclusive (two rooms), the residual agrees with the pruned automaton."""
    groups = [["p0", "p1"]]
    dfa = ltlf_to_dfa(formula, aps=APS, exclusive=groups)
    possible = np.flatnonzero(possible_labels(APS, groups))
    prefix = np.random.default_rng(seed).choice(possible, size=length)
    state = int(dfa.run(prefix.tolist())[-1])
    residual = progress(formula, letters(prefix, APS), exclusive=groups)
    assert equivalent(ltlf_to_dfa(residual, aps=APS, exclusive=groups), residual_automaton(dfa, state))
