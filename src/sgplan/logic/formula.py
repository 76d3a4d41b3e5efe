"""The LTL formula syntax tree: immutable, hashable values.

Nodes are frozen dataclasses, so two formulas built the same way are equal and hash alike, and
formulas can be dictionary keys (the LTLf -> DFA construction relies on that). The tree keeps the
structure it was written with (``a & (b & c)`` stays nested); :mod:`sgplan.logic.normal` builds the
flattened negation normal form used for automata.

Semantics (finite traces, see docs/logic.md): ``Next`` is the *strong* next (false at the last cell of a
path); ``WeakNext`` is its dual (true at the last cell) and appears mainly as the negation-normal form of
``!X``. ``Eventually``/``Always``/``Until``/``Release`` are the usual finite-trace operators.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Literal

from sgplan.errors import FormulaError


class Formula:
    """Base class of every formula node. Supports ``~f``, ``f & g``, ``f | g`` as shorthands."""

    __slots__ = ()

    def children(self) -> tuple[Formula, ...]:
        """The direct sub-formulas, left to right."""
        return ()

    def __invert__(self) -> Formula:
        return Not(self)

    def __and__(self, other: Formula) -> Formula:
        return And((self, other))

    def __or__(self, other: Formula) -> Formula:
        return Or((self, other))

    def __str__(self) -> str:
        return to_infix(self)


def _cached_hash(node: object, *parts: object) -> None:
    # Formulas are hashed over and over while building automata; hashing a deep tree each time would
    # make that quadratic, so every node stores its hash once.
    object.__setattr__(node, "_hash", hash((type(node).__name__, *parts)))


@dataclass(frozen=True, eq=True)
class Const(Formula):
    """``true`` or ``false``."""

    value: bool
    _hash: int = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        _cached_hash(self, self.value)

    def __hash__(self) -> int:
        return self._hash


TRUE = Const(True)
FALSE = Const(False)


@dataclass(frozen=True, eq=True)
class Atom(Formula):
    """An atomic proposition, e.g. ``p1`` or ``enter(room_2)``."""

    name: str
    _hash: int = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        _cached_hash(self, self.name)

    def __hash__(self) -> int:
        return self._hash


@dataclass(frozen=True, eq=True)
class _Unary(Formula):
    arg: Formula
    _hash: int = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        _cached_hash(self, self.arg._hash)  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return self._hash

    def children(self) -> tuple[Formula, ...]:
        return (self.arg,)


@dataclass(frozen=True, eq=True)
class _Binary(Formula):
    left: Formula
    right: Formula
    _hash: int = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        _cached_hash(self, self.left._hash, self.right._hash)  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return self._hash

    def children(self) -> tuple[Formula, ...]:
        return (self.left, self.right)


@dataclass(frozen=True, eq=True)
class _Nary(Formula):
    args: tuple[Formula, ...]
    _hash: int = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if len(self.args) < 2:
            raise ValueError(f"{type(self).__name__} needs at least 2 operands, got {len(self.args)}")
        _cached_hash(self, tuple(a._hash for a in self.args))  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return self._hash

    def children(self) -> tuple[Formula, ...]:
        return self.args


class Not(_Unary):
    """Negation ``!f``."""


class Next(_Unary):
    """Strong next ``X f``: there is a next cell and ``f`` holds from it (false at the last cell)."""


class WeakNext(_Unary):
    """Weak next: if there is a next cell, ``f`` holds from it (true at the last cell); ``!X!f``."""


class Eventually(_Unary):
    """``F f``: ``f`` holds at some cell from now on (now included)."""


class Always(_Unary):
    """``G f``: ``f`` holds at every cell from now on, up to the end of the path."""


class Implies(_Binary):
    """``f -> g``."""


class Equiv(_Binary):
    """``f <-> g``."""


class Until(_Binary):
    """``f U g``: ``g`` holds at some cell from now on, and ``f`` at every cell before it."""


class Release(_Binary):
    """``f R g``: ``g`` holds up to and including the first cell where ``f`` holds, or to the end."""


class And(_Nary):
    """Conjunction of two or more formulas."""


class Or(_Nary):
    """Disjunction of two or more formulas."""


TEMPORAL = (Next, WeakNext, Eventually, Always, Until, Release)


def walk(formula: Formula) -> Iterator[Formula]:
    """Every node of ``formula`` in pre-order (root first, children left to right)."""
    stack = [formula]
    while stack:
        node = stack.pop()
        yield node
        stack.extend(reversed(node.children()))


def atoms(formula: Formula) -> tuple[str, ...]:
    """Proposition names in order of first appearance (pre-order), without repetition."""
    seen: dict[str, None] = {}
    for node in walk(formula):
        if isinstance(node, Atom):
            seen.setdefault(node.name, None)
    return tuple(seen)


def conjuncts(formula: Formula) -> list[Formula]:
    """The conjuncts of ``formula``, nested ``And`` flattened, in order (iterative: any depth); ``[formula]``
    when it is no conjunction."""
    parts: list[Formula] = []
    stack = [formula]
    while stack:
        node = stack.pop()
        if isinstance(node, And):
            stack.extend(reversed(node.args))
        else:
            parts.append(node)
    return parts


def is_temporal(formula: Formula) -> bool:
    """Whether ``formula`` contains a temporal operator (X, weak X, F, G, U, R) anywhere."""
    return any(isinstance(node, TEMPORAL) for node in walk(formula))


def size(formula: Formula) -> int:
    """Number of nodes."""
    return sum(1 for _ in walk(formula))


def depth(formula: Formula) -> int:
    """The nesting depth of ``formula`` as written, every operator counting (iterative: safe at any depth).

    Code that recurses over a formula as written (not its normal form, see :func:`nesting`) checks it
    against :data:`MAX_NESTING` first.
    """
    deepest, stack = 0, [(formula, 1)]
    while stack:
        node, level = stack.pop()
        deepest = max(deepest, level)
        stack.extend((child, level + 1) for child in node.children())
    return deepest


MAX_NESTING = 100
"""Operator nesting the negation normal form of a formula may have for an automaton to be built from it
(see :func:`nesting`); missions nest fewer than 10 levels.

Automaton construction recurses over the normal form, so its depth must be bounded for the
interpreter's stack. The normal form cancels chains of negations, and chains of one junction
(``a & b & c ...``) count as one level, so a conjunction of any length and a chain of NOTs of any
length are accepted."""


def nesting(formula: Formula) -> int:
    """The operator nesting depth of ``formula``, a chain of one junction (``&`` in ``&``) counting once.

    Iterative, so it is safe on formulas of any depth.
    """
    deepest = 0
    stack: list[tuple[Formula, int]] = [(formula, 1)]
    while stack:
        node, depth = stack.pop()
        deepest = max(deepest, depth)
        for child in node.children():
            same_junction = isinstance(node, (And, Or)) and type(child) is type(node)
            stack.append((child, depth if same_junction else depth + 1))
    return deepest


def check_nesting(formula: Formula) -> Formula:
    """``formula`` itself if it nests at most :data:`MAX_NESTING` levels deep (see :func:`nesting`).

    Raises
    ------
    FormulaError
        the formula nests deeper (e.g. a chain of a thousand NOT tokens).
    """
    depth = nesting(formula)
    if depth > MAX_NESTING:
        raise FormulaError(
            f"the formula nests temporal and boolean operators {depth} levels deep (after pushing negations "
            f"in); sgplan builds automata for at most {MAX_NESTING} levels"
        )
    return formula


def rename_atoms(formula: Formula, names: dict[str, str]) -> Formula:
    """``formula`` with each atom named in ``names`` renamed (e.g. ``p1`` -> ``enter(room_2)``), its
    structure kept; atoms not in ``names`` stay."""
    if isinstance(formula, Atom):
        return Atom(names.get(formula.name, formula.name))
    if isinstance(formula, _Unary):
        return type(formula)(rename_atoms(formula.arg, names))
    if isinstance(formula, _Binary):
        return type(formula)(rename_atoms(formula.left, names), rename_atoms(formula.right, names))
    if isinstance(formula, _Nary):
        return type(formula)(tuple(rename_atoms(arg, names) for arg in formula.args))
    return formula


# Writing a formula as infix text lives with the tree (``str(formula)`` uses it); reading it back is
# :mod:`sgplan.logic.infix`, which shares these two tables.
Dialect = Literal["sgplan", "spot"]
INFIX_KEYWORDS = frozenset({"true", "false", "U", "R", "W", "M", "xor", "X", "F", "G"})
"""Words of the infix syntax that a proposition's name must not be (such a name is written quoted)."""
PLAIN_ATOM = re.compile(r"[a-z_][A-Za-z0-9_]*\Z")
"""A proposition's name that infix text writes without quotes."""

_BINARY_SYMBOL = {Implies: "->", Equiv: "<->", Until: "U", Release: "R", And: "&", Or: "|"}


def _atom_text(name: str) -> str:
    return name if PLAIN_ATOM.match(name) and name not in INFIX_KEYWORDS else f'"{name}"'


def to_infix(formula: Formula, dialect: Dialect = "sgplan") -> str:
    """Spot-style infix text; every binary sub-formula of a binary operator is parenthesised.

    ``parse_infix(to_infix(f, d), d) == f`` whenever every ``&``/``|`` of ``f`` has two operands (as the
    parsers produce them); n-ary ones print flat and read back left-nested.
    """
    strong, weak = ("X[!]", "X") if dialect == "spot" else ("X", None)
    symbols: dict[type, str | None] = {Not: "!", Next: strong, WeakNext: weak, Eventually: "F", Always: "G"}

    def unfold(f: Formula) -> Formula:
        # Without a weak-next symbol, weak next is written !X!f.
        return Not(Next(Not(f.arg))) if isinstance(f, WeakNext) and weak is None else f

    def leaf(f: Formula) -> str:
        if isinstance(f, Const):
            return "true" if f.value else "false"
        return _atom_text(f.name)  # type: ignore[attr-defined]

    root = unfold(formula)
    if isinstance(root, (Const, Atom)):
        return leaf(root)
    # Depth-first with an explicit stack (a formula from a file may nest deeper than Python recurses).
    # A frame is (node, its children, the texts of the children written so far).
    frames: list[tuple[Formula, list[Formula], list[str]]] = [
        (root, [unfold(c) for c in root.children()], [])
    ]
    while True:
        node, children, done = frames[-1]
        if len(done) < len(children):
            child = children[len(done)]
            if isinstance(child, (Const, Atom)):
                done.append(leaf(child))
            else:
                frames.append((child, [unfold(c) for c in child.children()], []))
            continue
        frames.pop()
        text = _node_text(node, children, done, symbols)
        if not frames:
            return text
        frames[-1][2].append(text)


_BINARY_NODES = (And, Or, Implies, Equiv, Until, Release)


def _node_text(
    node: Formula, children: list[Formula], texts: list[str], symbols: dict[type, str | None]
) -> str:
    """The infix text of an operator node from its children's texts (a binary child is parenthesised)."""
    if isinstance(node, (Not, Next, WeakNext, Eventually, Always)):
        symbol, inner = symbols[type(node)], texts[0]
        if isinstance(children[0], _BINARY_NODES):
            return f"{symbol}({inner})"
        return f"{symbol}{inner}" if symbol == "!" else f"{symbol} {inner}"
    parts = [
        f"({text})" if isinstance(child, _BINARY_NODES) else text for child, text in zip(children, texts)
    ]
    return f" {_BINARY_SYMBOL[type(node)]} ".join(parts)
