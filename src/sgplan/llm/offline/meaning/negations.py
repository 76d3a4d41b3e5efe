"""From prohibitions of the syntax tree to constraints: ``G !x`` for the whole mission, ``!x U y`` until a
goal, or, for an object of the room an action is in, ``F(action & !x)`` at that moment.

A trailing *and avoid X* / *without X* after an action forbids an object of a room the action is in at the
moment the action is done (the authors' convention: *visit the bathroom and avoid the sink*); a room, or an
object elsewhere, for the whole mission, as people mean it (one room at a time makes "in the bedroom and
not in the kitchen" say nothing).
"""

from __future__ import annotations

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.discourse import Grounded, Where
from sgplan.llm.offline.grounding.floors import floors_of
from sgplan.llm.offline.grounding.phrases import ground_list, ground_phrase
from sgplan.llm.offline.meaning.actions import steps_of
from sgplan.llm.offline.meaning.compose import Clause, conj, disj, until_formula
from sgplan.llm.offline.meaning.context import SentenceContext
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.syntax.tree import Action, Negation, OffLimits, StayOnFloor, UntilDone
from sgplan.llm.offline.tasks import Step, Task
from sgplan.logic.formula import Always, Atom, Formula, Not, atoms
from sgplan.logic.tokens import action_entity


def never(entities: list[Entity]) -> Formula:
    """Not at any of ``entities`` (one state)."""
    return conj([Not(Atom(e.action)) for e in entities])


_ENTERING = frozenset({"enter", "enters", "entering", "into"})
"""Verbs (and the particle) of a prohibition that only a room can follow: a pronoun after them names a room
(*Go to the bedroom with the teddy bear, but don't enter it until ...*: the bedroom, not the teddy bear)."""


def negation(item: Negation, clause: Clause, ctx: SentenceContext, said_whole: bool = False) -> None:
    """*always avoid X* / *never enter X* (``G !X``), *avoid X* after an action (local, see the module
    docstring), *don't enter X until Y* (``!X U Y``); ``said_whole``: for the whole mission whatever came
    before (*stay on the top floor and off the stairs*)."""
    if item.stay is not None:  # "don't leave this floor"
        stay_on_floor(item.stay, clause, ctx)
        return
    declared = said_whole or bool(lx.GLOBAL_NEG & set(item.marker)) or not any(clause.steps)
    rooms = ctx.scope if declared else ctx.step_rooms(clause.steps[-1])
    if item.floor is not None:  # "never go upstairs": every room there
        phrases = [ground_phrase(item.floor, Where("avoid"), ctx.disc)]
    else:
        assert item.phrases is not None and item.verbs is not None
        floor = floors_of(item.verbs.floor, ctx.disc) if item.verbs.floor is not None else None
        entering = bool(set(item.verbs.words) & _ENTERING)  # "don't enter it": a room, never the object
        where = Where("avoid", tuple(rooms), floor=floor, action_floor=ctx.floor_scope, rooms=entering)
        phrases = ground_list(item.phrases, where, ctx.disc)
    is_global = declared or item.whole
    entities = [e for g in phrases for e in g.entities]
    if item.until is not None:
        ctx.disc.kept_until |= {e.key for e in entities if e.kind == "room"}
        until(never(entities), item.until, clause, ctx)
    elif is_global:
        clause.constraints.append(Always(never(entities)))
    else:
        target = [t for s in clause.steps for t in s][-1]
        local, everywhere = avoidance_scope(target, entities, ctx)
        target.avoid.extend(Not(Atom(e.action)) for e in local)
        if everywhere:
            clause.constraints.append(Always(never(everywhere)))


def until(forbidden: Formula, target: object, clause: Clause, ctx: SentenceContext) -> None:
    """*... until you have seen Y* / *... until both of them are done* / *... before you've done that*:
    ``!X U y`` for each part of Y (Y must then happen); Y is the step a following *then* comes after."""
    steps = [previous_step(clause, ctx)] if isinstance(target, UntilDone) else steps_of(target, ctx).steps  # type: ignore[arg-type]
    tasks = [t for s in steps for t in s]
    if len(tasks) > 1 and all(t.mode == "all" for t in tasks):  # "until A and B": each of them
        tasks = [Task("all", [m for t in tasks for m in t.members])]
    if len(tasks) != 1:
        rf.refuse(rf.until_needs_one_goal())
    t = tasks[0]
    if isinstance(target, Action) and target.done:
        done_where_goals_are(target, t, ctx)
    ends = [disj(t.members)] if t.mode == "any" else t.members
    clause.constraints.extend(until_formula(forbidden, end) for end in ends)
    if not any(clause.steps) and not ctx.prior_steps:
        # "Keep out of X until you have seen Y, then Z": Y (which the until requires) is the step that *then*
        # follows
        clause.steps[-1].append(Task(t.mode, list(t.members), said_at=t.said_at))


def done_where_goals_are(target: Action, task: Task, ctx: SentenceContext) -> None:
    """Refuses *... until you're done in X* (``target``, read as ``task``) when X is a room that holds a goal
    named before it: until X is entered, or until that goal is done?"""
    said = [a for m in task.members for a in atoms(m)]
    if any(a.startswith("reach(") for a in said):
        return  # "until both of them are done": the goals themselves
    rooms = {action_entity(a) for a in said}
    if any(e.kind == "object" and e.room_key in rooms for g in ctx.disc.goals_before() for e in g.entities):
        span = target.phrases.span if target.phrases is not None else target.span
        rf.refuse(rf.done_in_a_room_of_goals(ctx.disc.said(span.start, span.end)))


def previous_step(clause: Clause, ctx: SentenceContext) -> Step:
    """The last step with goals, in this clause or the sentence before (what *that* in *before you have
    done that* refers to); refused when there is none."""
    for step in reversed(clause.steps):
        if step:
            return step
    if ctx.disc.last_step:
        return ctx.disc.last_step
    rf.refuse(rf.done_that_of_nothing())


def avoidance_scope(target: Task, forbidden: list[Entity], ctx: SentenceContext) -> tuple[list[Entity],
                                                                                            list[Entity]]:
    """Split what a trailing *avoid* / *without* forbids into what holds when ``target`` is done (an object of
    a room the target is in) and what holds for the whole mission (see the module docstring)."""
    by_key = ctx.disc.vocab.by_key
    keys = [action_entity(a) for m in target.members for a in atoms(m)]
    rooms = {by_key[k].room_key for k in keys if k in by_key}
    local = [e for e in forbidden if e.kind == "object" and e.room_key in rooms]
    return local, [e for e in forbidden if e not in local]


def stay_on_floor(item: StayOnFloor, clause: Clause, ctx: SentenceContext) -> None:
    """*stay on this floor* / *don't leave the ground floor* / *stay downstairs*: every room of the other
    floors is forbidden for the whole mission (the goals are grounded on the floors it stays on, see
    :func:`.mission.confinement`)."""
    disc = ctx.disc
    floors = floors_of(item.floor, disc).floors
    rooms = [e for e in disc.vocab.entities if e.kind == "room" and e.floor not in floors]
    said = disc.said(item.span.start, item.span.end)
    if not rooms:
        rf.refuse(rf.no_other_floor(said))
    # the grounded text names what the words name: the floors kept ("stay on room_9, ... room_14"), or the
    # others ("don't go to room_2, ... room_8" for "any other floor")
    kept = [e for e in disc.vocab.entities if e.kind == "room" and e.floor in floors]
    named = rooms if item.other else kept
    disc.record(Grounded(said, item.span.start, item.span.end, named, "all", False,
                         "avoid" if item.other else "qualifier"))
    clause.constraints.append(Always(never(rooms)))
    if item.and_off is not None:  # "stay on the top floor and off the stairs"
        negation(item.and_off, clause, ctx, said_whole=True)


def off_limits(item: OffLimits, clause: Clause, ctx: SentenceContext) -> None:
    """*The kitchen is off limits* / *the office and the garage are out of bounds*: ``G !x`` for each."""
    phrases = ground_list(item.phrases, Where("avoid"), ctx.disc)
    clause.constraints.append(Always(never([e for g in phrases for e in g.entities])))
