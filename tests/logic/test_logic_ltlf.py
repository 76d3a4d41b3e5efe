"""LTLf -> DFA: agreement with the textbook evaluator, pruning, size guard, speed."""

from __future__ import annotations

import random
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import AutomatonError, FormulaError
from sgplan.logic import (
    Atom,
    Automaton,
    Next,
    compact_difference_word,
    difference_word,
    equivalent,
    ltlf_to_compact_dfa,
    ltlf_to_dfa,
    minimize,
    parse_infix,
    parse_prefix,
    possible_labels,
)
from sgplan.logic.rows import unique_rows
from tests.logic.oracle import formulas, holds, random_formula, random_words, reference_minimize, run_words

APS = ("p0", "p1", "p2", "p3", "p4")
WORDS_PER_LENGTH = 500
MAX_LENGTH = 10
LARGER_FORMULAS = 300


@settings(max_examples=500, deadline=None)
@given(formula=formulas(APS, max_leaves=10), seed=st.integers(0, 2**32 - 1))
def test_dfa_agrees_with_the_textbook_semantics(formula, seed):
    check_against_oracle(formula, np.random.default_rng(seed))


def check_against_oracle(formula, rng: np.random.Generator) -> None:
    dfa = ltlf_to_dfa(formula, aps=APS)
    for length in range(MAX_LENGTH + 1):
        count = 1 if length == 0 else WORDS_PER_LENGTH
        words = random_words(rng, len(APS), count, length)
        expected = holds(formula, words, APS)
        got = run_words(dfa, words)
        bad = np.flatnonzero(expected != got)
        assert bad.size == 0, f"{formula}: word {words[bad[0]].tolist()} expected {expected[bad[0]]}"


def test_dfa_agrees_with_the_textbook_semantics_on_larger_formulas():
    """Seeded formulas of depth <= 5 (hypothesis favours small ones); up to ~40 DFA states."""
    rng = random.Random(7)
    words_rng = np.random.default_rng(7)
    for _ in range(LARGER_FORMULAS):
        check_against_oracle(random_formula(rng, APS, depth=5), words_rng)


@settings(max_examples=60, deadline=None)
@given(formula=formulas(APS, max_leaves=6))
def test_dfa_is_minimal_and_canonical(formula):
    dfa = ltlf_to_dfa(formula, aps=APS)
    again = minimize(dfa)
    assert again.num_states == dfa.num_states
    assert np.array_equal(again.table, dfa.table) and again.initial == dfa.initial == 0
    # Every state is reachable and no two states are equivalent (Moore's fixpoint is the identity).
    assert dfa.reachable_states().all()
    reference = reference_minimize(dfa)  # the textbook algorithm gives the same numbering
    assert np.array_equal(reference.table, dfa.table) and np.array_equal(reference.accepting, dfa.accepting)


def test_empty_word_is_rejected_even_by_valid_formulas():
    for text in ("true", "G p0", "p0 | !p0", "G !p0"):
        dfa = ltlf_to_dfa(parse_infix(text))
        assert not dfa.accepting[dfa.initial], text


def test_strong_next_is_false_at_the_last_cell():
    dfa = ltlf_to_dfa(Next(Atom("p")))
    assert not dfa.accepts([1])
    assert dfa.accepts([0, 1])
    weak = ltlf_to_dfa(parse_infix("!X !p"))
    assert weak.accepts([0]) and weak.accepts([0, 1]) and not weak.accepts([0, 0])


def test_small_known_automata():
    # F(p1 & F p2) & G !p3: waiting, p1 seen, done, violated.
    dfa = ltlf_to_dfa(parse_infix("F(p1 & F p2) & G !p3"))
    assert dfa.num_states == 4
    assert dfa.accepts([dfa.label_of(["p1"]), dfa.label_of(["p2"])])
    assert dfa.accepts([dfa.label_of(["p1", "p2"])])
    assert not dfa.accepts([dfa.label_of(["p1"]), dfa.label_of(["p2", "p3"])])
    assert not dfa.accepts([dfa.label_of(["p2"]), dfa.label_of(["p1"])])


def test_exclusive_groups_send_impossible_labels_to_a_sink():
    rooms = ["r1", "r2", "r3"]
    formula = parse_infix("F(r1 & F(r2 & F r3))")
    pruned = ltlf_to_dfa(formula, exclusive=[rooms])
    possible = possible_labels(pruned.aps, [rooms])
    assert possible.tolist() == [True, True, True, False, True, False, False, False]
    sinks = pruned.sink_states()
    assert sinks[pruned.table[:, ~possible]].all()
    # On possible labels the pruned DFA agrees with the unpruned one.
    full = ltlf_to_dfa(formula)
    rng = np.random.default_rng(0)
    words = rng.choice(np.flatnonzero(possible), size=(500, 6))
    assert np.array_equal(run_words(full, words), run_words(pruned, words))


def _pruned_by_hand(full: Automaton, possible: np.ndarray) -> Automaton:
    """``full`` with every impossible label sent to a new rejecting sink, minimised: the dense reference."""
    sink = full.num_states
    table = np.vstack([full.table, np.full((1, full.num_labels), sink)])
    table[:, ~possible] = sink
    return reference_minimize(Automaton(full.aps, table, full.initial, np.append(full.accepting, False)))


@settings(max_examples=60, deadline=None)
@given(formula=formulas(APS, max_leaves=8), groups=st.sampled_from([
    [["p0", "p1"]], [["p0", "p1", "p2"]], [["p1", "p3"], ["p0", "p2", "p4"]], [list(APS)],
]), keep=st.lists(st.booleans(), min_size=32, max_size=32))
def test_pruned_dfa_is_exactly_the_dense_one_pruned_by_hand(formula, groups, keep):
    """The builder works over the possible labels and one column for the rest; the result must be the
    very table (same numbering) of pruning the unpruned dense DFA by hand and minimising it."""
    possible = possible_labels(APS, groups) & np.array(keep)
    built = ltlf_to_dfa(formula, aps=APS, exclusive=groups, possible=np.array(keep))
    expected = _pruned_by_hand(ltlf_to_dfa(formula, aps=APS), possible)
    assert built.num_states == expected.num_states
    assert np.array_equal(built.table, expected.table) and np.array_equal(built.accepting, expected.accepting)


@settings(max_examples=60, deadline=None)
@given(a=formulas(APS, max_leaves=6), b=formulas(APS, max_leaves=6),
       keep=st.lists(st.booleans(), min_size=32, max_size=32))
def test_compact_dfas_compare_as_the_dense_ones_restricted_to_the_possible_labels(a, b, keep):
    """The compact builder's automata differ exactly when the dense ones, with the impossible labels sent to
    the sink, do; and the word found then is made of possible labels and is a shortest one."""
    possible = np.array(keep)
    def compact(f):
        return ltlf_to_compact_dfa(f, APS, possible)

    def dense(f):
        return ltlf_to_dfa(f, aps=APS, possible=possible)

    word, dense_word = compact_difference_word(compact(a), compact(b)), difference_word(dense(a), dense(b))
    assert (word is None) == (dense_word is None)
    if word is not None and dense_word is not None:
        assert len(word) == len(dense_word)
        full_a, full_b = ltlf_to_dfa(a, aps=APS), ltlf_to_dfa(b, aps=APS)
        labels = [full_a.label_of(letter) for letter in word]
        assert all(possible[label] for label in labels)
        assert full_a.accepts(labels) != full_b.accepts(labels)


def test_compact_dfas_compare_where_the_dense_table_is_too_large():
    """21 exclusive rooms: the dense automaton is refused (see the next test), the compact one has 23 columns
    (22 possible labels and one for the rest) and compares; the word found names possible labels only."""
    rooms = [f"room_{i}" for i in range(21)]
    possible = possible_labels(rooms, [rooms])
    stay = f"G !({' | '.join(rooms[2:])})"
    ordered = parse_infix(f"F(room_0 & F room_1) & {stay}")
    also_ordered = parse_infix(f"F(room_0 & X F room_1) & {stay}")
    either = parse_infix(f"F room_0 & F room_1 & {stay}")
    assert ltlf_to_compact_dfa(ordered, rooms, possible).table.table.shape[1] == 23
    assert compact_difference_word(ltlf_to_compact_dfa(ordered, rooms, possible),
                                   ltlf_to_compact_dfa(also_ordered, rooms, possible)) is None
    assert compact_difference_word(ltlf_to_compact_dfa(ordered, rooms, possible),
                                   ltlf_to_compact_dfa(either, rooms, possible)) == (
        frozenset({"room_1"}), frozenset({"room_0"}))
    with pytest.raises(ValueError, match="cannot be compared"):
        compact_difference_word(ltlf_to_compact_dfa(ordered, rooms, possible),
                                ltlf_to_compact_dfa(ordered, rooms, possible_labels(rooms, [rooms[:20]])))


def test_staying_on_one_floor_of_three_builds_fast_with_eighteen_propositions():
    """'Stay on this floor' forbids every room of the other floors: with the goals, 18 propositions
    (262,144 labels) of which few are possible, since the robot is in one room at a time."""
    other_floors = [f"room_{i}" for i in range(11)]
    goals = ["a", "b", "c", "room_20", "d", "room_21", "room_22"]
    sequence = "F(a & F(b & F(room_20 & F(c & F(room_21 & F(room_22 | d))))))"
    formula = parse_infix(f"{sequence} & G !({' | '.join(other_floors)})")
    start = time.perf_counter()
    dfa = ltlf_to_dfa(formula, aps=[*goals, *other_floors],
                      exclusive=[[*other_floors, "room_20", "room_21", "room_22"]])
    assert time.perf_counter() - start < 2.0
    assert dfa.num_labels == 2**18 and dfa.num_states == 8
    word = [dfa.label_of(["a"]), dfa.label_of(["b"]), dfa.label_of(["room_20"]), dfa.label_of(["c"]),
            dfa.label_of(["room_21"]), dfa.label_of(["d"])]
    assert dfa.accepts(word)
    assert not dfa.accepts([*word[:3], dfa.label_of(["room_3"]), *word[3:]])


def test_twelve_unordered_goals_are_refused_early_with_the_predicted_size():
    goals = " & ".join(f"F p{i}" for i in range(12))
    start = time.perf_counter()
    with pytest.raises(AutomatonError, match=r"4,096 states x 4,096 labels = 16,777,216 table entries"):
        ltlf_to_dfa(parse_infix(goals))
    assert time.perf_counter() - start < 2.0
    # The limit is configurable: five goals need 32 states x 32 labels.
    assert (
        ltlf_to_dfa(parse_infix(" & ".join(f"F p{i}" for i in range(5))), max_entries=1024).num_states == 32
    )
    with pytest.raises(AutomatonError, match="max_entries=1,023"):
        ltlf_to_dfa(parse_infix(" & ".join(f"F p{i}" for i in range(5))), max_entries=1023)


def test_nested_formula_exploration_is_bounded():
    with pytest.raises(AutomatonError, match="more than"):
        ltlf_to_dfa(parse_infix("F(p1 & F(p2 & F(p3 & F p4)))"), max_entries=40)


def test_collierville_5_builds_well_under_a_second():
    formula = parse_prefix("& & F & p1 F & p2 F p3 & F & p4 p5 F & p6 p7 i p8 F p9")
    start = time.perf_counter()
    dfa = ltlf_to_dfa(formula)
    assert time.perf_counter() - start < 0.5
    assert dfa.num_states == 33 and len(dfa.aps) == 9


def test_aps_order_and_superset():
    formula = parse_infix("F(b & F a)")
    assert ltlf_to_dfa(formula).aps == ("b", "a")
    wide = ltlf_to_dfa(formula, aps=["a", "x", "b"])
    assert wide.aps == ("a", "x", "b") and equivalent(wide, formula)
    with pytest.raises(FormulaError, match="proposition 'b' of the formula is not among"):
        ltlf_to_dfa(formula, aps=["a"])


def test_a_dense_table_beyond_its_cap_is_refused_with_what_to_do():
    """Work over the possible labels is small (21 exclusive rooms: 22 possible labels), but the automaton
    stores all 2**21 labels for each state: 4 states would need 8,388,608 entries."""
    rooms = [f"room_{i}" for i in range(21)]
    formula = parse_infix(f"F(room_0 & F room_1) & G !({' | '.join(rooms[2:])})")
    with pytest.raises(AutomatonError, match=r"more than the 8,000,000 an automaton may hold; use fewer"):
        ltlf_to_dfa(formula, aps=rooms, exclusive=[rooms])
    twenty = parse_infix(f"F(room_0 & F room_1) & G !({' | '.join(rooms[2:20])})")
    assert ltlf_to_dfa(twenty, aps=rooms[:20], exclusive=[rooms[:20]]).num_labels == 2**20  # 4 x 2**20 fit


def test_unique_rows_of_wide_and_empty_rows():
    rows = np.array([[1, 2, 3], [0, 0, 0], [1, 2, 3]])
    first, inverse = unique_rows(rows)
    assert np.array_equal(rows[first[inverse]], rows) and inverse[0] == inverse[2] != inverse[1]
    first, inverse = unique_rows(np.zeros((3, 0), np.int32))
    assert first.tolist() == [0] and inverse.tolist() == [0, 0, 0]
