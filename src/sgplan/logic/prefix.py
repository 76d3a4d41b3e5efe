"""Prefix (Polish) formula syntax: the shared parsing engine and Spot's LBT-style prefix strings.

LBT / Spot prefix strings look like ``& F & p1 F p2 G ! p3`` (the form of the shipped
``Spot_LTL_formula.txt`` files). Operators: ``!`` not, ``&`` and, ``|`` or, ``i`` implies, ``e`` equiv,
``^`` xor, ``X`` strong next, ``F`` eventually, ``G`` always, ``U`` until, ``R`` release, ``W`` weak
until, ``M`` strong release; constants ``t``/``true`` and ``f``/``false``; propositions are identifiers
(``p1``) or double-quoted strings (``"enter(room_2)"``). ``W``, ``M`` and ``^`` are expanded into the
other operators when parsed.

The engine :func:`parse_prefix_tokens` is shared with the LLM token-list syntax
(:mod:`sgplan.logic.tokens`); it never recurses, so arbitrarily long inputs cannot overflow the stack.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

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


@dataclass(frozen=True)
class Operator:
    """A prefix operator: how many operands it takes and how to build the node from them."""

    arity: int
    build: Callable[..., Formula]


def _weak_until(a: Formula, b: Formula) -> Formula:
    return Or((Until(a, b), Always(a)))


def _strong_release(a: Formula, b: Formula) -> Formula:
    return And((Release(a, b), Eventually(a)))


def _xor(a: Formula, b: Formula) -> Formula:
    return Not(Equiv(a, b))


def _and(a: Formula, b: Formula) -> Formula:
    return And((a, b))


def _or(a: Formula, b: Formula) -> Formula:
    return Or((a, b))


LBT_OPERATORS: dict[str, Operator] = {
    "!": Operator(1, Not), "X": Operator(1, Next), "F": Operator(1, Eventually), "G": Operator(1, Always),
    "&": Operator(2, _and), "|": Operator(2, _or), "i": Operator(2, Implies), "e": Operator(2, Equiv),
    "^": Operator(2, _xor), "U": Operator(2, Until), "R": Operator(2, Release),
    "W": Operator(2, _weak_until), "M": Operator(2, _strong_release),
}
_LBT_CONSTANTS = {"t": TRUE, "true": TRUE, "f": FALSE, "false": FALSE}
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*\Z")
_LBT_TOKEN = re.compile(r'"[^"]*"|\S+')


def parse_prefix_tokens(
    tokens: Sequence[str],
    operators: Mapping[str, Operator],
    leaf: Callable[[int, str], Formula],
    where: Callable[[int], str],
    positions: Sequence[int],
    noun: str,
) -> Formula:
    """Parse a prefix token sequence into one formula.

    Parameters
    ----------
    tokens:
        the tokens, operator names as keys of ``operators``.
    operators:
        operator token -> :class:`Operator`.
    leaf:
        ``leaf(i, token)`` returns the formula of a non-operator token or raises :class:`FormulaError`.
    where:
        ``where(i)`` names token ``i`` in error messages (e.g. ``"token 3 'AND'"``).
    positions:
        ``positions[i]`` is stored as ``FormulaError.position`` for a fault at token ``i``.
    noun:
        what the input is called in messages (``"list"``, ``"formula"``).

    Raises
    ------
    FormulaError
        empty input, an operator short of operands, or tokens left over after a complete formula.
    """
    if not tokens:
        raise FormulaError(f"the {noun} is empty")
    # Each open frame is [token index, operator, operands collected so far].
    stack: list[tuple[int, Operator, list[Formula]]] = []
    for i, token in enumerate(tokens):
        op = operators.get(token)
        if op is not None:
            stack.append((i, op, []))
            continue
        value = leaf(i, token)
        while stack:
            stack[-1][2].append(value)
            j, top, operands = stack[-1]
            if len(operands) < top.arity:
                break
            stack.pop()
            value = top.build(*operands)
        else:
            if i + 1 < len(tokens):
                rest = len(tokens) - i - 1
                raise FormulaError(
                    f"the formula is complete at token {i} but {rest} more "
                    f"{'tokens follow' if rest > 1 else 'token follows'}, "
                    f"starting with {where(i + 1)}; combine the parts with an operator such as AND",
                    positions[i + 1],
                )
            return value
    j, top, operands = stack[-1]
    raise FormulaError(
        f"{where(j)} needs {top.arity} operand{'s' * (top.arity > 1)} but the {noun} ends after "
        f"{len(operands)}",
        positions[j],
    )


def parse_prefix(text: str) -> Formula:
    """Parse an LBT / Spot prefix string such as ``"& F p1 G ! p2"``.

    Raises
    ------
    FormulaError
        with ``position`` = character offset of the faulty token (or of the end of the text).
    """
    matches = list(_LBT_TOKEN.finditer(text))
    tokens = [m.group() for m in matches]
    positions = [m.start() for m in matches] + [len(text)]

    def where(i: int) -> str:
        return f"token {i} {tokens[i]!r} (character {positions[i]})"

    def leaf(i: int, token: str) -> Formula:
        if token in _LBT_CONSTANTS:
            return _LBT_CONSTANTS[token]
        if token.startswith('"'):
            if len(token) < 2 or not token.endswith('"'):
                raise FormulaError(
                    f"{where(i)} opens a quoted proposition that is never closed", positions[i]
                )
            return Atom(token[1:-1])
        if _IDENTIFIER.match(token):
            return Atom(token)
        raise FormulaError(
            f"{where(i)} is neither an operator ({' '.join(LBT_OPERATORS)}) nor a proposition name",
            positions[i],
        )

    return parse_prefix_tokens(tokens, LBT_OPERATORS, leaf, where, positions, "formula")


_LBT_SYMBOL: dict[type, str] = {
    Not: "!", Next: "X", Eventually: "F", Always: "G", Implies: "i", Equiv: "e", Until: "U",
    Release: "R", And: "&", Or: "|",
}


def _lbt_atom(name: str) -> str:
    if _IDENTIFIER.match(name) and name not in _LBT_CONSTANTS and name not in LBT_OPERATORS:
        return name
    return f'"{name}"'


def to_prefix(formula: Formula) -> str:
    """The LBT / Spot prefix string of ``formula`` (n-ary ``&``/``|`` become left-nested binary ones).

    Weak next is written ``! X !`` (LBT has no weak next). Note that Spot's ``from_ltlf`` reads ``X`` as
    weak next; in sgplan ``X`` is strong (docs/logic.md).
    """
    out: list[str] = []
    stack: list[Formula] = [formula]
    while stack:
        f = stack.pop()
        if isinstance(f, Const):
            out.append("t" if f.value else "f")
        elif isinstance(f, Atom):
            out.append(_lbt_atom(f.name))
        elif isinstance(f, WeakNext):
            out.extend(["!", "X", "!"])
            stack.append(f.arg)
        elif isinstance(f, (And, Or)):
            out.extend([_LBT_SYMBOL[type(f)]] * (len(f.args) - 1))
            stack.extend(reversed(f.args))
        else:
            out.append(_LBT_SYMBOL[type(f)])
            stack.extend(reversed(f.children()))
    return " ".join(out)
