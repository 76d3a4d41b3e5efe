"""LTLf formula progression: what a formula still asks of a word once a prefix of it has been read.

``progress(f, w)`` is the formula ``psi`` such that, for every **non-empty** word ``u``, the word ``w u``
satisfies ``f`` iff ``u`` satisfies ``psi`` (finite-trace semantics, docs/logic.md). For the minimal DFA
``A`` of ``f``, the DFA of ``psi`` therefore accepts the same non-empty words as ``A`` started in the state
that ``w`` leads to; whether the empty continuation is accepted (the word may end here) is that state's
acceptance, which the automaton tells and ``psi`` does not. This is the residual mission of a robot that
has driven ``w``: it is said back in words and can be joined with an amendment.

One letter ``s`` (the set of propositions true at the cell read) is read by the rules below, applied to the
formula as written (so its structure, and hence its reading aloud, is kept):

=====================  ======================================================
``f``                  ``progress(f, s)``
=====================  ======================================================
``p``                  ``true`` if ``p`` in ``s``, else ``false``
``!g``, ``g & h`` ...  the same connective over the progressed operands
``X g``, weak ``X g``  ``g`` (the continuation is not empty)
``F g``                ``progress(g, s) | F g``
``G g``                ``progress(g, s) & G g``
``g U h``              ``progress(h, s) | (progress(g, s) & g U h)``
``g R h``              ``progress(h, s) & (progress(g, s) | g R h)``
=====================  ======================================================

Constants are folded as they arise. With ``simplify`` (the default), a disjunct that implies another
disjunct and a conjunct implied by another conjunct are then dropped, decided on the operands' automata
(language inclusion over non-empty words, within the ``exclusive`` groups): reading ``enter(a)`` in
``F(enter(a) & F enter(b))`` gives ``F enter(b) | F(enter(a) & F enter(b))``, which simplifies to
``F enter(b)`` ("go to b").
"""

from __future__ import annotations

from collections.abc import Collection, Iterable
from functools import lru_cache

from sgplan.logic.automaton import Automaton
from sgplan.logic.equivalence import included
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
    atoms,
    is_temporal,
)
from sgplan.logic.ltlf import ltlf_to_dfa

Letter = frozenset[str]
"""The propositions true at one cell."""


def progress(
    formula: Formula,
    word: Iterable[Collection[str]],
    *,
    exclusive: Collection[Collection[str]] = (),
    simplify: bool = True,
) -> Formula:
    """The formula the rest of a word must satisfy once ``word`` has been read (see the module).

    Parameters
    ----------
    formula:
        any formula, as written (no normal form needed).
    word:
        the letters read, first first; a letter is the collection of propositions true at that cell
        (names not in the formula are ignored).
    exclusive:
        groups of propositions of which at most one holds at a time (a cell is in one room); used only to
        decide the simplifications, so that "go to b or [go to a, then b]" becomes "go to b".
    simplify:
        drop the operands of ``&`` / ``|`` that another operand makes redundant, and give ``true`` /
        ``false`` for a result that every / no non-empty continuation satisfies. Without it only
        constants are folded.

    Returns
    -------
    Formula
        ``psi`` with: for every non-empty word ``u``, ``word + u`` satisfies ``formula`` iff ``u``
        satisfies ``psi``. ``FALSE`` when no continuation can satisfy ``formula`` any more.

    Cost: one pass over the formula per distinct (sub-formula, letter) pair, memoised; with ``simplify``,
    one small automaton per temporal operand of a junction of the result (a few milliseconds each).

    Example
    -------
    >>> from sgplan.logic import parse_infix, to_infix
    >>> to_infix(progress(parse_infix('F(a & F b) & G !c'), [{"a"}]))
    'F b & G !c'
    """
    result = formula
    for letter in word:
        result = _step(result, frozenset(letter))
    if simplify:
        names = atoms(formula)
        groups = tuple(tuple(p for p in group if p in names) for group in exclusive)
        result = _Simplifier(names, tuple(g for g in groups if len(g) > 1)).formula(result)
    return result


@lru_cache(maxsize=65_536)
def _step(f: Formula, letter: Letter) -> Formula:
    """``progress(f, [letter])`` with constants folded (no simplification)."""
    if isinstance(f, Const):
        return f
    if isinstance(f, Atom):
        return TRUE if f.name in letter else FALSE
    if isinstance(f, Not):
        return negation(_step(f.arg, letter))
    if isinstance(f, And):
        return conjunction(_step(a, letter) for a in f.args)
    if isinstance(f, Or):
        return disjunction(_step(a, letter) for a in f.args)
    if isinstance(f, Implies):
        return _implication(_step(f.left, letter), _step(f.right, letter))
    if isinstance(f, Equiv):
        return _equivalence(_step(f.left, letter), _step(f.right, letter))
    if isinstance(f, (Next, WeakNext)):
        return f.arg
    if isinstance(f, Eventually):
        return disjunction([_step(f.arg, letter), f])
    if isinstance(f, Always):
        return conjunction([_step(f.arg, letter), f])
    if isinstance(f, Until):
        return disjunction([_step(f.right, letter), conjunction([_step(f.left, letter), f])])
    if isinstance(f, Release):
        return conjunction([_step(f.right, letter), disjunction([_step(f.left, letter), f])])
    raise TypeError(f"not a formula node: {f!r}")


# -- folding constructors ------------------------------------------------------------------------------


def negation(f: Formula) -> Formula:
    """``!f``, with constants and double negations folded."""
    if isinstance(f, Const):
        return FALSE if f.value else TRUE
    if isinstance(f, Not):
        return f.arg
    return Not(f)


def _junction(items: Iterable[Formula], kind: type[And] | type[Or]) -> Formula:
    unit, zero = (TRUE, FALSE) if kind is And else (FALSE, TRUE)
    kept: dict[Formula, None] = {}  # in order of first appearance: the reading keeps the mission's order
    for item in items:
        for part in item.args if isinstance(item, kind) else (item,):
            if part == zero or negation(part) in kept:
                return zero
            if part != unit:
                kept.setdefault(part, None)
    parts = tuple(kept)
    if not parts:
        return unit
    return parts[0] if len(parts) == 1 else kind(parts)


def conjunction(items: Iterable[Formula]) -> Formula:
    """The ``&`` of ``items``: flattened, duplicates and ``true`` dropped, ``false`` absorbing."""
    return _junction(items, And)


def disjunction(items: Iterable[Formula]) -> Formula:
    """The ``|`` of ``items``, folded as :func:`conjunction` (``true`` absorbing)."""
    return _junction(items, Or)


def _implication(left: Formula, right: Formula) -> Formula:
    if isinstance(left, Const):
        return right if left.value else TRUE
    if isinstance(right, Const):
        return TRUE if right.value else negation(left)
    return TRUE if left == right else Implies(left, right)


def _equivalence(left: Formula, right: Formula) -> Formula:
    if left == right:
        return TRUE
    for a, b in ((left, right), (right, left)):
        if isinstance(a, Const):
            return b if a.value else negation(b)
    return Equiv(left, right)


# -- simplification --------------------------------------------------------------------------------------


class _Simplifier:
    """Drops redundant operands of junctions with temporal operands, deciding implication on automata
    (memoised per formula)."""

    def __init__(self, aps: tuple[str, ...], exclusive: tuple[tuple[str, ...], ...]) -> None:
        self.aps = aps
        self.exclusive = exclusive
        self.automata: dict[Formula, Automaton] = {}

    def automaton(self, f: Formula) -> Automaton:
        dfa = self.automata.get(f)
        if dfa is None:
            dfa = self.automata[f] = ltlf_to_dfa(f, aps=self.aps, exclusive=self.exclusive)
        return dfa

    def implies(self, f: Formula, g: Formula) -> bool:
        """Whether every non-empty word satisfying ``f`` satisfies ``g``."""
        return f == g or included(self.automaton(f), self.automaton(g))

    def formula(self, f: Formula) -> Formula:
        """``f`` with every junction simplified, bottom up; ``true`` / ``false`` for a valid / empty one."""
        simple = self.node(f)
        if isinstance(simple, Const) or not is_temporal(simple):
            return simple
        if self.empty(simple):
            return FALSE
        # Every non-empty word satisfies it iff none satisfies its negation (the empty word satisfies
        # neither).
        return TRUE if self.empty(negation(simple)) else simple

    def empty(self, f: Formula) -> bool:
        """Whether no word satisfies ``f``."""
        dfa = self.automaton(f)
        return not bool(dfa.live_states()[dfa.initial])

    def node(self, f: Formula) -> Formula:
        if not is_temporal(f) or isinstance(f, Atom):
            return f
        if isinstance(f, (And, Or)):
            parts = [self.node(a) for a in f.args]
            kept = self.irredundant(parts, conjunctive=isinstance(f, And))
            return conjunction(kept) if isinstance(f, And) else disjunction(kept)
        return f

    def irredundant(self, parts: list[Formula], *, conjunctive: bool) -> list[Formula]:
        """``parts`` without those another part makes redundant (the first of equivalent ones stays)."""
        kept: list[Formula] = []
        for part in parts:
            # In a conjunction a part implied by a kept one adds nothing; in a disjunction, a part that
            # implies a kept one.
            if any(self.implies(k, part) if conjunctive else self.implies(part, k) for k in kept):
                continue
            kept = [k for k in kept if not (self.implies(part, k) if conjunctive else self.implies(k, part))]
            kept.append(part)
        return kept
