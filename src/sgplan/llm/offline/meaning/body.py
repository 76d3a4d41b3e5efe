"""From the items of a sentence body to a clause: a sequence of steps and the constraints said with them.

Each kind of item has its reader here (:data:`READERS`), which adds to the clause: an action's tasks to the
current step (or a new one, before the others, on the way to the goal named last ...), a sequence word a
new step, a prohibition a constraint or a local avoidance.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any

from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.meaning.actions import steps_of
from sgplan.llm.offline.meaning.compose import Clause, moved
from sgplan.llm.offline.meaning.context import SentenceContext
from sgplan.llm.offline.meaning.negations import negation, off_limits, stay_on_floor
from sgplan.llm.offline.meaning.order import check_restriction_target
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.registry import Registry
from sgplan.llm.offline.syntax.tree import (
    AfterAll,
    Body,
    CommaSequence,
    DoneWith,
    GoalsFirst,
    InlineAfter,
    InlineBefore,
    Link,
    Negation,
    OffLimits,
    PlainAction,
    Pronoun,
    StayOnFloor,
    Waypoint,
)
from sgplan.llm.offline.tasks import Step, Task
from sgplan.logic import And

READERS: Registry[Callable[[Any, Clause, SentenceContext], None]] = Registry("item reader")
reads = READERS.register


def read_body(body: Body, ctx: SentenceContext) -> Clause:
    """The clause of ``body`` (see the module docstring)."""
    clause = Clause()
    for item in body.items:
        READERS(item, clause, ctx)
    return clause


def new_step(clause: Clause) -> None:
    """What follows goes in a new step (unless the current one is still empty)."""
    if clause.steps[-1]:
        clause.steps.append([])


@reads(Link)
def link(item: Link, clause: Clause, ctx: SentenceContext) -> None:
    """*then*, *after that* (a new step); *only after that* and *on the way,* also say how the next action
    is done."""
    ctx.strict_pending = ctx.strict_pending or item.strict
    ctx.waypoint_pending = ctx.waypoint_pending or item.waypoint
    if item.sequence:
        new_step(clause)


@reads(AfterAll)
def after_all(item: AfterAll, clause: Clause, ctx: SentenceContext) -> None:
    """*and after all three, X*: X after every goal of the sentence said before (their number checked;
    refused when an earlier sentence named goals too: after which ones?)."""
    goals = clause.goal_count()
    if not goals:
        rf.refuse(rf.after_all_of_nothing(item.said))
    if ctx.disc.goals_before(ctx.start):
        rf.refuse(rf.after_all_of_which(item.said))
    if item.number is not None and item.number != goals:
        rf.refuse(rf.after_all_count(item.said, goals, item.number))
    new_step(clause)


@reads(DoneWith)
@reads(InlineAfter)
def inline_after(item: DoneWith | InlineAfter, clause: Clause, ctx: SentenceContext) -> None:
    """*B after A* / *B once you have been to A* / *B when done with A*: A before the current step."""
    clause.steps[-1:-1] = moved(steps_of(item.action, ctx).steps)


@reads(InlineBefore)
def inline_before(item: InlineBefore, clause: Clause, ctx: SentenceContext) -> None:
    """*A before B*: B a step after the current one."""
    clause.steps.extend(steps_of(item.action, ctx).steps)
    clause.steps.append([])


@reads(GoalsFirst)
def goals_first(item: GoalsFirst, clause: Clause, ctx: SentenceContext) -> None:
    """*..., but first X* / *..., and before that X*: X before the steps said so far (*before that* after
    several steps is refused: before which?); with an obligation (*..., but before that you must X*) blind
    writers read it both as X, then the step, and as the step not done before X: refused."""
    if not any(clause.steps):
        if item.before_that:
            rf.refuse(rf.done_that_of_nothing())
        plain_action(PlainAction(item.action, False, False, False, None, item.rest, ""), clause, ctx)
        return
    if item.before_that and len(clause.filled()) > 1:
        rf.refuse(rf.before_which(item.rest))
    if item.obliged:  # "go in the dining room, but before this you must pass by the lobby"
        rf.refuse(rf.obliged_before_that(item.rest))
    clause.steps[0:0] = moved(steps_of(item.action, ctx).steps)


@reads(CommaSequence)
def comma_sequence(item: CommaSequence, clause: Clause, ctx: SentenceContext) -> None:
    """*go to the kitchen, pop up to the office, then ...*: the next action after this step, its objects
    looked for in this step's rooms first."""
    if clause.steps[-1]:
        ctx.carried_rooms = ctx.step_rooms(clause.steps[-1])
        clause.steps.append([])


@reads(Waypoint)
def waypoint(item: Waypoint, clause: Clause, ctx: SentenceContext) -> None:
    """*go to Y via X* / *..., passing through X*: X on the way, before the one goal Y just named."""
    if not clause.steps[-1]:
        verbs = replace(item.action.verbs, words=(*item.words, *item.action.verbs.words))
        plain_action(PlainAction(replace(item.action, verbs=verbs), False, False, False, None, item.rest, ""),
                     clause, ctx)
        return
    if len(clause.steps[-1]) != 1:
        rf.refuse(rf.waypoint_of_which(item.rest))
    target = clause.steps.pop()
    clause.steps.extend(moved(steps_of(item.action, ctx).steps))
    clause.steps.extend([target, []])


@reads(StayOnFloor)
def stay(item: StayOnFloor, clause: Clause, ctx: SentenceContext) -> None:
    """*stay on this floor* (:func:`.negations.stay_on_floor`)."""
    stay_on_floor(item, clause, ctx)


@reads(OffLimits)
def off_limits_item(item: OffLimits, clause: Clause, ctx: SentenceContext) -> None:
    """*X is off limits* (:func:`.negations.off_limits`)."""
    off_limits(item, clause, ctx)


@reads(Negation)
def negation_item(item: Negation, clause: Clause, ctx: SentenceContext) -> None:
    """*never enter X*, *avoid X* (:func:`.negations.negation`)."""
    negation(item, clause, ctx)


@reads(PlainAction)
def plain_action(item: PlainAction, clause: Clause, ctx: SentenceContext) -> None:
    """An action: its tasks in the current step, its objects looked for in the step's rooms (not when it is
    moved before the step, or after it: *go to the bedroom, but stop by the couch first*, *come back to
    X*); then what the words around it say of its order."""
    own_order = item.moved_first or item.goes_back or item.action.last
    later = own_order or ctx.listed
    context = [] if later else ctx.step_rooms(clause.steps[-1])
    # "go to the kitchen, take a bottle, then ...": the kitchen's bottle if it has one
    lenient = not context and bool(ctx.carried_rooms) and not later
    ctx.previous_room = [] if later or context or lenient else previous_room(clause, ctx)
    step_so_far = [m for task in clause.steps[-1] for m in task.members]  # not the steps before a "then"
    ctx.listed_room = ctx.rooms_of(step_so_far) if ctx.listed and not own_order else []
    done = steps_of(item.action, ctx, context or (ctx.carried_rooms if lenient else []), lenient)
    steps, ctx.carried_rooms, ctx.previous_room, ctx.listed_room = done.steps, [], [], []
    if ctx.strict_pending:
        check_restriction_target(steps[0], ctx)
        for task in steps[0]:
            task.strict = True
        ctx.strict_pending = False
    if ctx.waypoint_pending or item.on_the_way:
        ctx.waypoint_pending = False
        insert_on_the_way(clause, steps, ctx)
        return
    trailing = "first" if done.first_left else item.trailing
    again = any(t.revisit for t in steps[0]) and trailing is None and not item.action.last
    if (item.goes_back or again or acts_on_it(item)) and clause.steps[-1]:
        clause.steps.append([])  # "go to the kitchen and come back to the couch", "B and A again": after it
    check_revisits(steps[0], ctx.prior_steps + clause.steps[:-1], ctx)
    if trailing is not None:
        ordered_first(trailing, item, steps, clause, ctx)
    elif item.action.last:  # "... and the office last": after everything else said
        if item.more:
            rf.refuse(rf.last_followed_by(item.more))
        clause.steps[-1].extend(steps[0])
        clause.steps.extend([*steps[1:], []])
    else:
        clause.steps[-1].extend(steps[0])
        clause.steps.extend(steps[1:])


def previous_room(clause: Clause, ctx: SentenceContext) -> list[Entity]:
    """The one room the step before a new step puts the robot in, where a definite object that fits several
    is looked for (*go to the bedroom with the vase, then check the plant*; *bdrm w/o vase -> chk bed*): the
    clause's last step, else the previous sentence's when it had one step only (*up bth: sink*; after a
    sequence, *lobby -> LR -> kit. sink*, a sentence is in no order with it, so its sink is not the
    kitchen's); empty when that step is in several rooms or none."""
    filled = clause.filled()
    step = filled[-1] if filled else ctx.disc.last_step if ctx.disc.last_steps == 1 else []
    rooms = ctx.rooms_of([m for task in step for m in task.members])
    return rooms if len(rooms) == 1 else []


def acts_on_it(item: PlainAction) -> bool:
    """Whether the action acts on *it* / *them*, named by an action before it in the same clause (*grab the
    bowl, wipe it at the sink, and bring it to the couch*): done after that action, whatever joins them."""
    phrases = item.action.phrases
    return phrases is not None and any(isinstance(p, Pronoun) for p in phrases.items)


def ordered_first(trailing: str, item: PlainAction, steps: list[Step], clause: Clause,
                  ctx: SentenceContext) -> None:
    """*go to B, but go to A first / before that*: A before the steps so far; *go to A first and B*: A, then
    what follows; *Go to B. Go to A first.* is refused (before which goal?)."""
    if trailing == "before that" and len(clause.filled()) > 1:
        rf.refuse(rf.before_which_trailing(item.rest))
    if trailing == "before that" and not any(clause.steps):  # "Go to B. Go to A before that.": as 'first'
        rf.refuse(rf.trailing_first_later(trailing) if ctx.disc.last_step else
                  rf.before_that_of_nothing(item.rest.strip("'")))
    if any(clause.steps):
        clause.steps[0:0] = moved(steps)
        return
    if not item.more and ctx.disc.last_step:
        rf.refuse(rf.trailing_first_later())
    ctx.said_first = True
    clause.steps[-1].extend(steps[0])  # "go to A first and (then) B": A, then the rest
    clause.steps.extend(steps[1:] + [[]])


def insert_on_the_way(clause: Clause, steps: list[Step], ctx: SentenceContext) -> None:
    """Put ``steps`` (said *on the way*) right before the goal named last, in this sentence or the one it
    continues; refused when that goal is not one place (on the way to which?)."""
    new = moved(steps)
    for holder in (clause.steps, ctx.prior_steps):
        filled = [k for k, s in enumerate(holder) if s]
        if filled:
            k = filled[-1]
            earlier = ctx.prior_steps is holder and clause.steps != [[]] and any(clause.steps)
            if len(holder[k]) != 1 or earlier:
                rf.refuse(rf.on_the_way_to_which())
            holder[k:k] = new
            return
    rf.refuse(rf.on_the_way_to_nothing())


def check_revisits(step: Step, earlier: list[Step], ctx: SentenceContext) -> None:
    """A new visit (*again*, *go back to*, *return to*) must follow an earlier step of the same sequence
    that went there; otherwise nothing orders the two visits and the mission would be misread. When another
    goal lies between the two visits (*A, then B, then A again*), that goal separates them, as *then* does
    anywhere (``F(A & F(B & F A))``); only a visit right after the last (*A, then A again*) must leave
    first."""
    def went(tasks: list[Task], task: Task) -> bool:
        done = [m for t in tasks for m in t.members]
        # reaching "the bed in the bedroom" (the bed, in its room) was a visit of the bed
        covered = [a for m in done if isinstance(m, And) for a in m.args]
        return all(m in done or m in covered or any(ctx.task_is_in(t, m) for t in tasks)
                   for m in task.members)

    filled = [s for s in earlier if s]
    for task in step:
        if task.revisit and not went([t for s in filled for t in s], task):
            rf.refuse(rf.revisit_without_first_visit())
        if task.revisit and not went(filled[-1], task):
            task.revisit = False  # the goal in between separates the two visits
