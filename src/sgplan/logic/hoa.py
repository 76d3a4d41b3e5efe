"""Reading and writing the HOA automaton format for what Spot emits (no Spot needed).

Supported: one automaton per file, one initial state, ``AP:`` line (label bit ``i`` = ``i``-th AP),
Büchi acceptance ``Acceptance: 1 Inf(0)``, explicit edge labels over AP indices
with ``t f ! & | ( )``, and acceptance mark 0 on states (``State: 3 {0}``) or on self-loops
(transition-based marks as Spot may emit them). Anything else (aliases, implicit labels, state labels,
universal branching, other acceptance conditions) is refused with a precise :class:`AutomatonError`.

Read as a finite automaton, a state is accepting iff it carries mark 0 (or a self-loop with mark 0).
Two profiles say what a missing edge means:

``"ltlf"`` (default)
    a missing edge goes to a rejecting sink (added as the last state). Overlapping edges with different
    targets are an error (the automaton must be deterministic).
``"authors"``
    the authors' C++ rule (reference-algorithm.md §1.5): self-loops are ignored, the next state is the
    target of the non-self-loop edge containing the label, and a label with no such edge keeps the state.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

import numpy as np

from sgplan.errors import AutomatonError
from sgplan.files import write_text_atomically
from sgplan.logic.automaton import Automaton
from sgplan.logic.labels import format_cover, label_cover
from sgplan.logic.ltlf import DEFAULT_MAX_ENTRIES
from sgplan.safeio import quote, read_text

Profile = Literal["ltlf", "authors"]

MAX_HOA_APS = 20
"""Propositions an automaton file may declare: the transition table has 2^APs columns per state."""
MAX_HOA_TABLE = DEFAULT_MAX_ENTRIES
"""Entries (states x 2^APs) of the transition table a file may ask for, as for a formula's automaton."""
MAX_HOA_BYTES = 64 * 2**20
"""Size cap of an automaton file (64 MiB)."""
MAX_LABEL_DEPTH = 100
"""Nesting of ``!`` and ``(`` in one edge label (the label parser recurses)."""

_TOKEN = re.compile(
    r"""(?P<space>\s+|/\*.*?\*/)
    | (?P<string>"(?:[^"\\]|\\.)*")
    | (?P<marker>--BODY--|--END--|--ABORT--)
    | (?P<header>[A-Za-z_][A-Za-z0-9_-]*:)
    | (?P<alias>@[A-Za-z0-9_-]+)
    | (?P<int>\d+)
    | (?P<ident>[A-Za-z_][A-Za-z0-9_-]*)
    | (?P<punct>[!&|()\[\]{}])""",
    re.VERBOSE | re.DOTALL,
)


class _Tokens:
    """HOA tokens with line numbers; ``error`` builds an AutomatonError naming the line."""

    def __init__(self, text: str, path: Path | None) -> None:
        self.path = path
        self.lines = text.splitlines()
        self.items: list[tuple[str, str, int]] = []
        pos, line = 0, 1
        while pos < len(text):
            m = _TOKEN.match(text, pos)
            if m is None:
                raise AutomatonError(f"line {line}: unexpected character {text[pos]!r}", path)
            kind = m.lastgroup
            assert kind is not None, "every alternative of _TOKEN is a named group"
            if kind != "space":
                self.items.append((kind, m.group(), line))
            line += m.group().count("\n")
            pos = m.end()
        self.items.append(("eof", "end of file", line))
        self.i = 0

    def peek(self) -> tuple[str, str, int]:
        return self.items[self.i]

    def take(self) -> tuple[str, str, int]:
        item = self.items[self.i]
        if item[0] != "eof":
            self.i += 1
        return item

    def error(self, message: str, item: tuple[str, str, int] | None = None) -> AutomatonError:
        _, _, line = item or self.peek()
        return AutomatonError(f"line {line}: {message}", self.path)

    def expect(self, kind: str, what: str) -> str:
        item = self.take()
        if item[0] != kind:
            raise self.error(f"expected {what}, found {quote(item[1])}", item)
        return item[1]


def _parse_label(tokens: _Tokens, num_aps: int, labels: np.ndarray) -> np.ndarray:
    """A label expression ``0&!1 | t`` as the bool array of the labels it contains (up to ``]``)."""

    def disjunction(depth: int) -> np.ndarray:
        value = conjunction(depth)
        while tokens.peek()[1] == "|":
            tokens.take()
            value = value | conjunction(depth)
        return value

    def conjunction(depth: int) -> np.ndarray:
        value = negation(depth)
        while tokens.peek()[1] == "&":
            tokens.take()
            value = value & negation(depth)
        return value

    def negation(depth: int) -> np.ndarray:
        item = tokens.take()
        kind, text, _ = item
        if depth > MAX_LABEL_DEPTH:
            raise tokens.error(f"an edge label nests '!' and '(' more than {MAX_LABEL_DEPTH} deep", item)
        if text == "!":
            return ~negation(depth + 1)
        if text == "(":
            value = disjunction(depth + 1)
            if tokens.take()[1] != ")":
                raise tokens.error("unbalanced parenthesis in an edge label", item)
            return value
        if kind == "int":
            index = int(text)
            if index >= num_aps:
                raise tokens.error(f"edge label uses AP {index} but the AP: line declares {num_aps}", item)
            return (labels >> index & 1).astype(bool)
        if kind == "ident" and text in ("t", "f"):
            return np.full(labels.size, text == "t")
        if kind == "alias":
            raise tokens.error(f"alias {text} is not supported; write labels over AP indices", item)
        raise tokens.error(f"expected an AP index, t, f, ! or ( in an edge label, found {quote(text)}", item)

    value = disjunction(0)
    if tokens.take()[1] != "]":
        raise tokens.error("an edge label must end with ]")
    return value


def _parse_marks(tokens: _Tokens) -> set[int]:
    marks: set[int] = set()
    if tokens.peek()[1] != "{":
        return marks
    tokens.take()
    while tokens.peek()[1] != "}":
        item = tokens.take()
        if item[0] != "int":
            raise tokens.error(f"expected an acceptance mark number, found {quote(item[1])}", item)
        if int(item[1]) != 0:
            raise tokens.error(
                f"acceptance mark {item[1]} is not declared (Buchi acceptance has mark 0 only)", item
            )
        marks.add(0)
    tokens.take()
    return marks


def parse_hoa(text: str, profile: Profile = "ltlf", path: str | Path | None = None) -> Automaton:
    """Read an automaton from HOA text; see the module docstring for what is supported.

    Parameters
    ----------
    text:
        the HOA text (only the first automaton is read).
    profile:
        ``"ltlf"`` (missing edge -> rejecting sink) or ``"authors"`` (missing edge keeps the state).
    path:
        the file the text came from, named in error messages.

    Raises
    ------
    AutomatonError
        syntax errors (with the line), unsupported features or acceptance, nondeterminism.
    """
    if profile not in ("ltlf", "authors"):
        raise AutomatonError(f"unknown automaton profile {profile!r}; use 'ltlf' or 'authors'", path)
    tokens = _Tokens(text, Path(path) if path is not None else None)
    header = _parse_header(tokens)
    labels = np.arange(1 << len(header.aps), dtype=np.int64)
    body = _parse_body(tokens, len(header.aps), labels)
    n = _state_count(header, body, tokens.path)
    accepting = _accepting_states(n, body, tokens)
    table = _transition_table(n, labels.size, body.edges, profile, tokens)
    assert header.initial is not None  # _parse_header refuses a header without Start:
    return Automaton.from_partial(tuple(header.aps), table, header.initial, accepting)


@dataclass
class _Header:
    """What the header says: ``States:`` (``None`` if absent), ``Start:`` and ``AP:``."""

    num_states: int | None = None
    initial: int | None = None
    aps: list[str] = field(default_factory=list)


_Edge = tuple[int, np.ndarray, int, set[int], tuple[str, str, int]]
"""``(state, labels it is taken on (bool per label), target, marks, its token)``."""


@dataclass
class _Body:
    """The states and edges of the body: each state's marks, the declared states, the edges."""

    state_marks: dict[int, set[int]] = field(default_factory=dict)
    declared: set[int] = field(default_factory=set)
    edges: list[_Edge] = field(default_factory=list)


def _parse_header(tokens: _Tokens) -> _Header:
    """The header, up to and including ``--BODY--``; checks the version, the acceptance and the size."""
    first = tokens.take()
    if first[1] != "HOA:":
        raise tokens.error(f"expected 'HOA: v1' at the start, found {quote(first[1])}", first)
    tokens.expect("ident", "the version v1")
    header = _Header()
    while True:
        item = tokens.take()
        kind, name, _ = item
        if kind == "marker" and name == "--BODY--":
            break
        if kind != "header":
            raise tokens.error(f"expected a header line or --BODY--, found {quote(name)}", item)
        _header_line(tokens, item, header)
    if header.initial is None:
        raise tokens.error("the header has no Start: line")
    if header.num_states is not None and header.num_states << len(header.aps) > MAX_HOA_TABLE:
        raise tokens.error(
            f"States: {header.num_states} over {len(header.aps)} APs is a table of "
            f"{header.num_states << len(header.aps):,} entries, more than the {MAX_HOA_TABLE:,} sgplan builds"
        )
    return header


def _header_line(tokens: _Tokens, item: tuple[str, str, int], header: _Header) -> None:
    """Read the header line that starts with ``item`` into ``header``."""
    name = item[1]
    if name == "States:":
        header.num_states = int(tokens.expect("int", "the number of states"))
        if header.num_states < 1 or header.num_states > MAX_HOA_TABLE:
            raise tokens.error(f"States: {header.num_states} is not between 1 and {MAX_HOA_TABLE:,}", item)
    elif name == "Start:":
        if header.initial is not None:
            raise tokens.error("several Start: lines (several initial states) are not supported", item)
        header.initial = int(tokens.expect("int", "the initial state"))
        if tokens.peek()[1] == "&":
            raise tokens.error("a conjunction of initial states (alternation) is not supported", item)
    elif name == "AP:":
        count = int(tokens.expect("int", "the number of APs"))
        if count > MAX_HOA_APS:
            raise tokens.error(f"AP: declares {count} propositions; sgplan reads at most {MAX_HOA_APS} "
                               f"(the transition table has 2^APs columns per state)", item)
        header.aps = [tokens.expect("string", f"{count} quoted AP names")[1:-1] for _ in range(count)]
        if len(set(header.aps)) != count:
            raise tokens.error(f"the AP: line names a proposition twice: {quote(header.aps)}", item)
    elif name == "Acceptance:":
        acceptance = []
        while tokens.peek()[0] not in ("header", "marker", "eof"):
            acceptance.append(tokens.take()[1])
        if "".join(acceptance) != "1Inf(0)":
            written = tokens.lines[item[2] - 1].split("Acceptance:", 1)[-1].strip()
            raise tokens.error(
                f"acceptance '{written}' is not supported; sgplan reads Buchi automata "
                f"('Acceptance: 1 Inf(0)', accepting states marked {{0}})",
                item,
            )
    elif name in ("Alias:", "controllable-AP:"):
        raise tokens.error(f"header {name} is not supported", item)
    else:  # name:, tool:, acc-name:, properties:, and unknown headers carry no semantics we need
        while tokens.peek()[0] not in ("header", "marker", "eof"):
            tokens.take()


def _parse_body(tokens: _Tokens, num_aps: int, labels: np.ndarray) -> _Body:
    """The body, up to and including ``--END--``: every ``State:`` with its marks and edges."""
    body = _Body()
    while True:
        item = tokens.take()
        if item[1] == "--END--":
            return body
        if item[1] != "State:":
            raise tokens.error(f"expected 'State:' or '--END--', found {quote(item[1])}", item)
        if tokens.peek()[1] == "[":
            raise tokens.error("state labels are not supported; label the edges", item)
        state = int(tokens.expect("int", "a state number"))
        if state in body.declared:
            raise tokens.error(f"state {state} is declared twice", item)
        body.declared.add(state)
        if tokens.peek()[0] == "string":
            tokens.take()
        body.state_marks[state] = _parse_marks(tokens)
        while tokens.peek()[1] not in ("State:", "--END--") and tokens.peek()[0] != "eof":
            body.edges.append(_parse_edge(tokens, state, num_aps, labels))
        if tokens.peek()[0] == "eof":
            raise tokens.error("the body ends without --END--")


def _parse_edge(tokens: _Tokens, state: int, num_aps: int, labels: np.ndarray) -> _Edge:
    """One edge ``[label] target {marks}`` of ``state``."""
    edge = tokens.take()
    if edge[1] != "[":
        raise tokens.error(
            f"expected an edge '[label] target', found {quote(edge[1])} (implicit labels are not supported)",
            edge,
        )
    members = _parse_label(tokens, num_aps, labels)
    target = int(tokens.expect("int", "the edge's target state"))
    if tokens.peek()[1] == "&":
        raise tokens.error("universal branching (target1&target2) is not supported", edge)
    return (state, members, target, _parse_marks(tokens), edge)


def _state_count(header: _Header, body: _Body, source: Path | None) -> int:
    """The number of states (``States:``, else one past the highest named), checked against every state
    number the automaton names and the table size."""
    assert header.initial is not None  # _parse_header refuses a header without Start:
    edges, declared = body.edges, body.declared
    n = header.num_states if header.num_states is not None else max(
        declared | {e[2] for e in edges} | {header.initial}) + 1
    if n << len(header.aps) > MAX_HOA_TABLE:
        raise AutomatonError(f"the automaton uses {n:,} states over {len(header.aps)} APs, a table of more "
                             f"than {MAX_HOA_TABLE:,} entries", source)
    named = [(header.initial, "Start:")] + [(e[2], "an edge target") for e in edges] + \
        [(s, "State:") for s in declared]
    for value, what in named:
        if not 0 <= value < n:
            raise AutomatonError(f"{what} names state {value} but the automaton has {n} states (0..{n - 1})",
                                 source)
    return n


def _accepting_states(n: int, body: _Body, tokens: _Tokens) -> np.ndarray:
    """``(n,)`` bool: the states marked 0, or with a self-loop marked 0."""
    accepting = np.zeros(n, bool)
    for state, marks in body.state_marks.items():
        accepting[state] |= 0 in marks
    for state, _, target, marks, edge in body.edges:
        if 0 in marks:
            if target != state:
                raise tokens.error("an acceptance mark on an edge between different states is not supported",
                                   edge)
            accepting[state] = True
    return accepting


def _transition_table(n: int, num_labels: int, edges: list[_Edge], profile: Profile,
                      tokens: _Tokens) -> np.ndarray:
    """``(n, num_labels)`` targets, -1 where no edge is given (``ltlf``: completed later with a rejecting
    sink), the state itself under ``authors`` (a missing edge keeps the state; self-loops are implied)."""
    if profile == "authors":
        table = np.repeat(np.arange(n, dtype=np.int32)[:, None], num_labels, axis=1)
        edges = [e for e in edges if e[0] != e[2]]
    else:
        table = np.full((n, num_labels), -1, np.int32)
    assigned = np.zeros((n, num_labels), bool)
    for state, members, target, _, edge in edges:
        clash = members & assigned[state] & (table[state] != target)
        if clash.any():
            label = int(np.flatnonzero(clash)[0])
            raise tokens.error(
                f"state {state} has two edges for label {label} (to {table[state, label]} and {target}); "
                f"only deterministic automata are supported",
                edge,
            )
        table[state, members] = target
        assigned[state] |= members
    return table


def read_hoa(path: str | Path, profile: Profile = "ltlf") -> Automaton:
    """Read a HOA file; see :func:`parse_hoa`.

    Raises
    ------
    AutomatonError
        the file cannot be read or is not a supported HOA automaton (the message names the file).
    """
    path = Path(path)
    return parse_hoa(read_text(path, AutomatonError, "automaton file", MAX_HOA_BYTES), profile, path)


def _quote(name: str) -> str:
    return '"' + name.replace("\\", "\\\\").replace('"', '\\"') + '"'


def write_hoa(automaton: Automaton, path: str | Path | None = None, name: str | None = None) -> str:
    """The HOA text of a complete DFA (state-based Buchi marks on accepting states); also written to
    ``path`` if given. Reading it back with either profile gives the same language.
    """
    a = automaton
    index_names = [str(i) for i in range(len(a.aps))]
    lines = ["HOA: v1"]
    if name is not None:
        lines.append(f"name: {_quote(name)}")
    lines += [
        f"States: {a.num_states}",
        f"Start: {a.initial}",
        f"AP: {len(a.aps)}" + "".join(" " + _quote(p) for p in a.aps),
        "acc-name: Buchi",
        "Acceptance: 1 Inf(0)",
        "properties: trans-labels explicit-labels state-acc deterministic complete",
        "--BODY--",
    ]
    for q in range(a.num_states):
        lines.append(f"State: {q}" + (" {0}" if a.accepting[q] else ""))
        row = a.table[q]
        for target in np.unique(row):
            cubes = label_cover(row == target)
            lines.append(f"[{format_cover(cubes, index_names)}] {target}")
    lines.append("--END--")
    text = "\n".join(lines) + "\n"
    if path is not None:
        write_text_atomically(Path(path), text)
    return text
