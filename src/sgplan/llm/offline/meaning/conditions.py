"""From condition rules to formulas: *whenever X, Y* is the response ``G(X -> F Y)``; *if X, Y* is
``F X -> Y`` (*if* is said of one visit, each visit is *whenever* / *every time*; *if you ever / at any
point ...* is refused by the parser: read both ways); *when X, Y afterwards* is the response; a bare *when
X, Y* is refused (after X? whenever X? if X?).

A condition is one action that happened at some time during the path; its consequent is one action (or
one errand: a room, and things acted on there, :func:`.syntax.sentences.one_errand`), and goals only (a
prohibition scoped to *whenever* is not expressible this way, so it is refused).
"""

from __future__ import annotations

from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.meaning.actions import steps_of
from sgplan.llm.offline.meaning.body import read_body
from sgplan.llm.offline.meaning.compose import Clause, disj, sequence_formula
from sgplan.llm.offline.meaning.context import SentenceContext
from sgplan.llm.offline.syntax.tree import Action, Body, IfRule, Rule, WheneverRule
from sgplan.llm.offline.tasks import Task
from sgplan.logic.formula import Always, Formula, Implies


def rule_formula(rule: Rule, ctx: SentenceContext, body: Clause | None = None) -> Formula:
    """The formula of ``rule``; ``body``: the sentence's body when it is the rule's consequent (*S whenever
    X*), else the rule's own consequent is read (with the condition's rooms as its context)."""
    if isinstance(rule, WheneverRule):
        trigger = trigger_task(rule.trigger, ctx)
        said = body if body is not None else consequent(rule.consequent, trigger.members, ctx)
        return whenever(trigger, said)
    condition, tasks = condition_of(rule.condition, ctx)
    members = [m for t in tasks for m in t.members]
    said = body if body is not None else consequent(rule.consequent, members, ctx)
    return conditional(rule, condition, tasks, said)


def consequent(body: Body, members: list[Formula], ctx: SentenceContext) -> Clause:
    """The consequent of a condition on ``members``: a definite object of it that fits several is the one in
    the condition's room when exactly one is (*whenever you enter the bathroom upstairs, use the sink*)."""
    ctx.soft_scope = ctx.rooms_of(members)
    return read_body(body, ctx)


def trigger_task(action: Action, ctx: SentenceContext) -> Task:
    """The one place of *whenever you enter the kitchen* (a room or object, or a choice of them)."""
    tasks = [t for step in steps_of(action, ctx).steps for t in step]
    if len(tasks) != 1:
        rf.refuse(rf.trigger_needs_one())
    return tasks[0]


def condition_of(action: Action, ctx: SentenceContext) -> tuple[Formula, list[Task]]:
    """*if you go to the kitchen*: the formula that the condition happened (``F ...``), and its tasks."""
    steps = steps_of(action, ctx).steps
    formula = sequence_formula(steps)
    if formula is None:
        rf.refuse(rf.condition_names_nothing())
    return formula, [t for step in steps for t in step]


def whenever(trigger: Task, body: Clause) -> Formula:
    """*Whenever X, Y* / *Y whenever X*: each time the robot is at X, Y follows (``G(X -> F Y)``, the
    finite-path response; Y may happen at X itself)."""
    if body.constraints or any(t.avoid for step in body.steps for t in step):
        rf.refuse(rf.whenever_goals_only())
    return Always(Implies(disj(trigger.members), require(body, "for 'whenever'")))


def conditional(rule: IfRule, condition: Formula, tasks: list[Task], body: Clause) -> Formula:
    """*if X, Y*: ``F X -> Y``; *if X, Y afterwards*: ``F X -> F(X & F Y)`` (Y after that visit of
    X). *When X, Y* may mean either, or a plain sequence, so it is refused; so is *when X, Y afterwards*,
    read by some as each visit of X (*whenever*) and by others as once (*if*)."""
    if rule.word == "when":
        rf.refuse(rf.when_afterwards() if rule.afterwards else rf.bare_when())
    if rule.afterwards:  # "if you go into the living room, check the fridge afterwards": after that visit
        body = Clause(steps=[list(tasks), *body.steps], constraints=body.constraints)
    return Implies(condition, require(body, "for the condition"))


def require(clause: Clause, where: str) -> Formula:
    """The formula of ``clause``; refused when it asks nothing (*nothing to do <where>*)."""
    formula = clause.formula()
    if formula is None:
        rf.refuse(rf.nothing_to_do(where))
    return formula
