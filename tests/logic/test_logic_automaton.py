"""Automaton utilities: validation, completion, re-labelling, sinks, shortest paths, remaining mission,
DOT, equivalence/inclusion with counterexamples, fragment checks."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from sgplan.errors import AutomatonError
from sgplan.logic import (
    Automaton,
    difference_word,
    distances_to_accept,
    equivalent,
    formula_warnings,
    included,
    inclusion_counterexample,
    is_cosafe,
    ltlf_to_dfa,
    non_cosafe_parts,
    parse_infix,
    parse_prefix,
    remaining_mission,
    shortest_path,
    to_dot,
)
from tests.logic.oracle import formulas, holds

MISSION = parse_infix("F(p1 & F p2) & G !p3")


def test_validation_errors_are_specific():
    with pytest.raises(AutomatonError, match=r"shape \(2, 3\); expected \(num_states >= 1, 2\)"):
        Automaton(("a",), np.zeros((2, 3)), 0, np.zeros(2, bool))
    with pytest.raises(AutomatonError, match=r"targets outside 0..0"):
        Automaton(("a",), np.array([[0, 1]]), 0, np.zeros(1, bool))
    with pytest.raises(AutomatonError, match="initial state 3 is outside"):
        Automaton(("a",), np.zeros((1, 2)), 3, np.zeros(1, bool))
    with pytest.raises(AutomatonError, match="not distinct"):
        Automaton(("a", "a"), np.zeros((1, 4)), 0, np.zeros(1, bool))


def test_from_partial_adds_a_rejecting_sink_only_when_needed():
    a = Automaton.from_partial(("a",), np.array([[1, -1], [1, 1]]), 0, np.array([False, True]))
    assert a.num_states == 3 and a.table[0, 1] == 2 and not a.accepting[2]
    assert a.sink_states().tolist() == [False, False, True]
    b = Automaton.from_partial(("a",), np.array([[1, 0], [1, 1]]), 0, np.array([False, True]))
    assert b.num_states == 2


def test_labels_words_and_relabelling():
    dfa = ltlf_to_dfa(MISSION)
    assert dfa.label_of(["p3", "p1", "other"]) == 0b101 and dfa.props_of(0b101) == {"p1", "p3"}
    word = [dfa.label_of(["p1"]), 0, dfa.label_of(["p2"])]
    assert dfa.run(word).tolist()[0] == dfa.initial and dfa.accepts(word)
    wide = dfa.with_aps(["p3", "x", "p2", "p1"])
    assert wide.accepts([wide.label_of(["p1", "x"]), wide.label_of(["p2"])])
    assert equivalent(wide, dfa)
    with pytest.raises(AutomatonError, match=r"propositions \['p3'\] are not in"):
        dfa.with_aps(["p1", "p2"])


def test_sinks_live_and_reachable():
    dfa = ltlf_to_dfa(MISSION)
    sinks = dfa.sink_states()
    assert sinks.sum() == 1
    sink = int(np.flatnonzero(sinks)[0])
    assert (dfa.table[sink] == sink).all() and not dfa.accepting[sink]
    assert dfa.reachable_states().all() and (dfa.live_states() == ~sinks).all()


def test_shortest_paths_unit_and_weighted():
    dfa = ltlf_to_dfa(parse_infix("F(p1 & F p2) | F p3"))
    unit = shortest_path(dfa)
    assert unit.cost == 1 and len(unit.labels) == 1 and dfa.accepts(list(unit.labels))
    # Labels with p3 cost 10, labels with p1 (but not p3) 3, others 1: p1 then p2 costs 4 < 10.
    p1, p3 = 1 << dfa.aps.index("p1"), 1 << dfa.aps.index("p3")
    labels = np.arange(dfa.num_labels)
    weights = np.where(labels & p3, 10.0, np.where(labels & p1, 3.0, 1.0))
    cheap = shortest_path(dfa, weights=weights)
    assert cheap.cost == 3 and dfa.accepts(list(cheap.labels))
    assert [dfa.props_of(lab) for lab in cheap.labels] == [{"p1", "p2"}]
    dist = distances_to_accept(dfa)
    assert dist[dfa.initial] == 1 and np.isinf(dist[dfa.sink_states()]).all()
    assert (dist[dfa.accepting] == 0).all()
    with pytest.raises(AutomatonError, match="non-negative"):
        distances_to_accept(dfa, weights=-weights)


def test_shortest_path_from_accepting_and_sink_states():
    dfa = ltlf_to_dfa(MISSION)
    accepting = int(np.flatnonzero(dfa.accepting)[0])
    assert shortest_path(dfa, accepting).states == (accepting,)
    sink = int(np.flatnonzero(dfa.sink_states())[0])
    assert shortest_path(dfa, sink) is None and remaining_mission(dfa, sink) is None


def test_remaining_mission_keeps_order_and_negations():
    dfa = ltlf_to_dfa(MISSION)
    rest = remaining_mission(dfa, dfa.initial)
    assert rest.to_make_true == (frozenset({"p1", "p2"}),)  # one cell may do both
    assert rest.to_keep_false == {"p3"}
    after_p1 = dfa.step(dfa.initial, dfa.label_of(["p1"]))
    rest = remaining_mission(dfa, after_p1)
    assert rest.to_make_true == (frozenset({"p2"}),) and rest.to_keep_false == {"p3"}
    accepting = int(np.flatnonzero(dfa.accepting)[0])
    assert remaining_mission(dfa, accepting).steps == ()


def test_remaining_mission_does_not_ask_to_avoid_a_room_left_behind():
    # Rooms exclude each other: entering p2 means p1 is false, but p1 is not a room to avoid.
    dfa = ltlf_to_dfa(parse_infix("F(p1 & F p2) & G !p3 & G !(p1 & p2)"))
    after_p1 = dfa.step(dfa.initial, dfa.label_of(["p1"]))
    rest = remaining_mission(dfa, after_p1)
    assert "p1" in rest.steps[-1].must_not_hold
    assert rest.to_make_true == (frozenset({"p2"}),) and rest.to_keep_false == {"p3"}


def test_dot_export():
    dfa = ltlf_to_dfa(MISSION)
    text = to_dot(dfa)
    assert text.startswith('digraph "automaton" {') and "doublecircle" in text
    assert f"init -> {dfa.initial};" in text and '!p1&!p3' in text
    sink = int(np.flatnonzero(dfa.sink_states())[0])
    assert f"{sink} [shape" in text and f"{sink} [shape" not in to_dot(dfa, hide_sinks=True)


def test_equivalence_and_inclusion_with_counterexamples():
    assert equivalent(parse_infix("!(p U q)"), parse_infix("!p R !q"))
    assert equivalent(parse_infix("G !p"), parse_infix("!F p"))
    stronger, weaker = parse_infix("F(p & F q)"), parse_infix("F p & F q")
    assert included(stronger, weaker) and not included(weaker, stronger)
    word = inclusion_counterexample(weaker, stronger)
    assert word == (frozenset({"q"}), frozenset({"p"}))
    assert difference_word(stronger, weaker) == word
    assert difference_word(parse_infix("G p"), parse_infix("true")) == (frozenset(),)


@settings(max_examples=40, deadline=None)
@given(formulas(("a", "b", "c"), max_leaves=6), formulas(("a", "b", "c"), max_leaves=6))
def test_counterexample_words_really_separate(f, g):
    word = difference_word(f, g)
    if word is None:
        assert equivalent(g, f)
        return
    aps = ("a", "b", "c")
    labels = np.array([[sum(1 << aps.index(p) for p in letter) for letter in word]], dtype=np.int64)
    assert holds(f, labels, aps)[0] != holds(g, labels, aps)[0]


def test_cosafety_and_warnings():
    benevolence_1 = parse_prefix("& & F & p1 ! p2 F & p3 p4 G & ! p5 ! p6")
    assert not is_cosafe(benevolence_1)
    assert [str(p) for p in non_cosafe_parts(benevolence_1)] == ["G(!p5 & !p6)"]
    assert is_cosafe(parse_infix("F(p & X q) & !G r & (a U b)"))
    assert not is_cosafe(parse_infix("!X p"))  # weak next
    allensville_3 = parse_prefix("& & p1 p2 e | p3 p2 & & F p4 F p5 F p6")
    warnings = formula_warnings(allensville_3)
    assert warnings[0] == "'p1' has no temporal operator, so it only constrains the first cell of the path"
    assert any("'p3 | p2' in" in w and "first cell" in w for w in warnings)
    assert formula_warnings(parse_infix("F(a & F b) & G !c")) == []
    assert "NEXT" in formula_warnings(parse_infix("F(a & X b)"))[0]
