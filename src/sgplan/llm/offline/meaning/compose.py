"""From parsed goals to LTL: tasks, sequences of steps, and the formulas they stand for.

A :class:`Task` is one goal over a set of alternatives (``any``: one of them) or of obligations
(``all``: each of them, in any order); each member is a state formula such as ``reach(object_21)`` or
``reach(object_21) & enter(room_10)``. A *step* is a list of tasks done in any order; a mission sentence
is a sequence of steps, each finished before the next one's tasks count.

The sequence ``s_1, ..., s_n`` becomes, from the last step backwards, ``R_n = AND_t goal(t, None)`` and
``R_k = AND_{t in s_k} goal(t, R_{k+1})`` with ``goal(any, R) = F(OR members & avoid & R)`` and
``goal(all, R) = AND_m F(m & avoid & R)``. For an ``all`` task this says "every member is done, and the
rest of the sequence happens after it"; the rest then happens after the last of them, which is what
"do all of these, then ..." means (``F(a & F c) & F(b & F c)`` holds iff ``c`` follows both ``a`` and
``b``). ``avoid`` are the local negations of the task ("visit the bathroom and avoid the sink" ->
``F(enter(bathroom) & !reach(sink))``, the convention of the authors' missions). A ``revisit`` task
("twice", "... then the kitchen again" right after the kitchen) is a new visit: the robot is somewhere
else first, ``F(!m & F(m & avoid & R))``, so it cannot be satisfied by staying where the previous step
ended (with another goal in between, that goal separates the visits: not a ``revisit``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from sgplan.errors import MissionError
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.tasks import Step, Task
from sgplan.logic.formula import And, Atom, Eventually, Formula, Not, Or, Until, atoms


def until_formula(forbidden: Formula, end: Formula) -> Until:
    """``forbidden U end``, refused when ``end`` names what ``forbidden`` keeps out (``!X U X``: a back
    reference bound to the forbidden place itself, never what a person means)."""
    if set(atoms(forbidden)) & set(atoms(end)):
        rf.refuse(rf.until_what_it_forbids())
    return Until(forbidden, end)


def conj(parts: Sequence[Formula]) -> Formula:
    """The conjunction of ``parts`` (flattening nested conjunctions, dropping duplicates); one part as is."""
    return joined(parts, And)


def disj(parts: Sequence[Formula]) -> Formula:
    """The disjunction of ``parts`` (flattened, without duplicates); one part as is."""
    return joined(parts, Or)


def joined(parts: Sequence[Formula], op: type[And] | type[Or]) -> Formula:
    """``parts`` joined by ``op``, nested ``op`` flattened and duplicates dropped; one part as is."""
    flat: list[Formula] = []
    for p in parts:
        for q in p.args if isinstance(p, op) else (p,):
            if q not in flat:
                flat.append(q)
    if not flat:
        raise ValueError(f"empty {op.__name__}")
    return flat[0] if len(flat) == 1 else op(tuple(flat))


def task_formulas(task: Task, rest: Formula | None) -> list[Formula]:
    """The conjuncts that say ``task`` is done and ``rest`` (the later steps) happens afterwards."""
    extra = task.avoid + ([rest] if rest is not None else [])
    targets = [disj(task.members)] if task.mode == "any" else task.members
    if task.revisit:
        return [Eventually(conj([Not(m), Eventually(conj([m, *extra]))])) for m in targets]
    return [Eventually(conj([m, *extra])) for m in targets]


def sequence_formula(steps: Sequence[Step]) -> Formula | None:
    """The formula of a sequence of steps (see the module docstring); ``None`` if there is no task."""
    rest: Formula | None = None
    for step in reversed([s for s in steps if s]):
        rest = conj([f for task in step for f in task_formulas(task, rest)])
    return rest


def strict_formulas(steps: Sequence[Step]) -> list[Formula]:
    """``A, and only after that B``: for each ``strict`` task of a step, its members are not done until the
    previous step's tasks are (``!B U A``, one per member of an ``all`` task), on top of the sequence; after a
    sequence (``A, then C, and only after that B``) not until the whole of it is done in its order
    (``!B U (A & (!B U C))``), which needs one target per earlier step (else refused: after which?)."""
    out: list[Formula] = []
    done: list[Step] = []
    for step in [s for s in steps if s]:
        for task in step:
            if task.strict and done:
                forbidden = conj([Not(m) for m in task.members])
                out.extend(strict_after(forbidden, done))
        done.append(step)
    return out


def strict_after(forbidden: Formula, done: list[Step]) -> list[Formula]:
    """``forbidden`` kept until the steps ``done`` are, in their order (see :func:`strict_formulas`)."""
    targets = [[disj(t.members)] if t.mode == "any" else t.members for step in done for t in step]
    if len(done) == 1:
        return [Until(forbidden, t) for ts in targets for t in ts]
    if any(len(step) != 1 for step in done) or any(len(ts) != 1 for ts in targets):
        rf.refuse(rf.strict_after_several())
    nested = Until(forbidden, targets[-1][0])
    for ts in reversed(targets[:-1]):
        nested = Until(forbidden, And((ts[0], nested)))
    return [nested]


@dataclass
class Clause:
    """What one sentence body says: a sequence of steps and constraints on the whole mission."""

    steps: list[Step] = field(default_factory=lambda: [[]])
    constraints: list[Formula] = field(default_factory=list)

    def formula(self) -> Formula | None:
        """The sequence, its strict parts and the constraints, as one formula (``None`` if empty)."""
        goal = sequence_formula(self.steps)
        parts = ([goal] if goal is not None else []) + strict_formulas(self.steps) + self.constraints
        return conj(parts) if parts else None

    def filled(self) -> list[Step]:
        """The steps that have tasks."""
        return [s for s in self.steps if s]

    def goal_count(self) -> int:
        """How many goals the steps name (each member of an *all* task, one for a choice)."""
        return sum(len(t.members) if t.mode == "all" else 1 for step in self.steps for t in step)


def moved(steps: Sequence[Step]) -> list[Step]:
    """``steps`` with their tasks marked as placed by an explicit word (:attr:`Task.moved`), those without a
    task dropped."""
    for step in steps:
        for task in step:
            task.moved = True
    return [s for s in steps if s]


def check_text_order(clause: Clause, said: Callable[[int, int], str]) -> None:
    """The guard of the order of goals: a goal done after another that the text states after it is read out
    of the text's order, which only an explicit word (*before*, *first*, *after X*, *via*, ...) may do
    (:attr:`Task.moved`); any other inversion is a misreading, refused naming both (``said``: the text
    between two offsets)."""
    done: list[Task] = []
    for step in clause.filled():
        for later in step:
            for earlier in done:
                if (0 <= later.said_at < earlier.said_at and not later.moved and not earlier.moved):
                    raise MissionError(rf.out_of_text_order(said(later.said_at, later.said_at + 40),
                                                            said(earlier.said_at, earlier.said_at + 40)))
        done += step


def member_formula(entity: Entity, room_scoped: bool) -> Formula:
    """The state formula of being at ``entity`` (in its room too, for a room-scoped object)."""
    atom = Atom(entity.action)
    if entity.kind == "object" and room_scoped:
        return conj([atom, Atom(f"enter({entity.room_key})")])
    return atom


def goal_eventually(task: Task) -> list[Formula]:
    """``task`` done at some point (each member of an ``all`` task, one of an ``any`` task)."""
    if task.mode == "any":
        return [Eventually(disj(task.members))]
    return [Eventually(m) for m in task.members]
