"""The 15 shipped missions: every automaton.aut loads, and agrees with our DFA of both formula files."""

from __future__ import annotations

import ast

import numpy as np
import pytest

from sgplan.logic import (
    difference_word,
    ltlf_to_dfa,
    number_aps,
    parse_prefix,
    parse_tokens,
    read_hoa,
)

# reference-algorithm.md §10: (start, accepting state, |Q|, |AP|, missing (q, label) pairs).
SHIPPED = {
    ("Allensville", 1): (3, 0, 32, 8, 0), ("Allensville", 2): (2, 0, 9, 4, 0),
    ("Allensville", 3): (1, 0, 9, 5, 24), ("Allensville", 4): (1, 2, 3, 4, 24),
    ("Allensville", 5): (2, 0, 3, 3, 2), ("Benevolence", 1): (2, 0, 4, 6, 192),
    ("Benevolence", 2): (2, 0, 9, 7, 0), ("Benevolence", 3): (6, 0, 9, 5, 0),
    ("Benevolence", 4): (2, 6, 12, 6, 384), ("Benevolence", 5): (2, 0, 16, 7, 512),
    ("Collierville", 1): (2, 0, 4, 3, 16), ("Collierville", 2): (3, 0, 4, 4, 0),
    ("Collierville", 3): (5, 0, 24, 5, 0), ("Collierville", 4): (3, 0, 8, 6, 64),
    ("Collierville", 5): (1, 0, 33, 9, 0),
}


@pytest.mark.gibson
@pytest.mark.parametrize(("scene", "k"), sorted(SHIPPED))
def test_shipped_mission(gibson_root, scene, k):
    folder = gibson_root / scene / "missions" / str(k)
    start, accepting, num_states, num_aps, missing = SHIPPED[scene, k]

    authors = read_hoa(folder / "automaton.aut", profile="authors")
    assert (authors.initial, authors.num_states, len(authors.aps)) == (start, num_states, num_aps)
    assert np.flatnonzero(authors.accepting).tolist() == [accepting]
    strict = read_hoa(folder / "automaton.aut")
    assert strict.num_states == num_states + (missing > 0)
    if missing:
        sink = num_states
        assert int((strict.table[:num_states] == sink).sum()) == missing
        # Under the authors' rule exactly those pairs keep their state.
        kept = strict.table[:num_states] == sink
        assert (authors.table[kept] == np.nonzero(kept)[0]).all()

    spot_formula = parse_prefix((folder / "Spot_LTL_formula.txt").read_text())
    tokens = (folder / "GPT_LTL_formula.txt").read_text()
    ap_dict = ast.literal_eval((folder / "ap_dict.txt").read_text())
    assert number_aps(tokens) == ap_dict
    gpt_formula = parse_tokens(tokens, ap_names=ap_dict)

    ours = ltlf_to_dfa(spot_formula)
    assert difference_word(ours, strict) is None
    assert difference_word(ltlf_to_dfa(gpt_formula), strict) is None
    # Known entities: every id of env_elements.txt (written as [object_43, room_2, ...]).
    known = (folder / "env_elements.txt").read_text().strip().strip("[]").replace(" ", "").split(",")
    assert parse_tokens(tokens, known=known, ap_names=ap_dict) == gpt_formula
