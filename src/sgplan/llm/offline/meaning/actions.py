"""From an action of the syntax tree to steps of tasks: its phrases grounded in the step's context, the
list's order (*in that order*, *A, B, then C*, *B first*), *last*, *again* / *twice*, a destination
(*put X in Y*: X, then Y) and a purpose (*... to turn them off*)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from itertools import pairwise

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.discourse import Discourse, FloorReading, Grounded, Where
from sgplan.llm.offline.grounding.floors import floors_of
from sgplan.llm.offline.grounding.phrases import ground_list
from sgplan.llm.offline.grounding.restated import members_restated
from sgplan.llm.offline.meaning.compose import member_formula, moved
from sgplan.llm.offline.meaning.context import SentenceContext
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.syntax.tree import Action, Repeat
from sgplan.llm.offline.tasks import Step, Task


@dataclass
class ActionSteps:
    """The steps of an action; ``first_left``: *first* was said right after its phrases without reordering
    them (*go to A first and B*), so it orders the action itself (:mod:`.body`)."""

    steps: list[Step]
    first_left: bool = False


def steps_of(action: Action, ctx: SentenceContext, scope: list[Entity] | None = None, lenient: bool = False,
             action_floor: tuple[FloorReading, int] | None = None,
             floor: FloorReading | None = None) -> ActionSteps:
    """The steps of ``action``; ``scope``: the rooms of the step it is said in (its objects are looked for
    there, and, with ``lenient``, elsewhere when none is there); ``action_floor`` / ``floor``: the floors of
    a floor move before it (every goal there) and of the verb before it (its first phrase there)."""
    disc, verbs = ctx.disc, action.verbs
    if verbs.floor is not None:
        floor = floors_of(verbs.floor, disc)  # "go upstairs to the bathroom": the bathroom on that floor
    going_back = bool(set(verbs.words) & lx.REVISIT_VERBS)
    carry = bool(set(verbs.words) & lx.CARRY_VERBS)
    if set(verbs.words) & lx.FLOOR_CHANGES:  # "then head down to the kitchen (for X)": off the scope's floor
        ctx.floor_scope = None
    again = going_back or (action.repeat is not None and action.repeat.again)
    where = Where("goal", tuple(scope or ctx.scope), lenient, tuple(ctx.soft_scope), floor,
                  action_floor or ctx.floor_scope, going_back, carry, again,
                  previous=tuple(ctx.previous_room),
                  listed_after=tuple(ctx.listed_room))
    if action.phrases is None:  # "go upstairs and check the laptop": the laptop upstairs
        assert action.moved is not None and floor is not None
        return steps_of(action.moved, ctx, scope, lenient, (floor, action.moved.span.start), floor)
    if action.instead:
        instead_of_prohibitions(action, disc)
    phrases = ground_list(action.phrases, where, disc)
    left_the_scope(phrases, ctx)
    content_or_goal(phrases, disc)
    room_or_its_fixture(action, phrases, disc)
    if action.moved is not None:  # "go up to the top floor and check a bathroom (there)": one goal there
        floors = FloorReading(frozenset(e.floor for e in phrases[0].entities))
        return steps_of(action.moved, ctx, scope, lenient, (floors, action.moved.span.start))
    said_after = action.first and not action.verbs.first and action.phrases.comma_list
    phrases, lead = first_of_list(phrases, action.first, said_after)
    choice_remark(phrases, action.remark, disc)
    steps = ordered_steps(action, phrases, carry, lead, ctx)
    if action.repeat is not None:
        repeats(phrases, steps, action.repeat, going_back, ctx)
    elif going_back and named_before(phrases, ctx):
        for task in steps[0]:
            task.revisit = True
    tail(action, phrases, steps, carry, replace(where, floor=None, action_floor=None, objects=False), ctx)
    return ActionSteps(steps or [[]], action.first and not lead)


def left_the_scope(phrases: list[Grounded], ctx: SentenceContext) -> None:
    """A room gone to outside the sentence's room (*In the kitchen, check the fridge, then the bathroom
    downstairs (toilet)*, a note's *kit: oven -> din rm (any chair)*) leaves it: what is named after it is
    not looked for in the sentence's room."""
    if ctx.scope and any(g.role == "goal" and g.entities and all(e.kind == "room" and e not in ctx.scope
                                                                 for e in g.entities) for g in phrases):
        ctx.scope = []


def content_or_goal(phrases: list[Grounded], disc: Discourse) -> None:
    """*go to the bedroom, the one with the plant, and the vase* where that bedroom holds the vase: more of
    what it holds (as said in one breath), or another goal? Refused, as *the bedroom with the plant and the
    vase* is (:func:`.attachments.describes`): a room said by its contents, then, after *and* in the same
    list, an object of that room placed by nothing else and not of a kind its contents named (*the bathroom
    with the two toilets, either toilet* is the toilets)."""
    for room, thing in pairwise(phrases):
        words = room.phrase.lower().replace("w/", " with ").split()
        rooms = {e.key for e in room.entities}
        joined = disc.said(room.end, thing.start).lower().split()
        said_kinds = {" ".join(words[k:k + n]) for n in (1, 2) for k in range(len(words))}
        if (rooms and all(e.kind == "room" for e in room.entities) and set(words) & lx.CONTENT_WORDS
                and "and" in joined and not {e.category for e in thing.entities} & said_kinds
                and thing.entities and not set(thing.phrase.lower().split()) & lx.PLACING_WORDS
                and all(e.kind == "object" and e.room_key in rooms for e in thing.entities)):
            rf.refuse(rf.both_contents_or_goal(disc.said(room.start, thing.end), thing.phrase))


def room_or_its_fixture(action: Action, phrases: list[Grounded], disc: Discourse) -> None:
    """*check / clean the loo*: an everyday name of the room (:data:`.lexicon.EVERYDAY_NAMES`) that also names
    a thing in it, the object of a verb that acts on things: the bathroom, or its toilet? Refused where the
    scene has both (*go to / look in the loo* is the room)."""
    verbs = set(action.verbs.words)
    if not verbs & lx.FIXTURE_VERBS or verbs & (lx.INTO_A_ROOM | {"in"}):
        return
    for g in phrases:
        name = next((w for w in g.phrase.lower().split() if len(lx.EVERYDAY_NAMES.get(w, ())) > 1), None)
        if name is None or not g.entities or any(e.kind != "room" for e in g.entities):
            continue
        fixtures = lx.EVERYDAY_NAMES[name][1:]
        if any(c in disc.vocab.category_names("object") for c in fixtures):
            rf.refuse(rf.room_or_fixture(g.phrase, g.entities[0].category, fixtures[0]))


def instead_of_prohibitions(action: Action, disc: Discourse) -> None:
    """*... instead* closing ``action``: an alternative to the places kept out of before it (*Keep out of
    the kitchen. Check the couch instead.*), which changes nothing; after a goal it may take that goal back
    (*Go to the kitchen. Go to the lobby instead.*), and after no prohibition it says nothing clear:
    refused both ways."""
    before = [g for g in disc.references if g.end <= action.span.start]
    if any(g.role == "goal" for g in before) or not any(g.role == "avoid" for g in before):
        rf.refuse(rf.cannot_understand(lx.REFUSED_WORDS["instead"]))


def ordered_steps(action: Action, phrases: list[Grounded], carry: bool, lead: bool,
                  ctx: SentenceContext) -> list[Step]:
    """The tasks of the phrases, in the steps their order says: one step (any order), one each (*in that
    order*), the one said *first* before the rest, the one said *last* after the rest."""
    pronouns_only = all(g.phrase.lower() in lx.PRONOUNS and not g.mentioned for g in phrases)
    # "put it in Y": the object is already in hand, the goal is Y, after what came before.
    steps = [[]] if carry and pronouns_only else tasks_of(phrases, action.ordered)
    if action.carried_on:  # "take an apple and bring to Y": as "bring it to Y", Y after the apple
        if not any(e.kind == "object" for g in ctx.disc.references if g.start < action.span.start
                   for e in g.entities):
            rf.refuse(rf.carried_nothing(ctx.disc.said(action.span.start, action.span.end)))
        steps = [[], *steps]
    if lead:  # "A and B, B first": B, then A
        steps = [moved([steps[0][:1]])[0], steps[0][1:]]
    if action.last:
        if len(steps) != 1:
            rf.refuse(rf.cannot_understand(lx.REFUSED_WORDS["last"]))
        ctx.said_last = True  # "the kitchen and the office last": the office after the rest
        steps = [steps[0][:-1], steps[0][-1:]]
    return steps


def tail(action: Action, phrases: list[Grounded], steps: list[Step], carry: bool, where: Where,
         ctx: SentenceContext) -> None:
    """The destination and the purpose of ``action``, added to ``steps``."""
    if action.destination is not None:
        routed = carry or bool(set(action.verbs.words) & lx.ROUTE_VERBS) or all(
            e.kind == "object" for g in phrases for e in g.entities)
        if routed:  # "put X in Y", "take X to Y", "go from X to Y": X, then Y
            dest = ground_list(action.destination, replace(where, scope=()), ctx.disc)
            choice_remark(dest, action.destination_remark, ctx.disc)
            steps.extend(tasks_of(dest, False))
        else:  # "go to the kitchen to the office": another goal of the step
            dest = ground_list(action.destination, replace(where, scope=tuple(ctx.step_rooms(steps[-1]))),
                               ctx.disc)
            choice_remark(dest, action.destination_remark, ctx.disc)
            steps[-1].extend(tasks_of(dest, False)[0])
    if action.purpose is not None:  # "go to the bathroom downstairs to check the toilet": the toilet there
        own = tuple(ctx.step_rooms(steps[-1]))
        purpose = ground_list(action.purpose, replace(where, scope=own or where.scope), ctx.disc)
        several = next((g for g in purpose if g.mode == "all" and len(g.entities) > 1
                        and g.phrase.lower() not in lx.PRONOUNS), None)
        if several is not None and own and action.purpose_remark is None:
            # "go to the lobby for see the vases": each vase, or the lobby only? ("..., any one": one)
            rf.refuse(rf.purpose_of_several(ctx.disc.said(action.span.start, several.end), several.phrase))
        choice_remark(purpose, action.purpose_remark, ctx.disc)
        if not all(g.phrase.lower() in lx.PRONOUNS for g in purpose):
            steps[-1].extend(tasks_of(purpose, False)[0])


def tasks_of(phrases: list[Grounded], ordered: bool) -> list[Step]:
    """One task per phrase (``any`` or ``all`` of its members): one step, or one step each when ordered."""
    tasks = []
    for g in phrases:
        if g.choice_of is not None:  # "look at a vase, then look at it again": the same vase
            rf.refuse(g.choice_of)
        tasks.append(Task("any" if g.mode == "any" else "all", [member_formula(e, g.room_scoped)
                                                                 for e in g.entities], said_at=g.start))
    if ordered and len(tasks) > 1:
        return [[t] for t in tasks]
    return [tasks]


def first_of_list(phrases: list[Grounded], first: bool,
                  last_first: bool = False) -> tuple[list[Grounded], bool]:
    """``A and B, B first``: the list with B moved to the front and once only (and True: B goes first); so
    is ``A, B first`` (``last_first``: *first* after a list joined by commas only). A phrase that only
    restates the one before it is dropped (*the chairs, both of them*; *a TV, any TV*); any other phrase
    named twice in one list is refused: it is not clear what is meant."""
    phrases = members_restated(phrases)  # "both plants, the one by the couch and the one in the office"
    keys = [frozenset(e.key for e in g.entities) for g in phrases]
    phrases = [g for n, g in enumerate(phrases)
               if not (n and keys[n] == keys[n - 1] and restates_group(g.phrase))
               and not (n and keys[n] >= keys[n - 1] and restates_choice(g, phrases[n - 1]))]
    for g in phrases:
        words = g.phrase.lower().split()
        if g.mode == "any" and words[0] == "either" and "or" not in words and len(g.entities) != 2:
            rf.refuse(rf.either_of_more(g.phrase, [e.describe() for e in g.entities]))  # one of two
    keys = [frozenset(e.key for e in g.entities) for g in phrases]
    repeated = [n for n, k in enumerate(keys) if any(k & j for j in keys[:n])]
    if not repeated and last_first and len(phrases) > 1:  # "go to the office, the kitchen first"
        return [phrases[-1], *phrases[:-1]], True
    if not repeated:
        return phrases, False
    if repeated == [len(phrases) - 1] and first:  # "the clocks, the one in the bedroom first"
        return [phrases[-1]] + [g for n, g in enumerate(phrases[:-1]) if keys[n] != keys[-1]], True
    rf.refuse(rf.named_twice(phrases[repeated[0]].phrase))


def restates_choice(g: Grounded, before: Grounded) -> bool:
    """Whether ``g`` only says again that the choice before it is free: *a TV, any TV*, *a bed in the
    bedroom with the TV, either bed* (of the same kind, naming those of the choice and maybe more)."""
    return g.mode == before.mode == "any" and g.phrase.lower().split()[0] in lx.RESTATED_CHOOSERS


def restates_group(phrase: str) -> bool:
    """Whether a phrase only names the group before it again: *both of them*, *all three of them*, *all
    three* (*office TVs, all three*), *both*."""
    words = phrase.lower().split()
    counted = len(words) == 2 and (words[1] in lx.NUMBER_WORDS or words[1].isdigit())
    return words[-1] == "them" or (counted and words[0] in lx.UNIVERSAL) or words == ["both"]


def choice_remark(phrases: list[Grounded], remark: tuple[str, ...] | None, disc: Discourse) -> None:
    """*, either one is fine* after a choice only confirms it; after a phrase that means each of several
    (or after several phrases) it would turn "all" into "one of", so it is refused. *, just one of them* / *,
    any of the three* say outright that one will do: the phrase is a choice (of that many, when said)."""
    if remark is None:
        return
    said = disc.said
    words = tuple(w for w in remark if w != ",")
    count = next((lx.NUMBER_WORDS.get(w) or int(w) for w in words
                  if w.isdigit() or (w in lx.NUMBER_WORDS and w != "one")), None)
    choose = count is not None or any(words[k:k + len(p)] == p for p in lx.ONE_SUFFICES
                                      for k in range(len(words)))
    picked = bool(set(words) & lx.PICK_VERBS) and words[-1] == "one"  # not "lobby, pick any vase"
    if picked and len(phrases) == 1 and len(phrases[0].entities) == 1:
        rf.refuse(rf.pick_from_one(" ".join(words), phrases[0].phrase))  # "the kitchen, pick one": of what?
    if len(phrases) == 1 and choose and (count is None or count == len(phrases[0].entities)):
        phrases[0].mode = "any"  # "check the vases in the lobby, just one of them": any of them
        return
    if count is not None and len(phrases) == 1:  # "a TV in the office, any of the two" (there are three)
        rf.refuse(rf.group_size(" ".join(words), phrases[0].phrase, len(phrases[0].entities), count))
    if len(phrases) > 1 or (phrases[0].mode != "any" and len(phrases[0].entities) > 1):
        rf.refuse(rf.remark_after_each(" ".join(words), said(phrases[0].start, phrases[-1].end)))


def chosen_before(phrase: Grounded, ctx: SentenceContext) -> bool:
    """Whether ``phrase`` (each of several) names again a goal that was a choice among the same entities."""
    return any(r.role == "goal" and r.start < phrase.start and r.mode == "any"
               and set(phrase.entities) <= set(r.entities) for r in ctx.disc.references)


def named_before(phrases: list[Grounded], ctx: SentenceContext) -> bool:
    """Whether every entity of ``phrases`` was a goal before them; an object in room X named as a goal was a
    visit of X too (*a vase in the lobby, ..., the lobby again*), when every object it allowed is in X."""
    refs = ctx.disc.references
    return all(
        any(r.role == "goal" and r.start < phrases[0].start
            and (e in r.entities or (e.kind == "room" and all(o.kind == "object" and o.room_key == e.key
                                                              for o in r.entities)))
            for r in refs)
        for g in phrases for e in g.entities)


def repeats(phrases: list[Grounded], steps: list[Step], repeat: Repeat, going_back: bool,
            ctx: SentenceContext) -> None:
    """``X again`` / ``go back to X`` (X named as a goal before): a new visit; ``X twice`` / ``X three
    times``: the visit and then new visits; ``X twice, with a visit to Y in between``: X, Y, X."""
    before = named_before(phrases, ctx)
    if repeat.again and not before:
        rf.refuse(rf.again_not_a_goal(ctx.disc.said(phrases[0].start, phrases[-1].end)))
    chosen = next((g for g in phrases if repeat.again and g.mode != "any" and len(g.entities) > 1
                   and chosen_before(g, ctx)), None)
    if chosen is not None:  # "the TV (either one), ..., then back to the TVs again": each, or the one chosen?
        rf.refuse(rf.again_after_choice(ctx.disc.said(chosen.start, chosen.end)))
    if repeat.again or (going_back and before):
        for task in steps[0]:
            task.revisit = True
    if repeat.times < 2:
        return
    if not any(steps):  # "put it in the sink twice": the repetition would be lost
        rf.refuse(rf.cannot_understand(f"'{'twice' if repeat.times == 2 else f'{repeat.times} times'}' here"))
    last = list(steps[-1])
    if repeat.between is not None and repeat.times == 2:
        between = [s for s in steps_of(repeat.between, ctx).steps if s]
        steps.extend([*between, [Task(t.mode, t.members, said_at=t.said_at, moved=True) for t in last]])
    else:
        steps.extend([Task(t.mode, t.members, [], True, said_at=t.said_at, moved=True) for t in last]
                     for _ in range(repeat.times - 1))
