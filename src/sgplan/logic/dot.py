"""Graphviz DOT drawing of an automaton."""

from __future__ import annotations

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.logic.labels import format_cover, label_cover


def _escape(text: str) -> str:
    return text.replace("\\", "\\\\").replace('"', '\\"')


def to_dot(a: Automaton, hide_sinks: bool = False, name: str = "automaton") -> str:
    """DOT text: accepting states double circles, edges labelled with expressions over the propositions.

    With ``hide_sinks`` the states that cannot reach acceptance, and the edges into them, are left out
    (a missing edge then means "rejects").
    """
    shown = ~a.sink_states() if hide_sinks else np.ones(a.num_states, bool)
    shown[a.initial] = True
    lines = [f'digraph "{_escape(name)}" {{', "  rankdir=LR;", '  init [shape=point, label=""];']
    for q in np.flatnonzero(shown):
        shape = "doublecircle" if a.accepting[q] else "circle"
        lines.append(f'  {q} [shape={shape}, label="{q}"];')
    lines.append(f"  init -> {a.initial};")
    for q in np.flatnonzero(shown):
        for r in np.unique(a.table[q]):
            if shown[r]:
                text = format_cover(label_cover(a.table[q] == r), a.aps, true="true", false="false")
                lines.append(f'  {q} -> {r} [label="{_escape(text)}"];')
    lines.append("}")
    return "\n".join(lines) + "\n"
