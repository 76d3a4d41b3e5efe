"""HOA reading (both profiles) and writing, and precise errors on what we do not support."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from sgplan.errors import AutomatonError
from sgplan.logic import equivalent, ltlf_to_dfa, minimize, parse_hoa, parse_infix, read_hoa, write_hoa
from tests.logic.oracle import formulas

# Allensville mission 5 as shipped: state 2 has no edge for labels with p1 & p2 (bits 0 and 1).
ALLENSVILLE_5 = """HOA: v1
States: 3
Start: 2
AP: 3 "p1" "p2" "p3"
acc-name: Buchi
Acceptance: 1 Inf(0)
properties: trans-labels explicit-labels state-acc deterministic
--BODY--
State: 0 {0}
[t] 0
State: 1
[2] 0
[!2] 1
State: 2
[!0&2 | !1&2] 0
[!0&!2 | !1&!2] 1
--END--
"""


def test_missing_edges_reject_by_default_and_stay_under_the_authors_profile():
    strict = parse_hoa(ALLENSVILLE_5)
    assert strict.aps == ("p1", "p2", "p3") and strict.num_states == 4 and strict.initial == 2
    assert strict.accepting.tolist() == [True, False, False, False]
    assert strict.table[2, 0b011] == 3 and strict.sink_states()[3]
    assert strict.table[2, 0b100] == 0 and strict.table[1, 0b000] == 1
    authors = parse_hoa(ALLENSVILLE_5, profile="authors")
    assert authors.num_states == 3
    assert authors.table[2, 0b011] == 2 and authors.table[2, 0b111] == 2


def test_authors_profile_ignores_self_loops_that_overlap_other_edges():
    text = ALLENSVILLE_5.replace("[!2] 1", "[t] 1")  # self-loop now overlaps the edge to 0
    with pytest.raises(AutomatonError, match=r"line 13: state 1 has two edges for label 4 .* deterministic"):
        parse_hoa(text)
    authors = parse_hoa(text, profile="authors")
    assert authors.table[1, 0b100] == 0 and authors.table[1, 0b000] == 1


def test_transition_marks_on_self_loops_make_states_accepting():
    text = ALLENSVILLE_5.replace("State: 0 {0}\n[t] 0", "State: 0\n[t] 0 {0}")
    assert parse_hoa(text).accepting[0]
    bad = ALLENSVILLE_5.replace("[2] 0", "[2] 0 {0}")
    with pytest.raises(
        AutomatonError, match="line 12: an acceptance mark on an edge between different states"
    ):
        parse_hoa(bad)


@settings(max_examples=60, deadline=None)
@given(formulas(("a", "b", "c"), max_leaves=8))
def test_write_then_read_preserves_the_language(formula):
    dfa = ltlf_to_dfa(formula)
    text = write_hoa(dfa, name=str(formula))
    for profile in ("ltlf", "authors"):
        back = parse_hoa(text, profile=profile)
        assert back.aps == dfa.aps
        assert np.array_equal(back.table, dfa.table) and back.initial == dfa.initial
        assert np.array_equal(back.accepting, dfa.accepting)


def test_write_hoa_to_a_file(tmp_path):
    dfa = ltlf_to_dfa(parse_infix('F("enter(room_2)" & F p) & G !q'))
    path = tmp_path / "a.aut"
    write_hoa(dfa, path)
    assert equivalent(read_hoa(path), dfa)
    assert '"enter(room_2)"' in path.read_text()


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("Acceptance: 1 Inf(0)", "Acceptance: 2 Inf(0)&Inf(1)"),
         "line 6: acceptance '2 Inf(0)&Inf(1)' is not supported; sgplan reads Buchi automata"),
        (("Acceptance: 1 Inf(0)", "Acceptance: 1 Fin(0)"), "line 6: acceptance '1 Fin(0)' is not supported"),
        (("[2] 0", "[2 & ] 0"), "line 12: expected an AP index, t, f, ! or ( in an edge label, found ']'"),
        (("[2] 0", "[3] 0"), "line 12: edge label uses AP 3 but the AP: line declares 3"),
        (("[2] 0", "2 0"), "line 12: expected an edge '[label] target', found '2' (implicit labels"),
        (("[2] 0", "[@a] 0"), "line 12: alias @a is not supported"),
        (("[2] 0", "[2] 0&1"), "line 12: universal branching"),
        (("[2] 0", "[2] 7"), "an edge target names state 7 but the automaton has 3 states"),
        (("--END--\n", ""), "line 17: the body ends without --END--"),
        (("HOA: v1", "HOA v1"), "line 1: expected 'HOA: v1' at the start"),
        (("Start: 2", "Start: 2\nStart: 1"), "line 4: several Start: lines"),
        (("State: 1\n", "State: 1 {1}\n"), "line 11: acceptance mark 1 is not declared"),
        (("State: 1\n", "State: 1 %\n"), "line 11: unexpected character '%'"),
    ],
)
def test_hoa_errors_are_precise(change, message):
    text = ALLENSVILLE_5.replace(*change)
    with pytest.raises(AutomatonError) as info:
        parse_hoa(text, path="mission/automaton.aut")
    assert str(info.value).startswith("mission/automaton.aut: " + message)


def test_read_hoa_reports_unreadable_files(tmp_path):
    with pytest.raises(AutomatonError, match=r"missing.aut: cannot read the automaton file"):
        read_hoa(tmp_path / "missing.aut")
    with pytest.raises(AutomatonError, match="unknown automaton profile 'stay'"):
        parse_hoa(ALLENSVILLE_5, profile="stay")


def test_reading_spot_output_matches_our_construction():
    dfa = parse_hoa(ALLENSVILLE_5)
    ours = ltlf_to_dfa(parse_infix("(p1 -> !p2) & F p3"), aps=["p1", "p2", "p3"])
    assert equivalent(dfa, ours)
    assert minimize(dfa).num_states == ours.num_states
