"""Strict order: *Only after X, Y* / *Y only after X* / *A, and only after that B* (Y, and not before X).

When Y holds X itself among several goals (*check the couch and the cup, and go into the bathroom but only
once you've checked the cup*), which of the others wait is not said: refused (with one other, *go to the
office and the living room, but the living room only after the office*, it is that one).

When Y is an object named through its room (*go to a TV in the living room, but only after the kitchen*),
"not before X" can mean not entering that room or not reaching the object, which differ; that is refused,
offering both phrasings, unless the room itself is a goal of the same step.
"""

from __future__ import annotations

from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.meaning.compose import Clause, conj, disj, goal_eventually
from sgplan.llm.offline.meaning.context import SentenceContext
from sgplan.llm.offline.meaning.contradiction import spoken
from sgplan.llm.offline.tasks import Task
from sgplan.logic.formula import And, Atom, Formula, Not, Until, atoms


def only_after(before: Clause, body: Clause, ctx: SentenceContext) -> Formula:
    """``Only after X, visit Y``: Y is visited, and not before X is (``!Y U X`` for each part of X)."""
    prior = [t for step in before.steps for t in step]
    goals = [t for step in body.steps for t in step]
    if not prior or not goals or len(body.filled()) > 1:
        rf.refuse(rf.only_after_needs())
    check_restriction_target(goals, ctx)
    awaited = {m for t in prior for m in t.members}
    if any(set(t.members) & awaited for t in goals):  # "check the couch and the cup, and go into the bathroom
        waiting = list({tuple(t.members): t for t in goals  # but only once you've checked the cup"
                        if not set(t.members) & awaited}.values())
        if len(waiting) > 1:
            rf.refuse(rf.only_after_which_wait([spoken(atoms(w.members[0])[0], ctx.disc.vocab)
                                                for w in waiting]))
    parts: list[Formula] = [f for t in goals for f in goal_eventually(t)]
    forbidden = conj([Not(m) for t in goals for m in t.members])
    for t in prior:
        if t.mode == "any":
            parts.append(Until(forbidden, disj(t.members)))
        else:
            parts.extend(Until(forbidden, m) for m in t.members)
    return conj(parts + body.constraints)


def check_restriction_target(goals: list[Task], ctx: SentenceContext) -> None:
    """Refuse *only after X* restricting an object located by its room, unless the room is a goal of the same
    step too (see the module docstring); *only enter the living room after X* and *reach the TV only after
    X* single one out."""
    plain = {m for t in goals for m in t.members if isinstance(m, Atom)}
    refs = ctx.disc.references
    for member in (m for t in goals for m in t.members if isinstance(m, And)):
        room = next(a for a in member.args if isinstance(a, Atom) and a.name.startswith("enter("))
        if room in plain:
            continue
        obj = next(a.name for a in member.args if isinstance(a, Atom) and a != room)
        named = next((g for g in reversed(refs) if g.role != "qualifier"
                      and any(e.action == obj for e in g.entities)), None)
        entity = next(e for g in refs for e in g.entities if e.action == obj)
        in_room = next((e for g in refs for e in g.entities if e.key == entity.room_key), None)
        room_name = f"the {in_room.category.replace('_', ' ')}" if in_room is not None else entity.room_key
        thing = f"the {entity.category.replace('_', ' ')}"
        rf.refuse(rf.only_after_two_readings(named.phrase if named else thing, room_name, thing))
