"""Automaton pictures: the shared edge list, DOT with renamed and wrapped guards, SVG by both engines."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

from sgplan.errors import AutomatonError
from sgplan.logic import ltlf_to_dfa, parse_infix
from sgplan.logic.dot import edges, to_dot, wrap_guard
from sgplan.report.automaton import automaton_svg, graphviz_available, write_automaton

MISSION = parse_infix("F(p1 & F p2) & G !p3")
NAMES = {"p1": "enter(room_2)", "p2": "reach(object_17)", "p3": "enter(room_6)"}


def test_edges_cover_every_transition_of_the_shown_states() -> None:
    dfa = ltlf_to_dfa(MISSION)
    listed = edges(dfa, hide_sinks=True)
    live = ~dfa.sink_states()
    # Exactly one edge per (state, successor) pair among live states, none into the sink.
    expected = {(q, int(r)) for q in np.flatnonzero(live) for r in np.unique(dfa.table[q]) if live[r]}
    assert {(q, r) for q, r, _ in listed} == expected and len(listed) == len(expected)
    renamed = edges(dfa, hide_sinks=True, names=NAMES)
    assert [(q, r) for q, r, _ in renamed] == [(q, r) for q, r, _ in listed]
    assert all("p1" not in g and "p3" not in g for *_, g in renamed)
    assert any("enter(room_6)" in g for *_, g in renamed)


def test_wrap_guard_keeps_the_expression() -> None:
    guard = (
        "!enter(room_5)&!reach(object_21)&!enter(room_7)&!enter(room_11)"
        " | reach(object_21)&!enter(room_7) | true"
    )
    wrapped = wrap_guard(guard, width=30)
    lines = wrapped.split("\n")
    assert len(lines) >= 4 and all(len(line) <= 34 for line in lines)
    assert lines[-1] == "| true" and sum(line.startswith("| ") for line in lines) == 2
    assert re.sub(r"\s+", "", wrapped) == re.sub(r"\s+", "", guard)
    assert wrap_guard("p1&!p2") == "p1&!p2"


def test_dot_with_names_and_line_breaks() -> None:
    dfa = ltlf_to_dfa(MISSION)
    text = to_dot(dfa, hide_sinks=True, names=NAMES)
    assert "enter(room_6)" in text and '"p1' not in text
    # Multi-line guards use DOT's left-justified line ends; the text stays one DOT statement per line.
    long = to_dot(dfa, names={ap: f"a_rather_long_name_for({ap})" for ap in dfa.aps})
    assert "\\l" in long and all(line.startswith(("digraph", "  ", "}")) for line in long.splitlines())


@pytest.mark.skipif(
    not graphviz_available(), reason="Graphviz `dot` is not installed (apt-get install graphviz)"
)
def test_graphviz_svg_and_dot_parse(tmp_path: Path) -> None:
    dfa = ltlf_to_dfa(MISSION)
    svg = automaton_svg(dfa, names=NAMES, engine="graphviz")
    assert svg.startswith("<svg") and "enter(room_6)" in svg
    dot_path, svg_path = write_automaton(dfa, tmp_path, names=NAMES, engine="graphviz")
    done = subprocess.run(["dot", "-Tplain", str(dot_path)], capture_output=True, text=True, check=False)
    assert done.returncode == 0 and done.stdout.startswith("graph")
    assert svg_path.read_text(encoding="utf-8").startswith("<svg")


def test_matplotlib_svg_shows_states_and_guards(tmp_path: Path) -> None:
    dfa = ltlf_to_dfa(MISSION)
    svg = automaton_svg(dfa, names=NAMES, engine="matplotlib")
    assert svg.startswith("<svg") and "<?xml" not in svg
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", svg)
    shown = np.flatnonzero(~dfa.sink_states())
    assert {str(q) for q in shown} <= set(texts)
    assert any("reach(object_17)" in t for t in texts)
    written = write_automaton(dfa, tmp_path / "out", stem="mission", engine="matplotlib")
    assert [p.name for p in written] == ["mission.dot", "mission.svg"]


def test_engine_errors(monkeypatch: pytest.MonkeyPatch) -> None:
    dfa = ltlf_to_dfa(MISSION)
    with pytest.raises(AutomatonError, match="unknown automaton drawing engine"):
        automaton_svg(dfa, engine="tikz")  # type: ignore[arg-type]
    monkeypatch.setenv("PATH", "")
    with pytest.raises(AutomatonError, match="Graphviz is not installed"):
        automaton_svg(dfa, engine="graphviz")
    assert automaton_svg(dfa, engine="auto").startswith("<svg")  # falls back to matplotlib


def test_large_automata_get_numbered_edges_or_a_note() -> None:
    big = ltlf_to_dfa(parse_infix("F p1 & F p2 & F p3 & F p4 & G !p5"))  # 16 live states, many edges
    listed = edges(big, hide_sinks=True)
    assert len(listed) > 12
    svg = automaton_svg(big, engine="matplotlib")  # numbered by default above 12 edges
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", svg)
    assert f"[{len(listed)}]" in texts and not any("&" in t for t in texts)
    dot = to_dot(big, hide_sinks=True, numbered=True)
    assert dot.count('label="[') == len(listed) and dot.count("tooltip=") == len(listed)
    huge = ltlf_to_dfa(parse_infix("F p1 & F p2 & F p3 & F p4 & F p5"))  # 32 states
    note = automaton_svg(huge, engine="matplotlib")
    assert note.startswith("<svg") and "too large to draw without Graphviz" in note
