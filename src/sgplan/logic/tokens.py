"""The LLM's prefix token-list syntax, e.g. ``['AND', 'EVENTUALLY', 'enter(room_2)', 'ALWAYS', ...]``.

Operators (upper case; lower case is accepted too): ``NOT``/``NEGATION``, ``NEXT`` (strong next),
``EVENTUALLY``, ``ALWAYS`` take one operand; ``AND``, ``OR``, ``IMPLY``, ``EQUAL``, ``UNTIL`` take two.
Every other token must be an action: ``enter(room_<uuid>)`` or ``reach(object_<uuid>)``.

Actions become propositions either named by the canonical token itself (``"enter(room_2)"``, the
default) or through a mapping such as the authors' ``ap_dict.txt`` (``{'enter(room_2)': 'p1', ...}``,
see :func:`number_aps`). Error messages are one sentence naming the token index (0-based) and text;
they are written to be sent back to the LLM for repair.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Collection, Mapping, Sequence

from sgplan.errors import FormulaError
from sgplan.logic.formula import (
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
from sgplan.logic.prefix import Operator, parse_prefix_tokens
from sgplan.safeio import quote

TOKEN_OPERATORS: dict[str, Operator] = {
    "NOT": Operator(1, Not), "NEGATION": Operator(1, Not), "NEXT": Operator(1, Next),
    "EVENTUALLY": Operator(1, Eventually), "ALWAYS": Operator(1, Always),
    "AND": Operator(2, lambda a, b: And((a, b))), "OR": Operator(2, lambda a, b: Or((a, b))),
    "IMPLY": Operator(2, Implies), "EQUAL": Operator(2, Equiv), "UNTIL": Operator(2, Until),
}
_ACTION = re.compile(r"\s*(enter|reach)\s*\(\s*((room|object)_(\d+))\s*\)\s*\Z")
_ENTITY_OF_ACTION = {"enter": "room", "reach": "object"}


def action_entity(token: str) -> str | None:
    """The entity key (``"room_2"``, ``"object_27"``) of a well-formed action token, else ``None``."""
    m = _ACTION.match(token)
    if m is None or _ENTITY_OF_ACTION[m.group(1)] != m.group(3):
        return None
    return m.group(2)


def canonical_action(token: str) -> str | None:
    """``"enter( room_2 )"`` -> ``"enter(room_2)"``; ``None`` if ``token`` is not a well-formed action."""
    m = _ACTION.match(token)
    if m is None or _ENTITY_OF_ACTION[m.group(1)] != m.group(3):
        return None
    return f"{m.group(1)}({m.group(2)})"


MAX_TOKENS = 100_000
"""Tokens a formula's list may have (missions have tens); the parser itself never recurses."""


def as_token_list(tokens: Sequence[str] | str) -> list[str]:
    """The token list itself, or the list parsed from its Python repr (as in GPT_LTL_formula.txt).

    Raises
    ------
    FormulaError
        the text is not a Python list literal, an element is not a string, or the list is longer than
        :data:`MAX_TOKENS`.
    """
    if isinstance(tokens, str):
        text = tokens.strip()
        if len(text) > 32 * MAX_TOKENS:
            raise FormulaError(
                f"the formula text is {len(text):,} characters long; sgplan reads token lists of "
                f"at most {MAX_TOKENS:,} tokens"
            )
        try:
            value = ast.literal_eval(text)
        except (ValueError, SyntaxError, TypeError, MemoryError, RecursionError) as exc:
            detail = f" ({exc.msg} at character {exc.offset})" if isinstance(exc, SyntaxError) else ""
            raise FormulaError(
                "the formula is not a Python list of quoted tokens like "
                f"['AND', 'enter(room_2)', ...]{detail}"
            ) from None
        if not isinstance(value, (list, tuple)):
            raise FormulaError(f"the formula must be a list of tokens, got a {type(value).__name__}")
        tokens = value
    if len(tokens) > MAX_TOKENS:
        raise FormulaError(f"the formula has {len(tokens):,} tokens; sgplan reads at most {MAX_TOKENS:,}")
    result = []
    for i, token in enumerate(tokens):
        if not isinstance(token, str):
            kind = type(token).__name__
            article = "an" if kind[0] in "aeiou" else "a"
            raise FormulaError(f"token {i} is {quote(token)} ({article} {kind}), not a string", i)
        result.append(token)
    return result


def number_aps(tokens: Sequence[str] | str) -> dict[str, str]:
    """The authors' proposition names: action token -> ``p1``, ``p2``, ... by first appearance.

    This reproduces ``ap_dict.txt`` of the shipped missions (keys are canonical action tokens).
    Tokens that are not actions are skipped; use :func:`parse_tokens` to validate the list.
    """
    names: dict[str, str] = {}
    for token in as_token_list(tokens):
        action = canonical_action(token)
        if action is not None and action not in names:
            names[action] = f"p{len(names) + 1}"
    return names


def parse_tokens(
    tokens: Sequence[str] | str,
    known: Collection[str] | None = None,
    ap_names: Mapping[str, str] | None = None,
) -> Formula:
    """Parse an LLM prefix token list into a formula.

    Parameters
    ----------
    tokens:
        the list, or its Python repr (``"['AND', 'EVENTUALLY', ...]"``).
    known:
        optional entity keys present in the scene (``{"room_2", "object_27"}``); an action naming any
        other entity is an error.
    ap_names:
        optional action token -> proposition name (e.g. ``number_aps(tokens)`` or the authors'
        ap_dict); by default a proposition is named by its canonical action token.

    Raises
    ------
    FormulaError
        empty list, unknown operator, malformed action, unknown entity, an operator short of operands,
        or tokens left over; ``position`` is the 0-based token index.

    Example
    -------
    >>> str(parse_tokens(['AND', 'EVENTUALLY', 'enter(room_2)', 'ALWAYS', 'NOT', 'reach(object_3)']))
    'F "enter(room_2)" & G !"reach(object_3)"'
    """
    items = as_token_list(tokens)
    known_set = None if known is None else set(known)
    spelled = {t: TOKEN_OPERATORS.get(t.strip().upper()) for t in items}
    operators = {t: op for t, op in spelled.items() if op is not None}

    def where(i: int) -> str:
        return f"token {i} {items[i]!r}"

    def leaf(i: int, token: str) -> Formula:
        action = canonical_action(token)
        if action is None:
            m = _ACTION.match(token)
            if m is not None:
                raise FormulaError(
                    f"{where(i)} is malformed: enter takes a room_<id> and reach takes an object_<id>", i
                )
            raise FormulaError(
                f"{where(i)} is not an operator ({', '.join(TOKEN_OPERATORS)}) nor an action "
                f"enter(room_<id>) / reach(object_<id>)",
                i,
            )
        entity = action_entity(action)
        if known_set is not None and entity not in known_set:
            raise FormulaError(f"{where(i)} names {entity}, which is not a known room or object id", i)
        if ap_names is None:
            return Atom(action)
        if action not in ap_names:
            raise FormulaError(f"{where(i)} has no proposition name in the given AP mapping", i)
        return Atom(ap_names[action])

    return parse_prefix_tokens(items, operators, leaf, where, list(range(len(items))), "list")


_TOKEN_OF: dict[type, str] = {
    Not: "NOT", Next: "NEXT", Eventually: "EVENTUALLY", Always: "ALWAYS", Implies: "IMPLY",
    Equiv: "EQUAL", Until: "UNTIL", And: "AND", Or: "OR",
}


def to_tokens(formula: Formula, ap_tokens: Mapping[str, str] | None = None) -> list[str]:
    """The LLM prefix token list of ``formula``.

    ``ap_tokens`` maps proposition names to action tokens (e.g. ``{"p1": "enter(room_2)"}``); without it
    every proposition name must itself be an action token. ``R`` and weak next, which have no token,
    are written with ``NOT``/``UNTIL``/``NEXT`` (``a R b`` = ``!(!a U !b)``).

    Raises
    ------
    FormulaError
        a constant ``true``/``false`` (no token exists) or a proposition without an action token.
    """
    out: list[str] = []
    stack: list[Formula] = [formula]
    while stack:
        f = stack.pop()
        if isinstance(f, Const):
            raise FormulaError(f"the token syntax has no constant {str(f.value).lower()}; simplify it away")
        if isinstance(f, Atom):
            token = ap_tokens.get(f.name) if ap_tokens is not None else f.name
            if token is None or canonical_action(token) is None:
                raise FormulaError(
                    f"proposition {f.name!r} has no action token enter(room_<id>)/reach(object_<id>)"
                )
            out.append(token)
        elif isinstance(f, WeakNext):
            stack.append(Not(Next(Not(f.arg))))
        elif isinstance(f, Release):
            stack.append(Not(Until(Not(f.left), Not(f.right))))
        elif isinstance(f, (And, Or)):
            out.extend([_TOKEN_OF[type(f)]] * (len(f.args) - 1))
            stack.extend(reversed(f.args))
        else:
            out.append(_TOKEN_OF[type(f)])
            stack.extend(reversed(f.children()))
    return out
