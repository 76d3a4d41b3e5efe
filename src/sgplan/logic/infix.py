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

from sgplan.errors import FormulaError
from sgplan.logic.formula import (
    FALSE,
    INFIX_KEYWORDS,
    TRUE,
    Always,
    And,
    Atom,
    Dialect,
    Equiv,
    Eventually,
    Formula,
    Implies,
    Next,
    Not,
    Or,
    WeakNext,
)
from sgplan.logic.prefix import LBT_OPERATORS

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
        elif value in INFIX_KEYWORDS or value == "xor":
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
            before = self.tokens[self.i - 1] if self.i else None
            hint = ""
            if value == "(" and before is not None and before[0] == "atom":
                hint = (f"; a proposition with parentheses goes in double quotes, e.g. "
                        f"\"{before[1]}(...)\"")
            raise FormulaError(f"unexpected {value!r} at character {pos} after a complete formula{hint}", pos)

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
