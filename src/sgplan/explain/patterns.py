"""Reading a formula's structure aloud: sequences, choices, goals, avoidance, until, conditions.

:func:`pattern_clauses` turns a formula into one English clause per top-level conjunct, or returns
``None`` when some part has no pattern here (then the caller explains the automaton instead). Each
clause is an imperative sentence that names every proposition it covers through its :class:`Referent`.

Readings (finite paths; "moment" = a cell of the path; the first cell is the start):

==========================  ======================================================================
formula                     clause
==========================  ======================================================================
``s`` (no temporal op)      start <s>  (it is read at the first cell only)
``F s``                     go to / reach <s>; ``F !a``: be outside / out of reach of a
``F(A | B)``                do one of: [F A] or [F B]
``F(s & F t)``              go to <s>, then go to <t>           (``then``: at that moment or later)
``F(s & psi)``              go to <s>, and from that moment on <psi>
``G !a``, ``G(!a & !b)``    never enter a or b / never come within reach of ...
``G s``                     at every moment be <s>
``G(s -> F t)``             whenever you are <s>, go to <t> then or afterwards
``G(s -> psi)``             whenever you are <s>, from that moment on <psi>
``s U t``                   go to <t>, being <s> at every moment before that
``!a & !(o & r) U t``       go to <t>, without entering a or coming within reach of o before that
``A -> B``                  if <A>, then <B>            (A a condition: start / ever / always)
``A <-> B``                 make sure that <A> exactly when <B>
``A | B``                   do one of: [A] or [B]
``A & B`` (nested)          do both: [A] and [B]
==========================  ======================================================================

A state condition ``s`` (no temporal operator) reads "in the kitchen (room_11, floor 0)", "within reach
of the sink (...)", "not in ...", joined by "and" / "or"; a compound part inside another is put in
square brackets so that the reading is never ambiguous. ``X``, weak ``X``, ``R`` and ``G`` over
temporal formulas (other than the response shape) have no pattern.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from sgplan.explain.referents import Referent, group_phrase
from sgplan.logic.formula import (
    Always,
    And,
    Atom,
    Const,
    Equiv,
    Eventually,
    Formula,
    Implies,
    Not,
    Or,
    Until,
    conjuncts,
    is_temporal,
)

Describe = Callable[[str], Referent]


class _NoPattern(Exception):
    """Some part of the formula has no direct reading; the automaton explains it instead."""


def pattern_clauses(formula: Formula, describe: Describe) -> list[str] | None:
    """One clause per top-level conjunct of ``formula`` (capitalised, ending with "."), or ``None``.

    ``describe`` maps a proposition name to its :class:`Referent`.
    """
    reader = _Reader(describe)
    try:
        return [_sentence(clause) for clause in _clauses(reader, conjuncts(_simplify(formula)))]
    except _NoPattern:
        return None


def _clauses(reader: _Reader, parts: list[Formula]) -> list[str]:
    """One clause per part, but goals that share what must follow them (``F(a & F c) & F(b & F c)``:
    *a and b, in any order, then c*) as one clause where the first of them stands."""
    thens = [_goal_then(part) for part in parts]
    shared: dict[Formula, list[Formula]] = {}
    for then in thens:
        if then is not None:
            shared.setdefault(then[1], []).append(then[0])
    out, said = [], set()
    for part, then in zip(parts, thens):
        if then is None or len(shared[then[1]]) < 2:
            out.append(reader.clause(part))
        elif then[1] not in said:
            said.add(then[1])
            goals = " and ".join(reader.goal(goal) for goal in shared[then[1]])
            out.append(f"{goals}, in any order, then {reader.eventually(then[1])}")
    return out


def _goal_then(part: Formula) -> tuple[Formula, Formula] | None:
    """``(s, c)`` for ``F(s & F c)`` with ``s`` a state condition, else ``None``."""
    if not isinstance(part, Eventually) or not isinstance(part.arg, And):
        return None
    here = [p for p in conjuncts(part.arg) if not is_temporal(p)]
    later = [p for p in conjuncts(part.arg) if is_temporal(p)]
    if not here or len(later) != 1 or not isinstance(later[0], Eventually):
        return None
    return (here[0] if len(here) == 1 else And(tuple(here))), later[0].arg


def condition_text(formula: Formula, describe: Describe) -> str:
    """A state condition (no temporal operator) as a phrase: ``in the kitchen (...) and not within
    reach of the sink (...)``."""
    return _Reader(describe).cond(formula)


def _sentence(text: str) -> str:
    return text[:1].upper() + text[1:] + "."


def _disjuncts(formula: Formula) -> list[Formula]:
    if isinstance(formula, Or):
        return [d for arg in formula.args for d in _disjuncts(arg)]
    return [formula]


def _simplify(formula: Formula) -> Formula:
    """Equivalent formula with negations pushed through ``!``, ``F`` and ``G`` (``!F a`` = ``G !a``),
    and through ``&`` / ``|`` of state conditions, so that avoidance reads as avoidance."""
    if isinstance(formula, Not):
        arg = formula.arg
        if isinstance(arg, Not):
            return _simplify(arg.arg)
        if isinstance(arg, Eventually):
            return Always(_simplify(Not(arg.arg)))
        if isinstance(arg, Always):
            return Eventually(_simplify(Not(arg.arg)))
        return Not(_simplify(arg))
    if isinstance(formula, (Eventually, Always)):
        return type(formula)(_simplify(formula.arg))
    if isinstance(formula, (And, Or)):
        return type(formula)(tuple(_simplify(a) for a in formula.args))
    if isinstance(formula, (Implies, Equiv, Until)):
        return type(formula)(_simplify(formula.left), _simplify(formula.right))
    return formula


def _is_literal(f: Formula) -> bool:
    return isinstance(f, Atom) or (isinstance(f, Not) and isinstance(f.arg, Atom))


def _factored(s: Formula) -> list[Formula] | None:
    """``s`` as a list of conjoined literals and choices among atoms, or ``None``.

    A disjunction of conjunctions that share all literals but one atom each is factored:
    ``(a & r) | (b & r)`` -> ``[a | b, r]`` (two chairs of one room).
    """
    if isinstance(s, Or):
        options = [conjuncts(d) for d in _disjuncts(s)]
        if not all(all(_is_literal(x) for x in o) for o in options):
            return None
        common = [x for x in options[0] if all(x in o for o in options[1:])]
        rest = [[x for x in o if x not in common] for o in options]
        if not all(len(r) == 1 and isinstance(r[0], Atom) for r in rest) or len({r[0] for r in rest}) < len(
            rest
        ):
            return None
        return [Or(tuple(r[0] for r in rest)), *common]
    items = conjuncts(s)
    ok = all(_is_literal(x) or (isinstance(x, Or) and all(isinstance(d, Atom) for d in _disjuncts(x)))
             for x in items)
    return items if ok and len(items) > 1 else None


class _Reader:
    def __init__(self, describe: Describe) -> None:
        self.describe = describe

    # -- state conditions (no temporal operator) ---------------------------------------------------
    def entity(self, atom: Atom) -> Referent:
        return self.describe(atom.name)

    def at(self, atom: Atom) -> str:
        """``in the kitchen (...)`` / ``within reach of the sink (...)``."""
        e = self.entity(atom)
        return f"{'within reach of' if e.kind == 'object' else 'in'} {e.phrase()}"

    def _same_kind_atoms(self, f: Formula) -> list[Referent] | None:
        """The entities of a disjunction of two or more atoms of one kind, else ``None``."""
        items = _disjuncts(f)
        if len(items) < 2 or not all(isinstance(i, Atom) for i in items):
            return None
        entities = [self.entity(i) for i in items]  # type: ignore[arg-type]
        kinds = {e.kind for e in entities}
        return entities if len(kinds) == 1 and len({e.key for e in entities}) == len(entities) else None

    def choice(self, entities: Sequence[Referent]) -> str:
        """Alternatives grouped by category, in order of first appearance of each category."""
        groups: dict[tuple[str, str | None], list[Referent]] = {}
        for e in entities:
            groups.setdefault((e.kind, e.category if e.kind != "unknown" else e.key), []).append(e)
        return " or ".join(group_phrase(g) for g in groups.values())

    def cond(self, f: Formula) -> str:
        """The state condition ``f`` as an adjective phrase (``in X and not within reach of Y``)."""
        if isinstance(f, Const):
            return "anywhere" if f.value else "nowhere (impossible)"
        if isinstance(f, Atom):
            return self.at(f)
        if isinstance(f, Not):
            if isinstance(f.arg, Atom):
                return "not " + self.at(f.arg)
            return "not " + self.wrapped(f.arg)
        if isinstance(f, Or):
            same = self._same_kind_atoms(f)
            if same is not None:
                word = "within reach of" if same[0].kind == "object" else "in"
                return f"{word} {self.choice(same)}"
            return " or ".join(self.wrapped(d) for d in _disjuncts(f))
        if isinstance(f, And):
            return " and ".join(self.wrapped(c) for c in conjuncts(f))
        if isinstance(f, Implies):
            return f"if {self.wrapped(f.left)} then {self.wrapped(f.right)}"
        if isinstance(f, Equiv):
            return f"{self.wrapped(f.left)} exactly when {self.wrapped(f.right)}"
        raise _NoPattern(f)

    def wrapped(self, f: Formula) -> str:
        """:meth:`cond` in square brackets unless ``f`` is a literal or a grouped choice."""
        text = self.cond(f)
        same = self._same_kind_atoms(f) if isinstance(f, Or) else None
        # A choice within one category reads as one noun phrase ("a bedroom (room_5 or room_6)").
        if _is_literal(f) or (same is not None and same[0].kind != "unknown"
                                and len({(e.kind, e.category) for e in same}) == 1):
            return text
        return f"[{text}]"

    # -- goals: F s ----------------------------------------------------------------------------------
    def goal(self, s: Formula) -> str:
        """``F s`` for a state condition ``s`` as an imperative: go to / reach ..."""
        if isinstance(s, Atom):
            e = self.entity(s)
            return f"{'reach' if e.kind == 'object' else 'go to'} {e.phrase()}"
        if isinstance(s, Not) and isinstance(s.arg, Atom):
            e = self.entity(s.arg)
            return f"be {'out of reach of' if e.kind == 'object' else 'outside'} {e.phrase()}"
        same = self._same_kind_atoms(s) if isinstance(s, Or) else None
        if same is not None:
            return f"{'reach' if same[0].kind == 'object' else 'go to'} {self.choice(same)}"
        parts = _factored(s)
        if parts is not None:
            reading = self._joint_goal(parts)
            if reading is not None:
                return reading
        return f"at some moment be {self.cond(s)}"

    def _joint_goal(self, literals: list[Formula]) -> str | None:
        """``reach A and B at the same moment while in R while not ...`` for a conjunction of literals
        and choices among atoms of one kind."""
        positive: list[list[Referent]] = []
        for item in literals:
            if isinstance(item, Atom):
                positive.append([self.entity(item)])
            elif isinstance(item, Or):
                same = self._same_kind_atoms(item)
                if same is None:
                    return None
                positive.append(same)
        negative = [a for a in literals if isinstance(a, Not)]
        rooms = [g for g in positive if g[0].kind == "room"]
        objects = [g for g in positive if g[0].kind == "object"]
        if len(rooms) > 1 or len(rooms) + len(objects) != len(positive) or not positive:
            return None
        if objects:
            text = "reach " + " and ".join(self.choice(g) for g in objects)
            if len(objects) > 1:
                text += " at the same moment"
            if rooms:
                text += f" while in {self.choice(rooms[0])}"
        else:
            text = f"go to {self.choice(rooms[0])}"
        if negative:
            text += " while " + " and ".join(self.cond(n) for n in negative)
        return text

    # -- conditions of if / iff ----------------------------------------------------------------------
    def statement(self, f: Formula) -> str:
        """A formula as a condition that is true or false of the whole path."""
        if not is_temporal(f):
            return f"you start {self.cond(f)}"
        if isinstance(f, Eventually) and not is_temporal(f.arg):
            return f"you are at some moment {self.cond(f.arg)}"
        if isinstance(f, Always) and not is_temporal(f.arg):
            return f"you are at every moment {self.cond(f.arg)}"
        if isinstance(f, (And, Or)):
            word = " and " if isinstance(f, And) else " or "
            parts = conjuncts(f) if isinstance(f, And) else _disjuncts(f)
            return word.join(f"[{self.statement(p)}]" for p in parts)
        raise _NoPattern(f)

    # -- clauses -------------------------------------------------------------------------------------
    def clause(self, f: Formula) -> str:
        """Any supported formula as an imperative clause (lower-case start, no final period)."""
        if isinstance(f, Implies):
            return f"if {self.statement(f.left)}, then {self.clause(f.right)}"
        if not is_temporal(f):
            return f"start {self.cond(f)}"
        if isinstance(f, Eventually):
            return self.eventually(f.arg)
        if isinstance(f, Always):
            return self.always(f.arg)
        if isinstance(f, Until) and not is_temporal(f.left) and not is_temporal(f.right):
            forbidden = self.forbidden(f.left)
            if forbidden is not None:
                return f"{self.goal(f.right)}, without {forbidden} before that"
            return f"{self.goal(f.right)}, being {self.cond(f.left)} at every moment before that"
        if isinstance(f, Equiv):
            return f"make sure that [{self.statement(f.left)}] exactly when [{self.statement(f.right)}]"
        if isinstance(f, Or):
            return "do one of: " + " or ".join(f"[{self.clause(d)}]" for d in _disjuncts(f))
        if isinstance(f, And):
            return "do both: " + " and ".join(f"[{self.clause(c)}]" for c in conjuncts(f))
        raise _NoPattern(f)

    def forbidden(self, s: Formula) -> str | None:
        """A conjunction of negated places as what not to do (``entering the kitchen (...) or coming within
        reach of a tv (...)``), else ``None``. ``!(o & r)`` with ``r`` the room of object ``o`` reads
        ``coming within reach of o while in r``."""
        rooms: list[Referent] = []
        objects: list[Referent] = []
        in_room: dict[str, tuple[Referent, list[Referent]]] = {}
        for item in conjuncts(s):
            if not isinstance(item, Not):
                return None
            atoms = conjuncts(item.arg)
            if not all(isinstance(a, Atom) for a in atoms):
                return None
            entities = [self.entity(a) for a in atoms]  # type: ignore[arg-type]
            things = [e for e in entities if e.kind == "object"]
            places = [e for e in entities if e.kind == "room"]
            if len(entities) == 1 and entities[0].kind != "unknown":
                (objects if things else rooms).append(entities[0])
            elif (len(entities) == 2 and len(things) == 1 and len(places) == 1
                  and things[0].room_key == places[0].key):
                in_room.setdefault(places[0].key, (places[0], []))[1].append(things[0])
            else:
                return None
        said = []
        if rooms:
            said.append("entering " + " or ".join(e.phrase() for e in rooms))
        if objects:
            said.append("coming within reach of " + self.choice(objects))
        for room, group in in_room.values():
            said.append(f"coming within reach of {self.choice(group)} while in {room.phrase()}")
        return " or ".join(said)

    def eventually(self, body: Formula) -> str:
        """``F body``: a goal, possibly followed by what must happen from there."""
        if not is_temporal(body):
            return self.goal(body)
        if isinstance(body, Or):  # F(A | B) = F A | F B: a choice between two ways
            return "do one of: " + " or ".join(f"[{self.eventually(d)}]" for d in _disjuncts(body))
        parts = conjuncts(body)
        here = [p for p in parts if not is_temporal(p)]
        later = [p for p in parts if is_temporal(p)]
        if not here:
            return f"at some moment, from then on: {self.clause(body)}"
        goal = self.goal(here[0] if len(here) == 1 else And(tuple(here)))
        if len(later) == 1 and isinstance(later[0], Eventually):
            return f"{goal}, then {self.eventually(later[0].arg)}"
        if len(later) == 1:
            return f"{goal}, and from that moment on {self.clause(later[0])}"
        rest = " and ".join(f"[{self.clause(p)}]" for p in later)
        return f"{goal}, and from that moment on do both: {rest}"

    def always(self, body: Formula) -> str:
        """``G body``: avoidance, an invariant, or a response."""
        if isinstance(body, Implies) and not is_temporal(body.left):
            trigger = self.cond(body.left)
            if isinstance(body.right, Eventually) and not is_temporal(body.right.arg):
                return f"whenever you are {trigger}, {self.goal(body.right.arg)} then or afterwards"
            if is_temporal(body.right):
                return f"whenever you are {trigger}, from that moment on {self.clause(body.right)}"
        if is_temporal(body):
            raise _NoPattern(body)
        items = conjuncts(body)
        if all(isinstance(i, Not) and isinstance(i.arg, Atom) for i in items):
            entities = [self.entity(i.arg) for i in items]  # type: ignore[attr-defined]
            rooms = [e for e in entities if e.kind != "object"]
            objects = [e for e in entities if e.kind == "object"]
            said = []
            if rooms:
                said.append("enter " + " or ".join(e.phrase() for e in rooms))
            if objects:
                said.append("come within reach of " + " or ".join(e.phrase() for e in objects))
            return "never " + ", and never ".join(said)
        if isinstance(body, Not) and isinstance(body.arg, And):
            return f"never be {self.cond(body.arg)} at the same moment"
        return f"at every moment be {self.cond(body)}"
