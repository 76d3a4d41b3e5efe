"""LTLf -> minimal complete DFA, by formula progression vectorised over labels.

Construction (docs/logic.md has the semantics):

1. The formula is put in negation normal form (:func:`sgplan.logic.normal.nnf`) and split into its
   top-level conjuncts.
2. Each conjunct is turned into a DFA by progression. A state is a pair ``(psi, b)``: ``psi`` is what
   the rest of the word must satisfy if it continues, ``b`` whether the word read so far already
   satisfies the formula if it ends here. Reading label ``a`` in ``(psi, _)`` leads to
   ``(delta(psi, a), lam(psi, a))`` with, for NNF formulas,

   ===================  ==================================  ================
   psi                  delta(psi, a)                       lam(psi, a)
   ===================  ==================================  ================
   p / !p               true or false by ``a``              p in a / not
   f & g, f | g         delta(f) & delta(g), ...            lam(f) and ...
   X f (strong)         f                                   false
   weak X f             f                                   true
   F f                  delta(f) | F f                      lam(f)
   G f                  delta(f) & G f                      lam(f)
   f U g                delta(g) | (delta(f) & f U g)       lam(g)
   f R g                delta(g) & (delta(f) | f R g)       lam(g)
   ===================  ==================================  ================

   ``psi`` is kept as the unique minimal DNF over the formula's literals and temporal sub-formulas
   (see :class:`_Progression`), so finitely many states arise. ``delta``/``lam`` are computed once per
   temporal sub-formula as arrays over the possible labels.
   The initial state is ``(phi, False)``: the empty word satisfies no formula.
3. The conjuncts' minimal DFAs are multiplied pairwise (vectorised) and minimised after each step.

Labels that the ``exclusive`` groups rule out (two propositions of one group true together), and those
``possible`` leaves out, lead to the rejecting sink ``(false, False)``; the DFA is minimal for the
language restricted to possible labels. Steps 2 and 3 work on a compact alphabet, one column per possible
label and one for all the others (:class:`_Alphabet`), and the dense ``2**len(aps)`` table is made once at
the end: a mission over many rooms, of which the robot is in one at a time, stays cheap to build.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from typing import NamedTuple

import numpy as np

from sgplan.errors import AutomatonError, FormulaError
from sgplan.logic.automaton import Automaton
from sgplan.logic.formula import (
    Always,
    And,
    Atom,
    Const,
    Eventually,
    Formula,
    Next,
    Not,
    Or,
    Release,
    Until,
    WeakNext,
    atoms,
    check_nesting,
    to_infix,
)
from sgplan.logic.minimize import Table, minimal_table, product_table
from sgplan.logic.normal import nnf
from sgplan.logic.rows import unique_rows
from sgplan.safeio import quote

DEFAULT_MAX_ENTRIES = 1_000_000
"""Default limit on the builder's work: ``num_states`` x the number of possible labels (plus one column for
all impossible ones); every label is possible unless ``exclusive`` or ``possible`` rule some out."""

MAX_TABLE_ENTRIES = 8_000_000
"""Limit on the automaton's dense table, ``num_states * 2**len(aps)`` entries of 4 bytes (32 MB)."""


def possible_labels(aps: Sequence[str], exclusive: Collection[Collection[str]] = ()) -> np.ndarray:
    """``(2**len(aps),)`` bool: labels with at most one true proposition of each ``exclusive`` group.

    Group members that are not in ``aps`` are ignored.
    """
    labels = np.arange(1 << len(aps), dtype=np.int64)
    ok = np.ones(labels.size, bool)
    index = {name: i for i, name in enumerate(aps)}
    for group in exclusive:
        mask = sum(1 << index[p] for p in set(group) if p in index)
        within = labels & mask
        ok &= (within & (within - 1)) == 0  # at most one bit set
    return ok


Term = frozenset  # of element ids: a conjunction
Dnf = frozenset  # of Terms: a disjunction, kept as an antichain (no term contains another)


class _Progression:
    """Progression over a fixed array of (possible) labels, with memoisation.

    A progression state is a positive Boolean combination of *elements* -- literals and temporal
    sub-formulas (``X``, weak ``X``, ``F``, ``G``, ``U``, ``R`` nodes) of the NNF formula -- kept as its
    unique minimal DNF: a set of terms (sets of element ids) none of which contains another, with
    contradictory terms (``p`` and ``!p``) dropped. Positive Boolean functions have exactly one such form,
    and the elements come from the formula's finite closure, so finitely many states exist.
    """

    def __init__(self, aps: Sequence[str], labels: np.ndarray) -> None:
        self.bit = {name: i for i, name in enumerate(aps)}
        self.labels = labels
        self.elements: list[Formula] = []
        self.element_ids: dict[Formula, int] = {}
        self.complement: dict[int, int] = {}
        self.dnfs: list[Dnf] = []
        self.dnf_ids: dict[Dnf, int] = {}
        self.memo: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # element id -> (delta dnf ids, lam)
        self.state_memo: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # dnf id -> (delta dnf ids, lam)
        self.combined: dict[tuple, int] = {}
        self.false_id = self.intern_dnf(frozenset())
        self.true_id = self.intern_dnf(frozenset([frozenset()]))

    def element(self, f: Formula) -> int:
        eid = self.element_ids.get(f)
        if eid is None:
            eid = self.element_ids[f] = len(self.elements)
            self.elements.append(f)
            if isinstance(f, (Atom, Not)):
                other = self.element_ids.get(f.arg if isinstance(f, Not) else Not(f))
                if other is not None:
                    self.complement[eid], self.complement[other] = other, eid
        return eid

    def intern_dnf(self, dnf: Dnf) -> int:
        did = self.dnf_ids.get(dnf)
        if did is None:
            did = self.dnf_ids[dnf] = len(self.dnfs)
            self.dnfs.append(dnf)
        return did

    def _minimal(self, terms: set[Term]) -> Dnf:
        consistent = [t for t in terms if not any(self.complement.get(e) in t for e in t)]
        consistent.sort(key=len)
        kept: list[Term] = []
        for t in consistent:
            if not any(k <= t for k in kept):
                kept.append(t)
        return frozenset(kept)

    def dnf_and(self, dnfs: list[Dnf]) -> Dnf:
        terms: set[Term] = {frozenset()}
        for dnf in dnfs:
            terms = {a | b for a in terms for b in dnf}
        return self._minimal(terms)

    def dnf_or(self, dnfs: list[Dnf]) -> Dnf:
        return self._minimal(set().union(*dnfs))

    def to_dnf(self, f: Formula) -> Dnf:
        """The DNF of an NNF formula over its elements."""
        if isinstance(f, Const):
            return self.dnfs[self.true_id if f.value else self.false_id]
        if isinstance(f, And):
            return self.dnf_and([self.to_dnf(a) for a in f.args])
        if isinstance(f, Or):
            return self.dnf_or([self.to_dnf(a) for a in f.args])
        return frozenset([frozenset([self.element(f)])])

    def const(self, dnf: Dnf) -> np.ndarray:
        return np.full(self.labels.size, self.intern_dnf(dnf), np.int64)

    def junction(self, conj: bool, parts: list[np.ndarray]) -> np.ndarray:
        """Per label, the id of the ``&`` (``conj``) or ``|`` of the parts' DNFs."""
        if len(parts) == 1:
            return parts[0]
        by_label = np.stack(parts, axis=1)
        first, inverse = unique_rows(by_label)
        out = np.empty(first.size, np.int64)
        for k, label in enumerate(first):
            key = (conj, *by_label[label].tolist())
            did = self.combined.get(key)
            if did is None:
                operands = [self.dnfs[i] for i in key[1:]]
                did = self.intern_dnf(self.dnf_and(operands) if conj else self.dnf_or(operands))
                self.combined[key] = did
            out[k] = did
        return out[inverse]

    def step(self, f: Formula) -> tuple[np.ndarray, np.ndarray]:
        """``(delta DNF ids, lam)`` of an NNF formula for every label."""
        n = self.labels.size
        if isinstance(f, Const):
            return self.const(self.to_dnf(f)), np.full(n, f.value)
        if isinstance(f, (And, Or)):
            steps = [self.step(a) for a in f.args]
            conj = isinstance(f, And)
            lams = np.stack([s[1] for s in steps])
            return self.junction(conj, [s[0] for s in steps]), np.asarray(
                lams.all(0) if conj else lams.any(0)
            )
        eid = self.element(f)
        cached = self.memo.get(eid)
        if cached is not None:
            return cached
        if isinstance(f, (Atom, Not)):
            atom = f if isinstance(f, Atom) else f.arg
            assert isinstance(atom, Atom), "NNF: Not only wraps atoms"
            name = atom.name
            holds = (self.labels >> self.bit[name] & 1).astype(bool)
            if isinstance(f, Not):
                holds = ~holds
            result = np.where(holds, self.true_id, self.false_id), holds
        elif isinstance(f, (Next, WeakNext)):
            result = self.const(self.to_dnf(f.arg)), np.full(n, isinstance(f, WeakNext))
        elif isinstance(f, (Eventually, Always)):
            delta, lam = self.step(f.arg)
            result = self.junction(isinstance(f, Always), [delta, self.const(self.to_dnf(f))]), lam
        elif isinstance(f, (Until, Release)):
            d_left, _ = self.step(f.left)
            d_right, lam = self.step(f.right)
            strong = isinstance(f, Until)
            inner = self.junction(strong, [d_left, self.const(self.to_dnf(f))])
            result = self.junction(not strong, [d_right, inner]), lam
        else:
            raise TypeError(f"not a negation-normal-form node: {f!r}")
        self.memo[eid] = result
        return result

    def step_state(self, did: int) -> tuple[np.ndarray, np.ndarray]:
        """``(delta DNF ids, lam)`` of the state ``dnfs[did]`` for every label."""
        cached = self.state_memo.get(did)
        if cached is None:
            n = self.labels.size
            term_steps = []
            for term in self.dnfs[did]:
                steps = [self.step(self.elements[e]) for e in sorted(term)]
                if not steps:
                    term_steps.append((np.full(n, self.true_id, np.int64), np.ones(n, bool)))
                    continue
                lam = np.logical_and.reduce([s[1] for s in steps])
                term_steps.append((self.junction(True, [s[0] for s in steps]), lam))
            if not term_steps:
                cached = np.full(n, self.false_id, np.int64), np.zeros(n, bool)
            else:
                lam = np.logical_or.reduce([s[1] for s in term_steps])
                cached = self.junction(False, [s[0] for s in term_steps]), lam
            self.state_memo[did] = cached
        return cached


def _too_big(formula: Formula, states: int, num_labels: int, max_entries: int, how: str) -> AutomatonError:
    return AutomatonError(
        f"the automaton of {to_infix(formula)} would need {how} {states:,} states x {num_labels:,} labels "
        f"= {states * num_labels:,} table entries, more than max_entries={max_entries:,}; simplify the "
        f"mission (fewer unordered goals or propositions) or raise max_entries"
    )


def _table_too_big(formula: Formula, states: int, num_labels: int) -> AutomatonError:
    return AutomatonError(
        f"the automaton of {to_infix(formula)} has {states:,} states x {num_labels:,} labels = "
        f"{states * num_labels:,} table entries, more than the {MAX_TABLE_ENTRIES:,} an automaton may hold; "
        f"use fewer propositions (rooms and objects) in the mission"
    )


class _Alphabet(NamedTuple):
    """The columns the builder works on: one per possible label, and one for all the others.

    Columns follow the order of each column's first label, so breadth-first numbering by increasing
    column (:func:`sgplan.logic.minimize.minimal_table`) equals numbering by increasing label.
    """

    label_column: np.ndarray
    """``(num_possible,)`` the column of each possible label (in increasing label order)."""
    other_column: int | None
    """the column of every impossible label, or None when all labels are possible."""
    expand: np.ndarray
    """``(2**len(aps),)`` the column of every label."""

    @property
    def size(self) -> int:
        return int(self.label_column.size) + (self.other_column is not None)


def _alphabet(possible: np.ndarray) -> _Alphabet:
    labels = np.flatnonzero(possible)
    if possible.all():
        return _Alphabet(labels, None, labels)
    first_other = int(np.argmin(possible))
    firsts = np.sort(np.append(labels, first_other))
    every = np.where(possible, np.arange(possible.size), first_other)
    return _Alphabet(np.searchsorted(firsts, labels), int(np.searchsorted(firsts, first_other)),
                     np.searchsorted(firsts, every))


def _conjunct_dfa(
    phi: Formula, prog: _Progression, alphabet: _Alphabet, max_entries: int, original: Formula,
) -> Table:
    state_of: dict[int, int] = {}  # key 2 * formula id + acceptance bit -> state index
    keys: list[int] = []

    def state(key: int) -> int:
        index = state_of.get(key)
        if index is None:
            index = state_of[key] = len(keys)
            keys.append(key)
            if len(keys) * alphabet.size > max_entries:
                raise _too_big(original, len(keys), alphabet.size, max_entries, "more than")
        return index

    state(2 * prog.intern_dnf(prog.to_dnf(phi)))
    rows: list[np.ndarray] = []
    while len(rows) < len(keys):
        delta, lam = prog.step_state(keys[len(rows)] >> 1)
        unique, inverse = np.unique(2 * delta + lam, return_inverse=True)
        row = np.empty(alphabet.size, np.int32)
        row[alphabet.label_column] = np.array([state(int(k)) for k in unique], np.int32)[inverse.ravel()]
        if alphabet.other_column is not None:
            row[alphabet.other_column] = state(2 * prog.false_id)  # the rejecting sink
        rows.append(row)
    accepting = np.array([k & 1 for k in keys], bool)
    return minimal_table(Table(np.stack(rows), 0, accepting))


def _allowed_labels(aps: Sequence[str], exclusive: Collection[Collection[str]],
                    possible: np.ndarray | None) -> np.ndarray:
    """``(2**len(aps),)`` bool: the labels that ``exclusive`` allows and ``possible`` (if given) keeps."""
    allowed = possible_labels(aps, exclusive)
    if possible is not None:
        possible = np.asarray(possible, dtype=bool)
        if possible.shape != allowed.shape:
            raise ValueError(f"possible has shape {possible.shape}, expected {allowed.shape} (2**len(aps))")
        allowed &= possible
    return allowed


def ltlf_to_dfa(
    formula: Formula,
    aps: Sequence[str] | None = None,
    exclusive: Collection[Collection[str]] = (),
    max_entries: int = DEFAULT_MAX_ENTRIES,
    possible: np.ndarray | None = None,
) -> Automaton:
    """The minimal complete DFA accepting exactly the finite words that satisfy ``formula`` (LTLf).

    Parameters
    ----------
    formula:
        any formula; ``X`` is the strong next.
    aps:
        the proposition order of the labels (a superset of the formula's propositions); default: the
        formula's propositions in order of first appearance.
    exclusive:
        groups of propositions of which at most one holds at a time (e.g. all ``enter(room_*)``);
        labels violating a group go to the rejecting sink.
    max_entries:
        refuse (early) automata whose table over the possible labels would exceed ``num_states`` x
        (possible labels + 1) entries (``num_states * 2**len(aps)`` when every label is possible).
    possible:
        ``(2**len(aps),)`` bool, the labels that can occur (e.g. those realizable in a scene); the others
        lead to the rejecting sink, as labels ruled out by ``exclusive`` do. Progression runs over the
        possible labels only, so a small ``possible`` keeps building fast for many propositions.

    Returns
    -------
    Automaton
        minimal, canonical numbering (initial state 0); the empty word is rejected.

    Raises
    ------
    FormulaError
        a proposition of the formula is missing from ``aps``.
    AutomatonError
        the automaton would exceed ``max_entries``, or its dense table :data:`MAX_TABLE_ENTRIES`; the
        message gives the predicted size.

    Example
    -------
    >>> from sgplan.logic import parse_infix
    >>> ltlf_to_dfa(parse_infix("F(p1 & F p2) & G !p3")).num_states
    4
    """
    used = atoms(formula)
    aps = used if aps is None else tuple(aps)
    num_labels = 1 << len(aps)
    if num_labels > MAX_TABLE_ENTRIES:
        raise _table_too_big(formula, 1, num_labels)
    result, alphabet = _compact_table(formula, aps, _allowed_labels(aps, exclusive, possible), max_entries)
    if result.table.shape[0] * num_labels > MAX_TABLE_ENTRIES:
        raise _table_too_big(formula, result.table.shape[0], num_labels)
    return Automaton(tuple(aps), result.table[:, alphabet.expand], result.initial, result.accepting)


class CompactDfa(NamedTuple):
    """A minimal complete DFA over the possible labels only, with no dense ``2**len(aps)`` table: one column
    per possible label and one for all the impossible ones (which lead to the rejecting sink)."""

    aps: tuple[str, ...]
    table: Table
    """``table.table`` is ``(num_states, num_columns)``."""
    column_labels: np.ndarray
    """``(num_columns,)`` int64, a label of each column (the column of the impossible labels: one of them)."""


def ltlf_to_compact_dfa(formula: Formula, aps: Sequence[str], possible: np.ndarray,
                        max_entries: int = DEFAULT_MAX_ENTRIES) -> CompactDfa:
    """The DFA of :func:`ltlf_to_dfa` (``aps`` and ``possible`` as there) over the possible labels' columns
    only: for comparing automata whose dense table would be too large (many propositions of which few
    labels can occur). Two results built with the same ``aps`` and ``possible`` share their columns.

    Raises :class:`FormulaError` / :class:`AutomatonError` as :func:`ltlf_to_dfa` (``max_entries`` only)."""
    allowed = _allowed_labels(tuple(aps), (), possible)
    result, alphabet = _compact_table(formula, tuple(aps), allowed, max_entries)
    columns = np.zeros(alphabet.size, np.int64)
    columns[alphabet.expand] = np.arange(alphabet.expand.size)  # one label per column (any, the last)
    return CompactDfa(tuple(aps), result, columns)


def _compact_table(formula: Formula, aps: tuple[str, ...], allowed: np.ndarray,
                   max_entries: int) -> tuple[Table, _Alphabet]:
    """The minimal DFA of ``formula`` over the columns of ``allowed`` (see the module docstring)."""
    missing = [p for p in atoms(formula) if p not in aps]
    if missing:
        raise FormulaError(
            f"proposition {quote(missing[0])} of the formula is not among the automaton's {quote(list(aps))}"
        )
    # Progression, minimisation and products run over the possible labels (one column each) and one
    # column for all the others (the dense table, when wanted, is made from them once, by ltlf_to_dfa).
    prog = _Progression(aps, np.flatnonzero(allowed))
    alphabet = _alphabet(allowed)
    normal = check_nesting(nnf(formula))  # progression recurses over the normal form
    conjuncts = list(normal.args) if isinstance(normal, And) else [normal]
    if alphabet.size > max_entries:
        raise _too_big(formula, 1, alphabet.size, max_entries, "at least")
    parts = [_conjunct_dfa(c, prog, alphabet, max_entries, formula) for c in conjuncts]
    sizes = [p.table.shape[0] for p in parts]
    result = parts[0]
    for k, part in enumerate(parts[1:], start=1):
        if result.table.shape[0] * sizes[k] * alphabet.size > max_entries:
            predicted = result.table.shape[0] * int(np.prod(sizes[k:], dtype=np.float64))
            raise _too_big(formula, predicted, alphabet.size, max_entries, "up to")
        result = product_table(result, part, np.logical_and)
    return result, alphabet
