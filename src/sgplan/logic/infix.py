"""Spot's infix formula syntax: ``F(p1 & F p2) & G !p3``.

Grammar, loosest binding first (as in Spot): ``->``/``=>`` and ``<->``/``<=>`` (right-associative,
one level); ``^``/``xor``; ``|``/``||``; ``&``/``&&``; ``U``, ``R``, ``W``, ``M`` (right-associative);
prefix operators ``!``/``~``, ``X``, ``X[!]``, ``F``/``<>``, ``G``/``[]``. Constants ``true``/``1`` and
``false``/``0``. Propositions are identifiers (``p1``, ``room_2``) or double-quoted strings
(``"enter(room_2)"``). As in Spot, ``GFa`` reads as ``G F a``.

Next: in the default ``"sgplan"`` dialect ``X`` is the strong next (false at the last cell of a path);
Spot's LTLf reads ``X`` as the weak next and writes the strong one ``X[!]``. Choose
``dialect="spot"`` to read or write formulas with Spot's meaning; ``X[!]`` is strong in both dialects.
"""

from __future__ import annotations

import re
from typing import Literal

from sgplan.errors import FormulaError
from sgplan.logic.formula import (
    FALSE,
    TRUE,
    Always,
    And,
    Atom,
    Const,
    Equiv,
    Eventually,
    Formula,
    Implies,
    Next,
    Not,
    Or,
    Release,
    Until,
    WeakNext,
)
from sgplan.logic.prefix import LBT_OPERATORS

Dialect = Literal["sgplan", "spot"]

_LEX = re.compile(
    r"""\s*(?:
      (?P<quoted>"[^"]*")
    | (?P<xs>X\[!\])
    | (?P<sym><->|<=>|->|=>|-->|&&|\|\||<>|\[\]|[!~&|^()])
    | (?P<ident>[A-Za-z_][A-Za-z0-9_.]*)
    | (?P<num>[01](?![0-9]))
    )""",
    re.VERBOSE,
)
_SYMBOL_ALIASES = {"<=>": "<->", "=>": "->", "-->": "->", "&&": "&", "||": "|", "~": "!", "<>": "F",
                   "[]": "G", "xor": "^"}
_KEYWORDS = {"true", "false", "U", "R", "W", "M", "xor", "X", "F", "G"}
_PLAIN_ATOM = re.compile(r"[a-z_][A-Za-z0-9_]*\Z")


def _lex(text: str) -> list[tuple[str, str, int]]:
    """Tokens as (kind, value, character offset); kind is 'op', 'atom', 'const' or 'end'."""
    out: list[tuple[str, str, int]] = []
    pos = 0
    while True:
        while pos < len(text) and text[pos].isspace():
            pos += 1
        if pos == len(text):
            out.append(("end", "", pos))
            return out
        m = _LEX.match(text, pos)
        if m is None or m.end() == pos:
            if text[pos] == '"':
                raise FormulaError(f"the quoted proposition at character {pos} is never closed", pos)
            raise FormulaError(f"unexpected character {text[pos]!r} at character {pos}", pos)
        kind = m.lastgroup
        assert kind is not None, "every alternative of _LEX is a named group"
        start, value = m.start(kind), m.group(kind)
        pos = m.end()
        if kind == "quoted":
            out.append(("atom", value[1:-1], start))
        elif kind == "xs":
            out.append(("op", "X[!]", start))
        elif kind == "num":
            out.append(("const", value, start))
        elif kind == "sym":
            out.append(("op", _SYMBOL_ALIASES.get(value, value), start))
        elif value in ("true", "false"):
            out.append(("const", value, start))
        elif value in _KEYWORDS or value == "xor":
            out.append(("op", _SYMBOL_ALIASES.get(value, value), start))
        else:
            # Spot reads GFa as G F a: peel leading F/G/X letters off an identifier.
            k = 0
            while k < len(value) - 1 and value[k] in "FGX":
                out.append(("op", value[k], start + k))
                k += 1
            out.append(("atom", value[k:], start + k))


class _Parser:
    def __init__(self, text: str, dialect: Dialect) -> None:
        self.tokens = _lex(text)
        self.i = 0
        self.weak_x = dialect == "spot"

    def peek(self) -> tuple[str, str, int]:
        return self.tokens[self.i]

    def take(self) -> tuple[str, str, int]:
        tok = self.tokens[self.i]
        self.i += 1
        return tok

    def expect_end(self) -> None:
        kind, value, pos = self.peek()
        if kind != "end":
            raise FormulaError(f"unexpected {value!r} at character {pos} after a complete formula", pos)

    def binary(self, ops: tuple[str, ...], next_level, right_assoc: bool) -> Formula:
        left = next_level()
        while True:
            kind, value, _ = self.peek()
            if kind != "op" or value not in ops:
                return left
            self.take()
            right = self.binary(ops, next_level, right_assoc) if right_assoc else next_level()
            left = self.build(value, left, right)
            if right_assoc:
                return left

    @staticmethod
    def build(op: str, left: Formula, right: Formula) -> Formula:
        if op == "&":
            return And((left, right))
        if op == "|":
            return Or((left, right))
        if op == "->":
            return Implies(left, right)
        if op == "<->":
            return Equiv(left, right)
        return LBT_OPERATORS[op].build(left, right)  # ^ U R W M

    def implication(self) -> Formula:
        return self.binary(("->", "<->"), self.xor, True)

    def xor(self) -> Formula:
        return self.binary(("^",), self.disjunction, False)

    def disjunction(self) -> Formula:
        return self.binary(("|",), self.conjunction, False)

    def conjunction(self) -> Formula:
        return self.binary(("&",), self.temporal, False)

    def temporal(self) -> Formula:
        return self.binary(("U", "R", "W", "M"), self.unary, True)

    def unary(self) -> Formula:
        kind, value, pos = self.take()
        if kind == "op" and value in ("!", "X", "X[!]", "F", "G"):
            arg = self.unary()
            if value == "!":
                return Not(arg)
            if value == "X":
                return WeakNext(arg) if self.weak_x else Next(arg)
            if value == "X[!]":
                return Next(arg)
            return Eventually(arg) if value == "F" else Always(arg)
        if kind == "atom":
            return Atom(value)
        if kind == "const":
            return TRUE if value in ("true", "1") else FALSE
        if kind == "op" and value == "(":
            inner = self.implication()
            k, v, p = self.take()
            if v != ")" or k != "op":
                what = "the end of the formula" if k == "end" else repr(v)
                raise FormulaError(
                    f"the parenthesis opened at character {pos} is not closed: found {what} at "
                    f"character {p}",
                    p,
                )
            return inner
        if kind == "end":
            if pos == 0:
                raise FormulaError("the formula is empty")
            raise FormulaError(f"the formula ends at character {pos} where an operand is expected", pos)
        raise FormulaError(f"unexpected {value!r} at character {pos} where an operand is expected", pos)


def parse_infix(text: str, dialect: Dialect = "sgplan") -> Formula:
    """Parse Spot's infix syntax, e.g. ``parse_infix("F(p1 & F p2) & G !p3")``.

    Raises
    ------
    FormulaError
        with ``position`` = character offset of the fault.
    """
    parser = _Parser(text, dialect)
    try:
        formula = parser.implication()
    except RecursionError:
        raise FormulaError("the formula nests too deeply to parse") from None
    parser.expect_end()
    return formula


_BINARY_SYMBOL = {Implies: "->", Equiv: "<->", Until: "U", Release: "R", And: "&", Or: "|"}


def _atom_text(name: str) -> str:
    return name if _PLAIN_ATOM.match(name) and name not in _KEYWORDS else f'"{name}"'


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
