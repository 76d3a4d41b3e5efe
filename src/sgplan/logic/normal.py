"""Negation normal form and the normalising constructors used to build automata.

``nnf(f)`` pushes negations down to the propositions, removes ``->`` and ``<->``, and builds every
conjunction and disjunction with :func:`mk_and` / :func:`mk_or`, which flatten nested ones, drop
duplicates, sort operands into a fixed order, absorb ``true``/``false`` and detect ``p & !p``. Because of
this normalisation, formula progression (see :mod:`sgplan.logic.ltlf`) reaches only finitely many
distinct formulas.
"""

from __future__ import annotations

from collections.abc import Iterable
from functools import lru_cache

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

_RANK = {Const: 0, Atom: 1, Not: 2, Next: 3, WeakNext: 4, Eventually: 5, Always: 6, Until: 7,
         Release: 8, And: 9, Or: 10, Implies: 11, Equiv: 12}


@lru_cache(maxsize=200_000)
def order_key(formula: Formula) -> tuple:
    """A total, run-independent order on formulas (used to sort operands of ``&`` and ``|``)."""
    if isinstance(formula, Const):
        return (0, formula.value)
    if isinstance(formula, Atom):
        return (1, formula.name)
    return (_RANK[type(formula)], tuple(order_key(c) for c in formula.children()))


def _is_literal_pair(items: set[Formula]) -> bool:
    return any(isinstance(f, Not) and f.arg in items for f in items)


def _junction(items: Iterable[Formula], kind: type[And] | type[Or], unit: Const, zero: Const) -> Formula:
    flat: set[Formula] = set()
    stack = list(items)
    while stack:
        item = stack.pop()
        if item == zero:
            return zero
        if item == unit:
            continue
        if isinstance(item, kind):
            stack.extend(item.args)
        else:
            flat.add(item)
    if not flat:
        return unit
    if _is_literal_pair(flat):
        return zero
    if len(flat) == 1:
        return next(iter(flat))
    return kind(tuple(sorted(flat, key=order_key)))


def mk_and(items: Iterable[Formula]) -> Formula:
    """The normalised conjunction of ``items`` (flattened, sorted, deduplicated, constants absorbed)."""
    return _junction(items, And, TRUE, FALSE)


def mk_or(items: Iterable[Formula]) -> Formula:
    """The normalised disjunction of ``items`` (flattened, sorted, deduplicated, constants absorbed)."""
    return _junction(items, Or, FALSE, TRUE)


def mk_eventually(arg: Formula) -> Formula:
    if isinstance(arg, (Const, Eventually)):
        return arg
    return Eventually(arg)


def mk_always(arg: Formula) -> Formula:
    if isinstance(arg, (Const, Always)):
        return arg
    return Always(arg)


def mk_next(arg: Formula) -> Formula:
    return FALSE if arg == FALSE else Next(arg)


def mk_weak_next(arg: Formula) -> Formula:
    return TRUE if arg == TRUE else WeakNext(arg)


def mk_until(left: Formula, right: Formula) -> Formula:
    if isinstance(right, Const) or left == FALSE:
        return right
    if left == TRUE:
        return mk_eventually(right)
    return Until(left, right)


def mk_release(left: Formula, right: Formula) -> Formula:
    if isinstance(right, Const) or left == TRUE:
        return right
    if left == FALSE:
        return mk_always(right)
    return Release(left, right)


def nnf(formula: Formula) -> Formula:
    """Negation normal form: negations only on propositions, no ``->``/``<->``, normalised junctions.

    The result uses only ``Const``, ``Atom``, ``Not(Atom)``, ``And``, ``Or``, ``Next``, ``WeakNext``,
    ``Eventually``, ``Always``, ``Until`` and ``Release`` and is equivalent to ``formula`` on every
    finite path.
    """
    return _nnf(formula, False)


def _nnf(formula: Formula, negate: bool) -> Formula:
    """``nnf`` of ``formula`` (negated if ``negate``), with an explicit stack: no recursion, so a long
    chain of ``&`` or ``!`` as written by a user cannot overflow the interpreter's stack. Shared
    sub-formulas are normalised once (the memo)."""
    memo: dict[tuple[Formula, bool], Formula] = {}
    stack: list[tuple[Formula, bool]] = [(formula, negate)]
    while stack:
        f, neg = stack[-1]
        if (f, neg) in memo:
            stack.pop()
            continue
        needs = _operands(f, neg)
        missing = [item for item in needs if item not in memo]
        if missing:
            stack.extend(missing)
            continue
        stack.pop()
        memo[(f, neg)] = _combine(f, neg, [memo[item] for item in needs])
    return memo[(formula, negate)]


def _operands(f: Formula, negate: bool) -> list[tuple[Formula, bool]]:
    """The (sub-formula, negated?) pairs whose normal forms :func:`_combine` builds ``f``'s from."""
    if isinstance(f, (Const, Atom)):
        return []
    if isinstance(f, Not):
        return [(f.arg, not negate)]
    if isinstance(f, (And, Or)):
        return [(a, negate) for a in f.args]
    if isinstance(f, Implies):  # a -> b  ==  !a | b
        return [(f.left, not negate), (f.right, negate)]
    if isinstance(f, Equiv):
        return [(f.left, False), (f.right, False), (f.left, True), (f.right, True)]
    if isinstance(f, (Next, WeakNext, Eventually, Always)):
        return [(f.arg, negate)]
    if isinstance(f, (Until, Release)):
        return [(f.left, negate), (f.right, negate)]
    raise TypeError(f"not a formula node: {f!r}")


def _combine(f: Formula, negate: bool, parts: list[Formula]) -> Formula:
    """The normal form of ``f`` (negated if ``negate``) from those of :func:`_operands`, in order."""
    if isinstance(f, Const):
        return Const(f.value != negate)
    if isinstance(f, Atom):
        return Not(f) if negate else f
    if isinstance(f, Not):
        return parts[0]
    if isinstance(f, And):
        return mk_or(parts) if negate else mk_and(parts)
    if isinstance(f, Or):
        return mk_and(parts) if negate else mk_or(parts)
    if isinstance(f, Implies):  # !(a -> b) == a & !b;  a -> b == !a | b
        return mk_and(parts) if negate else mk_or(parts)
    if isinstance(f, Equiv):
        left, right, not_left, not_right = parts
        if not negate:
            return mk_or([mk_and([left, right]), mk_and([not_left, not_right])])
        return mk_or([mk_and([left, not_right]), mk_and([not_left, right])])
    arg = parts[0]
    if isinstance(f, Next):
        # !X f == weak-next !f: at the last cell X f is false, so its negation is true there.
        return mk_weak_next(arg) if negate else mk_next(arg)
    if isinstance(f, WeakNext):
        return mk_next(arg) if negate else mk_weak_next(arg)
    if isinstance(f, Eventually):
        return mk_always(arg) if negate else mk_eventually(arg)
    if isinstance(f, Always):
        return mk_eventually(arg) if negate else mk_always(arg)
    if isinstance(f, Until):
        return mk_release(parts[0], parts[1]) if negate else mk_until(parts[0], parts[1])
    if isinstance(f, Release):
        return mk_until(parts[0], parts[1]) if negate else mk_release(parts[0], parts[1])
    raise TypeError(f"not a formula node: {f!r}")
