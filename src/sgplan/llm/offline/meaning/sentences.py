"""From a sentence of the syntax tree to a clause (steps and constraints) or a formula (condition rules).

A sentence opening (*After X, ...*, *Before Y, ...*, *Until Y, ...*, *Only after X, ...*, *In the kitchen,
...*) places its prefix in the sequence of the body's steps or constrains the body; a closing condition
(*... if X*, *... whenever X*, *... only after X*) takes the body as its consequent, or stands beside it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.discourse import Where
from sgplan.llm.offline.grounding.phrases import ground_phrase
from sgplan.llm.offline.meaning.actions import steps_of
from sgplan.llm.offline.meaning.body import read_body
from sgplan.llm.offline.meaning.compose import Clause, conj, disj, moved, until_formula
from sgplan.llm.offline.meaning.conditions import condition_of, require, rule_formula
from sgplan.llm.offline.meaning.context import SentenceContext
from sgplan.llm.offline.meaning.order import only_after
from sgplan.llm.offline.registry import Registry
from sgplan.llm.offline.syntax.tree import (
    Body,
    Negation,
    OnlyAfterPost,
    OnlyAfterSentence,
    OnlyIfPost,
    PlainSentence,
    Postfix,
    PrefixedSentence,
    RuleSentence,
    RulesPost,
    UntilSentence,
)
from sgplan.llm.offline.tasks import Task
from sgplan.logic.formula import Always, Formula, Implies

Meaning = Clause | Formula
SENTENCES: Registry[Callable[[Any, SentenceContext], Meaning]] = Registry("sentence reader")
reads = SENTENCES.register


def read_sentence_body(body: object, ctx: SentenceContext) -> Meaning:
    """The clause or formula of a sentence body (see the module docstring)."""
    meaning: Meaning = SENTENCES(body, ctx)
    return meaning


@reads(RuleSentence)
def rules(sentence: RuleSentence, ctx: SentenceContext) -> Meaning:
    """*Whenever X, Y, and if Z, W*: each rule kept."""
    return conj([rule_formula(rule, ctx) for rule in sentence.rules])


@reads(UntilSentence)
def until_first(sentence: UntilSentence, ctx: SentenceContext) -> Meaning:
    """*Until you have reached Y, stay out of X*: ``!X U Y`` for each prohibition; Y is a step, so a later
    *afterwards* / *then* follows it. The rest of the sentence must be prohibitions only."""
    tasks = [t for step in steps_of(sentence.target, ctx).steps for t in step]
    if len(tasks) > 1 and all(t.mode == "all" for t in tasks):  # "until A and B": each of them
        tasks = [Task("all", [m for t in tasks for m in t.members])]
    if len(tasks) != 1:
        rf.refuse(rf.until_needs_one_goal(prefix=True))
    # "..., and avoid the dining room the whole time": that one holds for the whole mission, not until Y
    whole = [item for item in sentence.body.items if isinstance(item, Negation) and item.whole]
    body = read_body(Body(tuple(i for i in sentence.body.items if i not in whole)), ctx)
    if any(body.steps) or not body.constraints or not all(isinstance(c, Always) for c in body.constraints):
        rf.refuse(rf.until_prohibitions_only())
    target = tasks[0]
    ends = [disj(target.members)] if target.mode == "any" else target.members
    untils: list[Formula] = [until_formula(c.arg, end) for c in body.constraints if isinstance(c, Always)
                             for end in ends]
    always = read_body(Body(tuple(whole)), ctx).constraints if whole else []
    return Clause(steps=[[target]], constraints=untils + always)


@reads(OnlyAfterSentence)
def only_after_first(sentence: OnlyAfterSentence, ctx: SentenceContext) -> Meaning:
    """*Only after X, Y* / *only <do Y> after X*: Y, and not before X; and the rules joined to it. Without
    rules, Y is the step a following *then* comes after."""
    if sentence.said_first:
        before = Clause(steps=steps_of(sentence.before, ctx).steps)
        body = read_body(sentence.body, ctx)
    else:
        body = read_body(sentence.body, ctx)
        before = Clause(steps=steps_of(sentence.before, ctx).steps)
    first = only_after(before, body, ctx)
    if not sentence.rules:
        return Clause(steps=body.steps, constraints=[first])
    return conj([first, *(rule_formula(rule, ctx) for rule in sentence.rules)])


@reads(PrefixedSentence)
def prefixed(sentence: PrefixedSentence, ctx: SentenceContext) -> Meaning:
    """*After X, Y* (X first) / *Before Y, X* and *On your way to Y, X* (Y last); *before Y, you must X*:
    Y, and not before X (``!Y U X``); Y is the step a following *then* comes after."""
    prefix = steps_of(sentence.prefix, ctx).steps
    goals = sum(len(task.members) if task.mode == "all" else 1 for step in prefix for task in step)
    if sentence.on_the_way and goals > 1:
        rf.refuse(rf.on_the_way_to_several(goals))  # "on your way up to the bedrooms": both, or a direction?
    prior = ctx.prior_steps
    if sentence.prefix.moved is not None and not sentence.prefix_last:
        # "once you're downstairs, water X, but keep out of Z until Y": the prefix took the goals (the floor
        # move and X): what the body says is not the first step of the sentence
        ctx.prior_steps = [*prior, *prefix]
    try:
        body = read_body(sentence.body, ctx)
    finally:
        ctx.prior_steps = prior
    if sentence.strict:
        strict = only_after(body, Clause(steps=prefix), ctx)
        return postfix(Clause(steps=prefix, constraints=[strict]), sentence.postfix, ctx)
    if sentence.prefix_last:
        body.steps.extend(moved(prefix))
    else:
        body.steps[:0] = prefix
    return postfix(body, sentence.postfix, ctx)


@reads(PlainSentence)
def plain(sentence: PlainSentence, ctx: SentenceContext) -> Meaning:
    """A body, in the room of *In the kitchen,* when said (which must then locate something said after it),
    with its closing condition and the whole-mission prohibitions said after it."""
    if sentence.scope is None:
        return with_prohibitions(postfix(read_body(sentence.body, ctx), sentence.postfix, ctx),
                                 sentence.prohibitions, ctx)
    room = ground_phrase(sentence.scope, Where("qualifier"), ctx.disc)
    ctx.scope, known = list(room.entities), len(ctx.disc.references)
    meaning = postfix(read_body(sentence.body, ctx), sentence.postfix, ctx)
    keys = {e.key for e in room.entities}
    if not any(g.role != "qualifier" and any(e.room_key in keys for e in g.entities)
               for g in ctx.disc.references[known:]):
        rf.refuse(rf.scope_unused(room.phrase))  # "In the garage, go to the office": the garage is not lost
    return with_prohibitions(meaning, sentence.prohibitions, ctx)


def with_prohibitions(meaning: Meaning, prohibitions: Body | None, ctx: SentenceContext) -> Meaning:
    """``meaning`` and the whole-mission prohibitions said after its condition (*..., but only after Y, and
    stay out of Z the whole time*), which hold beside it."""
    if prohibitions is None:
        return meaning
    said = read_body(prohibitions, ctx).constraints
    if isinstance(meaning, Clause):
        meaning.constraints.extend(said)
        return meaning
    return conj([meaning, *said])


def postfix(body: Clause, post: Postfix, ctx: SentenceContext) -> Meaning:
    """The body with its closing condition (see the module docstring)."""
    if post is None:
        return body
    if isinstance(post, OnlyAfterPost):  # "go to Y only after X": X said last, done first
        known = len(ctx.disc.references)
        before = Clause(steps=steps_of(post.before, ctx).steps)
        ctx.disc.done_before += [g for g in ctx.disc.references[known:] if g.role == "goal"]
        return Clause(steps=body.steps, constraints=[only_after(before, body, ctx)])  # Y: what "then" follows
    if isinstance(post, OnlyIfPost):
        condition, _ = condition_of(post.condition, ctx)
        return Implies(require(body, "before 'only if'"), condition)
    assert isinstance(post, RulesPost)
    if post.body_is_consequent:  # "S whenever X": the body is what the rule asks for
        first = rule_formula(post.rules[0], ctx, body)
        return conj([first, *(rule_formula(rule, ctx) for rule in post.rules[1:])])
    formulas = [rule_formula(rule, ctx) for rule in post.rules]  # "S, and whenever X, T": beside S
    return conj([require(body, "before the condition"), *formulas])
