"""Graphviz DOT drawing of an automaton, and the edge list every drawing of it shares."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.logic.labels import format_cover, label_cover

GUARD_LINE_CHARS = 40
"""Guards longer than this are broken into lines: one disjunct per line, long conjunctions wrapped."""


def _escape(text: str) -> str:
    """A DOT string body: backslashes and quotes escaped, line breaks as DOT's left-justified ``\\l``."""
    body = text.replace("\\", "\\\\").replace('"', '\\"')
    return body.replace("\n", "\\l") + "\\l" if "\n" in text else body


def wrap_guard(guard: str, width: int = GUARD_LINE_CHARS) -> str:
    """The guard on several lines: a line per disjunct (from the second on, led by ``|``), long ones cut
    before an ``&``."""
    lines = []
    for k, term in enumerate(guard.split(" | ")):
        line = "| " if k else ""
        for j, literal in enumerate(term.split("&")):
            piece = ("&" if j else "") + literal
            if len(line) + len(piece) > width and line.strip("| "):
                lines.append(line)
                line = "  "
            line += piece
        lines.append(line)
    return "\n".join(lines)


def shown_states(a: Automaton, hide_sinks: bool = False) -> np.ndarray:
    """``(num_states,)`` bool: the states a drawing shows (all, or without the rejecting sinks).

    The initial state is always shown, even when it is a sink (the mission is then unsatisfiable).
    """
    shown = ~a.sink_states() if hide_sinks else np.ones(a.num_states, bool)
    shown[a.initial] = True
    return shown


def edges(
    a: Automaton, hide_sinks: bool = False, names: Mapping[str, str] | None = None
) -> list[tuple[int, int, str]]:
    """``(source, target, guard)`` for every pair of shown states joined by some label.

    The guard is an expression over the propositions (``&``, ``|``, ``!``, ``true``); ``names`` renames
    propositions in it (e.g. ``{"p1": "enter(room_2)"}``). With ``hide_sinks`` the edges into the states
    that cannot reach acceptance are left out (a missing edge then means "rejects").
    """
    shown = shown_states(a, hide_sinks)
    labels = [names.get(ap, ap) if names else ap for ap in a.aps]
    out = []
    for q in np.flatnonzero(shown):
        for r in np.unique(a.table[q]):
            if shown[r]:
                guard = format_cover(label_cover(a.table[q] == r), labels, true="true", false="false")
                out.append((int(q), int(r), guard))
    return out


def to_dot(
    a: Automaton,
    hide_sinks: bool = False,
    name: str = "automaton",
    names: Mapping[str, str] | None = None,
    numbered: bool = False,
) -> str:
    """DOT text: accepting states double circles, edges labelled with expressions over the propositions.

    With ``hide_sinks`` the states that cannot reach acceptance, and the edges into them, are left out
    (a missing edge then means "rejects"); ``names`` renames propositions in the edge labels. With
    ``numbered`` an edge is labelled ``[k]``, its position in :func:`edges` from 1, and its guard becomes
    its tooltip (large automata stay readable next to a table of the guards).
    """
    shown = shown_states(a, hide_sinks)
    lines = [
        f'digraph "{_escape(name)}" {{',
        "  rankdir=LR;",
        "  node [fontsize=12]; edge [fontsize=9];",
        '  init [shape=point, label=""];',
    ]
    for q in np.flatnonzero(shown).tolist():
        shape = "doublecircle" if a.accepting[q] else "circle"
        lines.append(f'  {q} [shape={shape}, label="{q}"];')
    lines.append(f"  init -> {a.initial};")
    for k, (q, r, guard) in enumerate(edges(a, hide_sinks, names), start=1):
        if numbered:
            lines.append(f'  {q} -> {r} [label="[{k}]", tooltip="{_escape(guard)}"];')
        else:
            lines.append(f'  {q} -> {r} [label="{_escape(wrap_guard(guard))}"];')
    lines.append("}")
    return "\n".join(lines) + "\n"
