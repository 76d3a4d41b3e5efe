"""From the sentences of a mission to one formula: how sentences join (a new goal, the next steps of the
sequence, steps before the previous sentence's), where the robot is said to start, the floors the whole
mission stays on, and the safeguard that no phrase read is left out of the formula.

Sentences are independent goals (joined by AND), except that a sentence starting with *then*, *after
that*, *finally* ... continues the sequence of the previous one, and one starting with *before that* or
*first* (after a sentence with goals) comes before it; a sentence ending in *last* comes after all the
goals before it.
"""

from __future__ import annotations

from sgplan.errors import MissionError
from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.attachments import describes
from sgplan.llm.offline.grounding.discourse import Discourse, Grounded, Where
from sgplan.llm.offline.grounding.floors import floors_of
from sgplan.llm.offline.grounding.phrases import ground_phrase
from sgplan.llm.offline.meaning.compose import Clause, check_text_order, conj, moved
from sgplan.llm.offline.meaning.context import SentenceContext
from sgplan.llm.offline.meaning.contradiction import check_goal_not_forbidden
from sgplan.llm.offline.meaning.sentences import Meaning, read_sentence_body
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax import Reader, parse_sentence
from sgplan.llm.offline.syntax.any_time import LEAD_WORDS, any_time_said
from sgplan.llm.offline.syntax.context import is_time, times_of_parts
from sgplan.llm.offline.syntax.preamble import stated_start as said_start
from sgplan.llm.offline.syntax.reader import Match, Refusal
from sgplan.llm.offline.syntax.tree import (
    AfterAll,
    MissionSentence,
    PhraseList,
    PrefixedSentence,
    RelativeFloor,
    SetAside,
    StatedStart,
    StayOnFloor,
    nodes,
)
from sgplan.llm.offline.tasks import Step
from sgplan.logic.formula import Always, Atom, Formula, atoms


def mission_formula(readers: list[Reader], disc: Discourse) -> Formula:
    """The formula of the mission whose sentences are ``readers`` (see the module docstring)."""
    for r in readers:
        start = said_start(r)
        if start is not None:
            stated_start(start, disc)
    correction = taken_back(readers)
    if correction is not None:  # "go to the kitchen, sorry, I mean the office": which part stands?
        rf.refuse(rf.self_correction(correction))
    times = [r.quote(0, len(r)) for r in readers if r.aside and is_time(r, 0, len(r))
             and r.words != ("today",)  # "Right now, ...": no time; "Morning: ..." heads a part
             and (r.words not in lx.NOW_SAID or heads_a_colon(r))]
    if len(times) > 1:  # "Before dinner, A. After dinner, B.": an order of times, which no formula keeps
        rf.refuse(rf.times_in_order(times))
    headed = times_of_parts(readers)  # "Jobs before lunch: A. Jobs after lunch: B."
    if len(headed) > 1:
        rf.refuse(rf.times_in_order(headed))
    check_brought_to_speaker(readers)
    disc.confined = confinement(readers, disc)
    parts: list[Meaning] = []
    listed: dict[int, list[MissionSentence]] = {}
    run: list[Clause] = []  # the clauses of the list items in no order read last
    for r in readers:
        parsed = parse_sentence(r, lambda a: describes(a, disc))
        if isinstance(parsed, Refusal):
            rf.refuse(parsed.message)
        assert parsed is not None
        if isinstance(parsed.node, SetAside):
            set_aside(parsed.node, disc)
        if isinstance(parsed.node, MissionSentence):
            if parsed.node.announced is not None:
                listed.setdefault(parsed.node.announced.at, []).append(parsed.node)
            join(parsed.node, parts, disc, run, any_time=any_time_said(r, r.skip(0, LEAD_WORDS), len(r)))
    for said in listed.values():
        check_count(said)
    check_time_after_goals(readers, disc)
    for part in parts:
        if isinstance(part, Clause):
            check_text_order(part, disc.said)
    formulas = [p.formula() if isinstance(p, Clause) else p for p in parts]
    present = [f for f in formulas if f is not None]
    if not present:
        rf.refuse(rf.no_goal_at_all(disc.set_aside))
    formula = conj(present)
    check_left_by_no_goal(readers, disc)
    check_goal_not_forbidden(formula, disc.vocab)  # "A, then the kitchen, then, actually skip the kitchen"
    check_all_used(formula, disc.references)
    check_choice_remarks(disc)
    return formula


def check_time_after_goals(readers: list[Reader], disc: Discourse) -> None:
    """Refuse a time set aside that opens with *after* / *once* / *when* between goals (*Check the fridge, and
    after lunch, go to the office*): what follows it may come after the goals before it (*later*), or at any
    time.
    Closing the goals' own clause (*check the oven after the match*), it only says when."""
    goals = [g for g in disc.references if g.role == "goal" and g.entities]
    for r in readers:
        if (r.aside and r.toks and r.word(0) in ("after", "once", "when") and is_time(r, 0, len(r))
                and any(g.start < r.toks[0].start for g in goals)
                and any(g.start >= r.toks[-1].end for g in goals)):
            rf.refuse(rf.time_after_goals(r.quote(0, len(r))))


def check_brought_to_speaker(readers: list[Reader]) -> None:
    """Refuse *bring me X* when words set aside say where the speaker is (*I'm lying on the couch. Could you
    bring me the bottle ...*): the thing is wanted there, a goal the set-aside words hold (elsewhere *bring
    me X* is read as getting X, the speaker's place being unknown)."""
    placed = next((r for r in readers if r.aside and any(
        r.at(k, "i", "am") and any(r.head(j) is not None for j in range(k, len(r))) for k in range(len(r)))),
        None)
    brought = next((r for r in readers if not r.aside and any(
        w in ("bring", "bringing") and r.word(k + 1) == "me" for k, w in enumerate(r.words))), None)
    if placed is not None and brought is not None:
        rf.refuse(rf.brought_to_speaker(placed.quote(0, len(placed))))


def check_left_by_no_goal(readers: list[Reader], disc: Discourse) -> None:
    """Refuse words set aside that say where a person left something, by an object that no goal is, in a room
    the mission goes to (*Go to the kitchen - I think I left the charger by the microwave*): the object may be
    where to look there, a goal the set-aside words hold. Said by a goal's kind (*check the couch, I left my
    wallet by the couch*), by *there*, or by a place the mission does not go to (*My son forgot his book in
    the bedroom. Check the couch.*), they add nothing."""
    goals = {e for g in disc.references if g.role == "goal" for e in g.entities}
    kinds = {e.category for e in goals}
    rooms = {e.key for e in goals if e.kind == "room"} | {e.room_key for e in goals if e.kind == "object"}
    for r in readers:
        left = next((k for k, w in enumerate(r.words) if w in lx.LEFT_THERE), None) if r.aside else None
        at = next((j for j in range(left + 1, len(r)) if r.word(j) in lx.LOCATIVE
                   or r.words[j - 1:j + 1] == ("next", "to")), None) if left is not None else None
        place = r.head(r.skip(at + 1, lx.DETERMINERS)) if at is not None else None  # "by the microwave"
        if place is not None and place.kind == "object" and not place.categories & kinds and any(
                e.category in place.categories and e.room_key in rooms for e in disc.vocab.entities):
            rf.refuse(rf.left_by_no_goal(r.quote(0, len(r))))


def said_one_by_one(group: Clause, order: Clause) -> bool:
    """Whether the sentence ``order`` (opening with *Start with*, *First*) names one by one every member of
    the one group the sentence before it asked for, each of them (*Could you water the plants? Start with
    the one in the bathroom, then the one in the bedroom, and lastly the one in the other bathroom.*): the
    order of that group, not more visits after it."""
    steps = group.filled()
    if len(steps) != 1 or len(steps[0]) != 1 or steps[0][0].mode != "all" or len(steps[0][0].members) < 2:
        return False
    named = {primary(m) for step in order.filled() for task in step for m in task.members}
    return {primary(m) for m in steps[0][0].members} <= named


def primary(member: Formula) -> str:
    """The proposition a goal member is about (its object, not the room that locates it)."""
    names = list(atoms(member))
    return next((n for n in names if n.startswith("reach(")), names[0])


def check_choice_remarks(disc: Discourse) -> None:
    """Refuse a remark set aside that leaves a choice of a kind no goal names, nor the room of one (*have a
    seat at the dining room table, any chair's fine*: the chairs were meant, the table was read; *Either
    bathroom's fine, just check a toilet* is the toilets' rooms), or that names other places, which narrow
    the choice (*a vase - any vase in the dining room or the living room will do*)."""
    entities = [e for g in disc.references if g.role == "goal" for e in g.entities]
    goals = {e.category for e in entities} | {disc.vocab.by_key[e.room_key].category for e in entities
                                              if e.kind == "object" and e.room_key in disc.vocab.by_key}
    for said in disc.set_aside:
        words = said.lower().replace("'", " '").rstrip(".!").split()
        remark = words[:1] and words[0] in lx.REMARK_CHOOSERS and words[-1] in lx.REMARK_ENDS
        head = disc.vocab.nouns.match(words, 1) if remark else None
        if head is not None and head.categories and not head.categories & goals:
            rf.refuse(rf.choice_of_no_goal(said, words[1]))
        places = range(1 + head.words, len(words)) if head is not None else range(0)
        if any(disc.vocab.nouns.match(words, k) for k in places):
            rf.refuse(rf.choice_narrowed_aside(said))  # "a vase - any vase in the dining room will do"


def join(sentence: MissionSentence, parts: list[Meaning], disc: Discourse, run: list[Clause], *,
         any_time: bool = False) -> None:
    """Read ``sentence`` and join it to the sentences before it (``parts``); ``run``: the clauses of the list
    items in no order read right before it (updated); ``any_time``: the sentence says *at some point*."""
    if sentence.after_all is not None:
        check_after_all(sentence.after_all, parts)
    precedes = sentence_precedes(sentence, parts)
    continues = sentence.lead.sequence or sentence.after_item
    if continues and len(run) > 1:
        after_list_items(run, parts, disc.said(sentence.span.start, sentence.span.end))
    previous = previous_clause(parts)
    ctx = SentenceContext(disc, sentence.span.start, strict_pending=sentence.lead.strict,
                          waypoint_pending=sentence.lead.waypoint,
                          listed=(sentence.announced is not None and not sentence.marked)
                          or sentence.order_free)
    disc.announced = sentence.announced.head if sentence.announced is not None else None
    if sentence.floor_scope is not None:  # "While you're upstairs, ...": its goals there
        ctx.floor_scope = (floors_of(sentence.floor_scope, disc), sentence.span.start)
    ctx.prior_steps = previous.steps if continues and previous is not None else []
    known = len(disc.references)
    result = read_sentence_body(sentence.body, ctx)
    if sentence.announced is not None and sentence.announced.head is not None:
        check_announced(disc.references[known:], sentence.announced.head, sentence.announced.said)
    if sentence.opener and not (isinstance(result, Clause) and not any(result.steps) and result.constraints
                                and all(isinstance(c, Always) for c in result.constraints)):
        rf.refuse(rf.whole_mission_opener(sentence.opener))
    if ctx.said_last and not continues and not precedes and previous is not None:
        continues = True  # "Go to the office last.": after the goals of the sentences before
        if len(run) > 1:  # "- A - B - C  Do C last.": after every item of the list
            after_list_items(run, parts, disc.said(sentence.span.start, sentence.span.end))
            previous = previous_clause(parts)
    if (isinstance(result, Clause) and not any(result.steps) and not result.constraints and previous
            and sentence.says_order and len(previous.filled()) > 1):
        rf.refuse(rf.order_after_ordered_goals())
    first = (isinstance(result, Clause) and any(result.steps)
             and (ctx.said_first or said_first(sentence, parts)))
    if not continues and not precedes and in_visit_of_its_room(result, parts, ctx):
        return  # "A, then the kitchen, then B. In the kitchen, check the microwave.": on that visit
    if continues and parts and previous is None:  # after a rule or a constraint: the order would be lost
        rf.refuse(rf.follows_nothing(disc.said(sentence.span.start, sentence.span.end)))
    if (precedes and previous is None and parts and isinstance(result, Clause)
            and all(isinstance(p, Always) for p in parts) and sentence.precedes is not None
            and "before" not in sentence.precedes.lower().split()):
        parts.append(result)  # "Whenever X, Y afterwards. First, Z.": only standing rules before: no goal
    elif precedes:
        if previous is None or not isinstance(result, Clause):
            rf.refuse(rf.precedes_needs_goals())
        if said_one_by_one(previous, result):  # "Water the plants? Start with the one in A, then ..."
            previous.steps[:] = moved(result.steps)
        else:
            previous.steps[0:0] = moved(result.steps)
        previous.constraints.extend(result.constraints)
    elif continues and previous is not None and isinstance(result, Clause):
        previous.steps.extend(result.steps)
        previous.constraints.extend(result.constraints)
    elif isinstance(result, Clause) and (sequence := last_sequence(parts)) is not None and resumes(
            sentence, result, sequence, disc):
        sequence.steps.extend(result.filled()[1:])  # "A, then B. After B, C.": that visit of B, then C
        sequence.constraints.extend(result.constraints)
    elif (isinstance(result, Clause) and disc.first_said is not None and not any_time
          and new_goals(sentence, disc)):
        after_first(result, parts, disc.first_said)  # "First, go to A. Check B.": B after A
    else:
        parts.append(result)
    if first and disc.first_said is None:
        disc.first_said = disc.said(sentence.span.start, sentence.span.end)
    if isinstance(result, Clause) and any(result.steps):
        disc.last_step, disc.last_steps = result.filled()[-1], len(result.filled())
    in_no_order = sentence.marked and not sentence.after_item and bool(parts) and parts[-1] is result
    run[:] = [*run, result] if in_no_order and isinstance(result, Clause) else []


def previous_clause(parts: list[Meaning]) -> Clause | None:
    """The sentence before, which a sentence of *then*, *last* or *before that* goes on from: the last one
    when it is a clause, or across sentences of prohibitions only (no goal: *A. Avoid X. Then B.*, B after A)
    the last one with goals; ``None`` after a rule (refused there: the order would be lost)."""
    if not parts or not isinstance(parts[-1], Clause):
        return None
    for part in reversed(parts):
        if not isinstance(part, Clause):
            break
        if part.filled():
            return part
    return parts[-1]


def in_visit_of_its_room(result: Meaning, parts: list[Meaning], ctx: SentenceContext) -> bool:
    """Whether ``result``, a sentence of one step in the room it opens with (*In the kitchen, check the
    microwave.*, a note's *kit: microwave*), was joined to the one visit of that room in a sequence said
    before it (*chair before kit*: the microwave after the chair, as the kitchen is; read on its own, the
    microwave could come first). A visit is the room as a goal of its own (not an object in it: *the fridge,
    then the couch. Kitchen: the oven* stays in no order). Several visits of the room in sequences before it
    are refused (which one?); no visit leaves the sentence on its own."""
    if not ctx.scope or not isinstance(result, Clause) or len(result.filled()) != 1:
        return False
    rooms = [Atom(f"enter({e.key})") for e in ctx.scope]
    visits = [(part, step) for part in parts if isinstance(part, Clause) and len(part.filled()) > 1
              for step in part.filled() if any(room in t.members for t in step for room in rooms)]
    if len(visits) > 1:
        rf.refuse(rf.which_visit_of_scope(", ".join(e.key for e in ctx.scope)))
    if not visits:
        return False
    part, step = visits[0]
    step.extend(result.filled()[0])
    part.constraints.extend(result.constraints)
    return True


def after_list_items(run: list[Clause], parts: list[Meaning], said: str) -> None:
    """*- A - B* (a list in no order), then *Then C* or *Do C last.* (a line or an item of its own): C comes
    after every item, as after *A and B.*; the items, the last parts, are joined into one clause whose one
    step holds their goals (an item may only keep out of a place). Refused when an item has steps of its own
    (after all of them, or after the last?)."""
    if any(len(c.filled()) > 1 for c in run) or parts[-len(run):] != run:
        rf.refuse(rf.after_all_of_sentences(said))
    joined = Clause([[task for c in run for step in c.filled() for task in step]],
                    [f for c in run for f in c.constraints])
    parts[-len(run):] = [joined]


def check_after_all(said: AfterAll, parts: list[Meaning]) -> None:
    """*After all that, X.* / *Once you've done both, X.*: X comes after every goal of the sentence before
    (:func:`join` continues its sequence), which must be the only one with goals (else: after which?) and
    name as many goals as a number said."""
    has_goals = [p for p in parts if not isinstance(p, Clause) or any(p.steps)]
    if not has_goals:
        rf.refuse(rf.after_all_of_nothing(said.said, sentence=False))
    if len(has_goals) > 1 or has_goals[0] is not parts[-1] or not isinstance(has_goals[0], Clause):
        rf.refuse(rf.after_all_of_sentences(said.said))
    goals = has_goals[0].goal_count()
    if said.number is not None and said.number != goals:
        rf.refuse(rf.after_all_count(said.said, goals, said.number, sentence=False))


def set_aside(said: SetAside, disc: Discourse) -> None:
    """Words set aside: said back; the rooms and objects they name are kept as mentions (each grounded on its
    own; one that names nothing here is left out)."""
    disc.put_aside(said.said)
    for phrase in said.mentions:
        try:
            named = ground_phrase(phrase, Where("qualifier"), disc.fork())
        except MissionError:
            continue  # a phrase that names nothing here: nothing to point back to
        disc.mentions.append(named)


def check_count(sentences: list[MissionSentence]) -> None:
    """The number an announcement said (*three things:*) must be the number of phrases of its list (one
    sentence, or the items of a numbered or bulleted list)."""
    announced = sentences[0].announced
    assert announced is not None
    items = sum(len(found.items) for s in sentences for found in nodes(s.body, PhraseList))
    if announced.count is not None and items != announced.count:
        rf.refuse(rf.announced_count(announced.said, announced.count, items))


def check_announced(phrases: list[Grounded], head: Head, said: str) -> None:
    """Every phrase of a list announced as *two rooms:* / *these plants:* must be such a room or object."""
    for g in phrases:
        if g.role != "qualifier" and any(e.kind != head.kind or (head.categories and e.category not in
                                                                 head.categories) for e in g.entities):
            rf.refuse(rf.not_announced(g.phrase, said))


def sentence_precedes(sentence: MissionSentence, parts: list[Meaning]) -> bool:
    """Whether a sentence starting with *before that* or *first* comes before the previous one (it does
    after a sentence with goals); refused when it is not clear before which goals."""
    if sentence.precedes is None:
        return False
    said = sentence.precedes.rstrip(" ,")
    has_goals = [p for p in parts if not isinstance(p, Clause) or any(p.steps)]
    if not said.lower().endswith("before that") and not has_goals:
        return False  # "First, go to X": a first sentence
    if len(has_goals) != 1 or (said.lower().startswith("before") and isinstance(has_goals[0], Clause)
                               and len(has_goals[0].filled()) > 1):
        rf.refuse(rf.precedes_which(sentence.precedes))
    return True


def after_first(result: Clause, parts: list[Meaning], first_said: str) -> None:
    """Join ``result``, a sentence of goals in no order with the ones before it, after the goals said *first*
    (:attr:`.Discourse.first_said`), as more goals of the step after them: *First, go to the garage. Check
    the keyboard.* is the garage, then the keyboard; *Go to A first and then B. Check C.* is A, then B and
    C in any order. Refused when ``result`` is a sequence of its own, or the steps after the first goals are
    more than one (after which of them?)."""
    first = next(p for p in parts if isinstance(p, Clause) and p.filled())
    filled, steps = first.filled(), result.filled()
    if len(steps) != 1 or len(filled) > 2 or (len(filled) == 2 and first.steps[-1] is not filled[1]):
        rf.refuse(rf.after_first_sentence(first_said))
    if first.steps[-1] is filled[0]:
        first.steps.append([])
    first.steps[-1].extend(steps[0])
    first.constraints.extend(result.constraints)


def new_goals(sentence: MissionSentence, disc: Discourse) -> bool:
    """Whether ``sentence`` names a goal not named before it (not only *until then*, *before you finish the
    laptop* about goals said already)."""
    before = {e.key for g in disc.goals_before(sentence.span.start) for e in g.entities}
    return any(not {e.key for e in g.entities} <= before for g in disc.goals_before(sentence.span.end)
               if g.start >= sentence.span.start)


def said_first(sentence: MissionSentence, parts: list[Meaning]) -> bool:
    """Whether ``sentence`` opens with *first* (*First, go to the garage.*) with no goal said before it."""
    return (sentence.precedes is not None and sentence.precedes.split()[0].lower().strip(",") in lx.FIRST
            and not any(not isinstance(p, Clause) or any(p.steps) for p in parts))


def last_sequence(parts: list[Meaning]) -> Clause | None:
    """The last sentence with goals among ``parts`` (sentences of prohibitions or rules after it skipped:
    *A, then B. Stay out of X. After B, C.*)."""
    return next((p for p in reversed(parts) if isinstance(p, Clause) and p.filled()), None)


def resumes(sentence: MissionSentence, result: Clause, previous: Clause, disc: Discourse) -> bool:
    """Whether ``sentence`` is *After X, Y* with X the last step of the sequence before (*Go to A, then B.
    After B, C.*): Y goes on from that visit of X. Refused when X is an earlier step of that sequence (its
    place against the steps after X is not said)."""
    body = sentence.body
    if not isinstance(body, PrefixedSentence) or body.prefix_last or body.strict or len(result.filled()) < 2:
        return False
    after = same_goals(result.filled()[0])
    done = [same_goals(step) for step in previous.filled()]
    if len(done) > 1 and after in done[:-1]:
        rf.refuse(rf.after_a_middle_step(disc.said(sentence.span.start, sentence.span.end)))
    return bool(done) and (after == done[-1] or names_every_goal(result.filled()[0], previous.filled()))


def names_every_goal(step: Step, steps: list[Step]) -> bool:
    """Whether ``step`` is one task naming each goal of ``steps``, all of them one thing each (*the one in the
    living room, then the one in the office. When you're done with the plants, ...*: after both)."""
    if len(steps) < 2 or len(step) != 1 or step[0].mode != "all" or step[0].avoid:
        return False
    goals = [task.members[0] for s in steps for task in s if len(task.members) == 1]
    if len(goals) != sum(len(s) for s in steps):
        return False
    return sorted(map(goal_thing, goals)) == sorted(map(goal_thing, step[0].members))


def goal_thing(member: Formula) -> str:
    """The thing a goal is about, whatever room it was said in (``reach(object_24)`` of ``reach(object_24) &
    enter(room_6)``)."""
    names = atoms(member)
    return next((n for n in names if n.startswith("reach(")), names[0] if names else "")


def same_goals(step: Step) -> list[tuple[str, list[Formula], list[Formula]]]:
    """What a step asks for, to compare it with another (where it was said left out)."""
    return [(task.mode, task.members, task.avoid) for task in step]


def stated_start(start: StatedStart, disc: Discourse) -> None:
    """A sentence that only says where the robot is (*I'm downstairs right now*): the start floor, used by
    *upstairs*, *this floor* ...; refused when it contradicts the known start floor, or when *upstairs* /
    *downstairs* do not name one floor."""
    n = disc.vocab.num_floors
    if isinstance(start.floor, RelativeFloor):
        extreme = 0 if start.floor.word == "downstairs" else n - 1
        if n != 2 and disc.start_floor != extreme:
            rf.refuse(rf.stated_floor_unclear(start.floor.word, disc.vocab.building_name, n, extreme))
        floor = extreme
    else:
        floor = min(floors_of(start.floor, disc).floors)
    if disc.start_floor is not None and disc.start_floor != floor:
        rf.refuse(rf.stated_floor_contradicts(start.said, floor, disc.start_floor))
    disc.start_floor = floor


def taken_back(readers: list[Reader]) -> str | None:
    """The words with which the speaker takes back something said before them (:data:`.lexicon.CORRECTIONS`),
    or ``None``; those read as replacing a phrase (:mod:`.syntax.corrections`) are set aside."""
    for n, r in enumerate(readers):
        for k in range(len(r) if not r.aside else 0):
            said = r.phrase(k, lx.CORRECTIONS)
            if said is not None and (n or k):
                return r.quote(k, k + len(said))
    return None


def heads_a_colon(r: Reader) -> bool:
    """Whether the words of ``r`` were said before a colon (*Morning: ...*: a time heading, no greeting)."""
    return bool(r.toks) and r.text[r.toks[-1].end:].lstrip().startswith(":")


def confinement(readers: list[Reader], disc: Discourse) -> frozenset[int] | None:
    """The floors the whole mission is confined to by *stay on <floor>* / *don't leave <floor>* anywhere in
    it (read before the rest, so that "go to the toilet, staying on this floor" grounds *the toilet* on
    that floor); ``None`` when the mission says no such thing. A sentence with *until*, *before*, *if* ...
    confines nothing (the stay may be for part of the mission)."""
    confined: frozenset[int] | None = None
    for r in readers:
        if set(r.words) & lx.TIME_SCOPED:
            continue
        parsed = parse_sentence(r, lambda a: True)
        if not isinstance(parsed, Match):
            continue
        for stay in nodes(parsed.node, StayOnFloor):
            floors = floors_of(stay.floor, disc).floors
            confined = floors if confined is None else confined & floors
    return confined


def check_all_used(formula: Formula, phrases: list[Grounded]) -> None:
    """The second safeguard against a silently dropped clause (the first: every sentence is read to its
    end): every place the text names as a goal, a place to avoid or a condition must show up in the formula
    (qualifiers such as *the kitchen* in *the sink in the kitchen* only narrow another phrase; so does a floor
    gone to before the goals on it, *go down to floor 1 and check the couch*, when a goal is on it). A phrase
    that vanished is refused, named."""
    used = set(atoms(formula))
    floors_used = {e.floor for g in phrases for e in g.entities if e.action in used}
    for g in phrases:
        if g.floor and g.role == "goal" and any(e.floor in floors_used for e in g.entities):
            continue
        if g.role != "qualifier" and g.entities and not any(e.action in used for e in g.entities):
            rf.refuse(rf.dropped(g.phrase))
