"""Words that only give context, set aside before parsing: statements (*We're hosting dinner tonight.*, *The
plants are looking sad.*, *..., the floor's still wet*) and times (*Before lunch, ...*, *Tonight, ...*,
*... after dinner*).

People tell a robot why and when as well as what. Such words ask nothing a mission can require, so they
are not read; they are kept as :class:`.tree.SetAside` sentences, which the translator says back (*Not
part of the mission: 'We're hosting dinner tonight.'*): nothing is dropped silently. The rooms and objects
a statement names are kept as mentions, which *there* may point back to (*Grandpa's napping in the
bedroom, so stay out of there*).

Set aside are: a sentence or a comma clause (first or last of its sentence) that starts with a subject
(*I, we, it, there, the guests, my mum, Grandpa*) and a verb, unless it is a polite wrapper (*I need you
to ...*), says what is off limits (*the kitchen is off limits*), or states a need about a room or object of
the scene (*the plants need watering*: that may ask for a goal, and is refused by the parser); and a time of
day, meal or event opening or closing a sentence (*Before lunch,*, *... tonight*). A clock time is refused
(:func:`.reader.unreadable`). A subject is known by its shape: a pronoun, a phrase with a determiner, a
bare noun the grammar has no role for (*Laundry's done*, *people are asleep*), *things* / *stuff* /
*everything* naming nothing (*things are piling up*), *one of them* with a verb that neither says one will
do nor where it is (*..., one of them got knocked*), or a place and its state in a note (*office wet*).
Remarks (:data:`.lexicon.CLOSING`) around the context or closing the sentence are set
aside with it, and so is a sentence of praise only (*Perfect.*) or a bare apology before a statement that
names nothing (*Sorry, I forgot something.*), praise before a sign-off (*Lovely, thank you.*), a guess added
to a statement (*..., probably somewhere upstairs*) and a time of day opening an order without a comma
(*This evening stay ...*); a reason or a purpose after an order (*... as it needs charging*, *..., to rinse
off*) is set aside where it stands. After a statement that names one place, the pronoun of the order is
bound to it (:mod:`.stated_place`). A statement may open with notice (*Note that ...*) or be the speaker's
doubt without *I* (*Not sure if ...*). An apology about a room or object (*Sorry about the kitchen.*) and
a reason naming a place between an order and a pronoun (*..., because the kitchen is wet, avoid it*) are
refused.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.phrases import Phrases
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.preamble import stated_start
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.syntax.stated_place import BOUND_PRONOUNS, bind_statement_pronoun
from sgplan.llm.offline.syntax.tree import Described, NounPhrase
from sgplan.llm.offline.text import is_clock_time


def set_aside_context(readers: list[Reader]) -> list[Reader]:
    """``readers`` with the context of each sentence split off as readers set aside (see the module
    docstring)."""
    out: list[Reader] = []
    for k, r in enumerate(readers):
        if r.word(0) in _MEANWHILE and r.word(1) == "," and out and out[-1].aside and not r.aside:
            out.append(aside(r, 0, 1))  # "I'm expecting a call. Meanwhile, check ...": while I'm busy
            r = replace(r, toks=r.toks[2:])
        said_before = any(not o.aside for o in out)
        if not r.aside and (met_need(r, readers[k + 1:]) or kind_remark(r, out)):
            out.append(aside(r, 0, len(r)))  # "The vases need dusting. ... dust the vase in the hall ...
            continue
        out += [r] if r.aside or stated_start(r) is not None else split(r, said_before)
    return out


_MEANWHILE = frozenset({"meanwhile"})
"""*Meanwhile,* after words set aside (*I'll be busy for a while. Meanwhile, check ...*): while the speaker
does what they said, which asks nothing of the robot; elsewhere it is refused (while doing what?)."""


def kind_remark(r: Reader, before: list[Reader]) -> bool:
    """Whether the sentence ``r`` only remarks on the kind of a thing the orders before it named (*It's a
    fussy plant lol.*, *That's an old vase, mind.*): *it* / *that* / *this* and a verb of being, *a* / *an*,
    one or two words the translator does not know (the remark), the noun of a kind some order before it
    named as *the* one (*Check a vase. It's a pretty vase.* may say which to choose), and remarks only.
    Without such a word (*It's a vase.*: says what to look for), with a kind no order named, or with *the*
    (*It's the kitchen.*: a correction) it is left to the parser."""
    k = r.skip(0, lx.INTERJECTIONS)
    if (r.word(k) not in lx.DEICTIC_SUBJECTS or r.word(k + 1) not in ("'s", "is", "was")
            or r.word(k + 2) not in ("a", "an")):
        return False
    k += 3
    said = k
    while k < len(r) and k - said < 2 and r.word(k).isalpha() and r.word(k) not in lx.LEXICON_WORDS \
            and r.head(k) is None and not misspelt_name(r, k, k + 1):
        k += 1
    head = r.head(k) if k > said else None
    if head is None or not (k + head.words == len(r) or closing_only(r, k + head.words, len(r))):
        return False
    named = [h.categories for o in before if not o.aside
             for j in range(len(o)) if (h := o.head(j)) is not None and not negated(o, j)
             and (o.word(j - 1) in lx.DEFINITE or o.word(j - 1) in lx.POSSESSIVES)
             and not any(w in lx.CHOICE_WORDS or w in lx.UNIVERSAL for w in o.words)]
    return any(head.categories & other for other in named)


def negated(r: Reader, k: int) -> bool:
    """Whether a prohibition or a negation comes before the word at ``k`` in its sentence (*avoid the
    bathroom*, *never enter the kitchen*, *not the office*)."""
    return any(r.phrase(j, lx.NEG_STARTS) or r.word(j) in ("not", "no", "never", "without") for j in range(k))


def met_need(r: Reader, later: list[Reader]) -> bool:
    """Whether the sentence ``r`` only states a need about things of the scene (*The vases need dusting.*,
    *Mum's visiting so the vases need dusting.*) that the sentences after it name again as goals, each of its
    kinds (*... dust the vase in the bedroom*; not after a negation: *avoid the bathroom downstairs*): the
    orders say the work, the need only why. A need that nothing
    after it names (or only a pronoun does: *... dust them*) is left to the parser, which refuses it."""
    joins = [j for j in range(1, len(r))
             if r.word(j) in lx.STATEMENT_JOINERS and statement(r, 0, j) == "aside"]
    start = joins[0] + 1 if joins else 0
    end = time_tail(r, start, len(r)) or len(r)  # "... need a clean before the weekend"
    if (statement(r, start, end) != "need" or "," in r.words
            or any(w in lx.PRONOUNS or w in lx.WISH_STOPS for w in r.words[start:end])):
        return False
    kinds = [h.categories for j in range(start, end) if (h := r.head(j)) is not None]
    named = [h.categories for o in later if not o.aside
             for j in range(len(o)) if (h := o.head(j)) is not None and not negated(o, j)]
    return bool(kinds) and all(any(kind & other for other in named) for kind in kinds)


def split(r: Reader, said_before: bool = False) -> list[Reader]:
    """A sentence, its leading and trailing context clauses set aside, and the times said between its
    clauses; ``said_before``: sentences with content came before it (then *it* after a statement that names
    a room or object could be read as what they named last: not set aside, so refused)."""
    if said_before and r.says(lx.CORRECTIONS, 0, len(r)):
        # "Oh, I meant the kitchen": takes back what was said before (corrections.py reads or refuses it);
        # "Sorry, I forgot something.": an apology before a statement that names nothing, said back
        return [aside(r, 0, len(r))] if apology(r) else [r]
    people_at = event_of_people_at_place(r)
    if people_at is not None:  # "after the kids are at the couch": never the couch as a goal
        rf.refuse(rf.event_of_people_at_place(r.quote(*people_at)))
    praise = [w for w in r.words if w.isalpha()]
    if praise and all(w in lx.PRAISE or w in lx.HESITATIONS for w in praise):
        return [aside(r, 0, len(r))]  # "Perfect.", "Cool cool.": a sentence of praise only, said back
    if event_note(r, 0, len(r)) or is_time(r, 0, len(r)) or chore_note(r):
        return [aside(r, 0, len(r))]
    heading = None if said_before else before_you_start(r)  # (after an order: before which step?)
    if heading is not None:  # "Before you start: the carpet is wet, so ...": the rest read on its own
        rest = replace(r, toks=r.toks[heading:])
        return [aside(r, 0, heading - 1), *(split(rest) if rest.words else [])]
    clauses = comma_clauses(r)
    for a, b in clauses:
        tail = time_tail(r, a, b)  # "turn off the oven when the timer goes off": closing the clause
        for k in (a, *((tail,) if tail is not None else ())):
            if waits_for_an_end(r, k, b):  # "switch the TV off once the match has finished": when is that?
                rf.refuse(rf.wait_for_an_end(r.quote(k, b)))
        if (r.word(a) in lx.APOLOGY_WORDS and r.word(a + 1) in ("for", "about")
                and any(r.head(k) is not None for k in range(a, b))):  # "Sorry about the kitchen."
            rf.refuse(rf.apology_about_place(r.quote(a, b)))
    if closing_only(r, 0, len(r)):
        return [aside(r, 0, len(r))]  # "Thanks a lot!", "Lovely, cheers.": a sign-off, said back
    opening = replace(r, toks=r.toks[:clauses[0][1]])
    if len(clauses) > 1 and stated_start(opening) is not None:  # "I'm on the middle floor - stay on it, ..."
        return [opening, *split(replace(r, toks=r.toks[skip_joiner(r, clauses[1][0]):]), said_before)]
    first, last = 0, len(clauses)
    while first < last and (is_context(r, *clauses[first], leading=True) or closing_only(r, *clauses[first])
                            or caution(r, *clauses[first])
                            or (first > 0 and hedged_addition(r, *clauses[first]))
                            or (first == 0 and praise_before_order(r, *clauses[0]))):
        first += 1
    while last > first and (is_context(r, *clauses[last - 1], leading=False)
                            or closing_only(r, *clauses[last - 1]) or manner_only(r, *clauses[last - 1])):
        last -= 1  # "..., the cat's asleep in there", "..., okay?", "..., sorry about this": said back
    if first == last or (first > 0 and mere_talk(r, clauses[first][0], clauses[last - 1][1])):
        return [aside(r, 0, len(r))]
    if first and r.word(clauses[first - 1][0]) in lx.CAUTIONS and caution_on_place(r, *clauses[first]):
        rf.refuse(rf.caution_not_goal(r.quote(clauses[first - 1][0], clauses[first][1])))
    named = mentions(aside(r, 0, clauses[first - 1][1])) if first else ()
    start = skip_joiner(r, clauses[first][0]) if first else 0
    # "check the laptop before dinner, then ...", "the kitchen because the coffee's in there, then ..."
    middle = [c for c in clauses[first:last] if is_time(r, *c) or is_reason(r, *c) or counted(r, *c)
              # the "later" of "While you're in X later, ..." opening the mission (after a goal: "after" it?)
              or (not said_before and c[0] > 0 and while_later(r, 0, c[1]) == c[0])
              or (c != clauses[first] and (aside_between(r, *c) or closing_only(r, *c)))]
    words = [k for k in range(start, clauses[last - 1][1])
             if not any(a <= k < b or (k == a - 1 and r.word(k) == ",") for a, b in middle)]
    naming = [(a, b) for a, b in middle if any(r.head(k) is not None for k in range(a, b))]
    pronoun = next((k for k in words if naming and k > naming[0][0] and r.word(k) in lx.PRONOUNS), None)
    if pronoun is not None:  # "check the oven, because the kitchen is wet, avoid it": which is 'it'?
        rf.refuse(rf.reason_before_pronoun(r.quote(*naming[0]), r.word(pronoun)))
    subject = skip_joiner(r, r.skip(clauses[first - 1][0], lx.INTERJECTIONS)) if first else 0
    order = bind_statement_pronoun(r, subject, [clauses[first][0], *words], named) if first else None
    if order is not None:
        refuse_stated_there(r, subject, clauses[first - 1][1], order)
    floors = [k for k in range(clauses[0][0], clauses[first - 1][1])
              if r.word(k) in lx.RELATIVE_FLOORS or r.word(k) in lx.FLOOR_WORDS] if first else []
    if floors and order is None and not named:
        order = bind_floor_there(r, floors, words)
    pronouns = lx.PRONOUNS if named else BOUND_PRONOUNS if floors else ()
    if order is None and said_before and any(w in pronouns for w in r.words[clauses[first][0]:]):
        # "the lobby floor is wet, so avoid it", "the kids are upstairs, so don't go down there": 'it' /
        # 'there' would be the goal named last: refused
        return [r]
    kept = [aside(r, clauses[0][0], clauses[first - 1][1])] if first else []
    kept += [order or replace(r, toks=tuple(r.toks[k] for k in words))] + [aside(r, a, b) for a, b in middle]
    if last < len(clauses):
        refuse_left_there(r, clauses[last][0], words)
        kept.append(aside(r, clauses[last][0], len(r)))
    return kept


def refuse_stated_there(r: Reader, subject: int, end: int, order: Reader) -> None:
    """Refuses the order bound to what the statement ``[subject, end)`` names when the statement puts it
    *there* (*... head up to the office. I left my laptop up there, so check on it*): on that visit, or at any
    time?"""
    if "there" in r.words[subject:end] and "there" not in order.words:
        rf.refuse(rf.stated_there_order(r.quote(subject, end)))


def refuse_left_there(r: Reader, start: int, order: list[int]) -> None:
    """Refuses a statement from ``start`` after the order's words ``order`` that a thing is *there* where the
    order goes (:func:`left_there_after`: *pop up to the office, I think I left my laptop open there*: the
    laptop?)."""
    thing = left_there_after(r, start, order)
    if thing is not None:
        rf.refuse(rf.thing_left_there(r.quote(start, len(r)), r.quote(*thing)))


def left_there_after(r: Reader, start: int, order: list[int]) -> tuple[int, int] | None:
    """The words of the object of the scene said in a statement from ``start`` that a person left it *there*,
    or that it is there (*..., I think I left my laptop open there*, *..., my laptop is there*), when the
    order's words ``order`` do not name its kind; ``None`` otherwise."""
    things = [k for k in range(start, len(r)) if (h := r.head(k)) is not None and h.kind == "object"]
    if not things or "there" not in r.words[things[0]:] or not any(
            w in lx.LEFT_THERE or w in _BE_HAVE for w in r.words[start:]):  # "..., my laptop is there"
        return None
    if any(w in ("not", "never", "no") for w in r.words[start:]):
        return None  # "..., my laptop is not there": no goal it could be
    head = r.head(things[0])
    assert head is not None
    named = any((h := r.head(k)) is not None and h.categories & head.categories for k in order)
    return None if named else (things[0], things[0] + head.words)


def bind_floor_there(r: Reader, floors: list[int], order: list[int]) -> Reader | None:
    """The order (the token indexes ``order`` of ``r``) with its *up there* / *down there* replaced by the one
    floor word the statement before it names (at ``floors``: *the kids are upstairs, so don't go up there*:
    upstairs), when they agree (*up*: *upstairs*) and the order names nothing else; ``None`` otherwise
    (refused)."""
    there = [k for k in order if r.word(k) in BOUND_PRONOUNS or r.word(k) in lx.PRONOUNS]
    if len(floors) != 1 or len(there) != 1 or r.word(there[0]) != "there" or any(
            r.head(k) is not None for k in order):
        return None
    floor, k = floors[0], there[0]
    if lx.RELATIVE_FLOORS.get(r.word(floor)) != {"up": 1, "down": -1}.get(r.word(k - 1)):
        return None
    return replace(r, toks=tuple(r.toks[floor] if j == k - 1 else r.toks[j] for j in order if j != k))


_DONE_TASKS = frozenset({"all", "both", "those", "these", "that", "this", "it", "them", "they", "everything",
                         "three", "two", "four", "jobs", "tasks", "chores"})
"""Words of what the robot has done (*when all three are done*): its own goals, never an event to wait for."""


def waits_for_an_end(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is the end of an event of others (*once the match has finished*,
    *when the film is over*, *after the washing machine stops*, *when the timer goes off*): what it closes or
    opens must wait for something the robot can neither sense nor plan for (refused); the robot's own (*once
    you have finished*) is an order."""
    words = r.words[start + 1:end]
    if r.word(start) not in ("once", "when", "after") or r.word(start + 1) in lx.PEOPLE | {"you"} or any(
            w in lx.EVENT_WORDS or w in _DONE_TASKS for w in words):
        return False  # "once breakfast is over": a time of day, set aside; "when all three are done": goals
    return any(r.at(k, *said) and k + len(said) == end and k > start + 1
               for k in range(start + 2, end) for said in lx.EVENT_ENDS)


def caution(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is only a caution without its verb (*Careful*, *careful now*)."""
    return end - start in (1, 2) and r.word(start) in lx.CAUTIONS and r.word(end - 1) in ("careful", "now")


def caution_on_place(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` after a caution (*Careful, the office.*) is only a place, with no
    order and no statement of it: the warning may be about that place, or a goal; refused."""
    return r.np_starts(start) and not starts_order(r, start) and not any(
        r.word(k) in lx.COPULAS or r.phrase(k, lx.OFF_LIMITS) or finite_verb(r.word(k))
        for k in range(start, end))


def apology(r: Reader) -> bool:
    """Whether the sentence is a bare apology word (*sorry*, *oops*) and a comma before a statement that
    names nothing and says nothing of what was meant (*Sorry, I forgot something.*): no room, object, floor,
    pronoun, number or word of correcting (:data:`.lexicon.CORRECTING_WORDS`)."""
    if r.word(0) not in lx.APOLOGY_WORDS or r.word(1) != "," or statement(r, 2, len(r)) != "aside":
        return False
    return not any(r.head(k) is not None or w in lx.ANAPHORIC_ONE
                   or ((w in lx.PRONOUNS or w in lx.DEICTIC_SUBJECTS) and not judged_request(r, k))
                   or w in lx.RELATIVE_FLOORS or w in lx.FLOOR_WORDS or w in lx.NUMBER_WORDS or w.isdigit()
                   or w in lx.CORRECTING_WORDS or r.phrase(k, lx.CORRECTIONS)
                   for k, w in enumerate(r.words[2:], 2))


_JUDGEMENTS = frozenset({"a", "an", "bit", "little", "kind", "of", "sort", "odd", "weird", "strange", "silly",
                         "random", "fussy", "picky", "lot", "much", "request", "ask"})
"""The words of a speaker's judgement of their own request (*it's a bit odd*, *it's a weird request*); kept
out of the lexicon (its words are no words of the grammar)."""
_JUDGING = frozenset({"'s", "is", "sounds", "seems", "looks"})


def judged_request(r: Reader, k: int) -> bool:
    """Whether the *it* / *that* at ``k`` is the request judged in the words that close the sentence (*Sorry,
    I know it's a bit odd.*), not a thing: *'s* / *is* / *sounds* and only words of :data:`_JUDGEMENTS` after
    it, to the end of its clause."""
    end = next((j for j in range(k + 2, len(r)) if r.word(j) == ","), len(r))
    return (r.word(k) in ("it", "that", "this") and r.word(k + 1) in _JUDGING and end > k + 2
            and all(w in _JUDGEMENTS for w in r.words[k + 2:end]))


def comma_clauses(r: Reader) -> list[tuple[int, int]]:
    """The ``[start, end)`` of the clauses between the commas of ``r``, and before *so* / *but* followed by
    an order (*my son is asleep upstairs so don't go up there*); a time expression closing a clause is a
    clause of its own (*go to the kitchen tonight*, *check the laptop before dinner, then ...*), also before
    a reason (*check the fridge before lunch so I know what to cook*) or *and* / *then* (*make the beds this
    morning and don't leave this floor*)."""
    cuts = [k for k, w in enumerate(r.words) if w == ","]
    joins = [k for k, w in enumerate(r.words) if w in lx.ORDER_JOINERS and k and r.word(k - 1) != ","
             and (starts_order(r, k + 1) or said_after_joiner(r, k))]
    starts = sorted({0, *(c + 1 for c in cuts), *joins})
    ends = sorted({*cuts, *joins, len(r)})
    out: list[tuple[int, int]] = []
    for start, end in zip(starts, ends):
        head = time_head(r, start, end)
        if head is not None:  # "This evening stay on this floor", "Tonight check the oven"
            out.append((start, head))
            start = head
        joined = next(((j, t) for j in range(start + 2, end) if r.word(j) in ("and", "then")
                       and starts_order(r, r.skip(j + 1, ("and", "then")))
                       and (t := time_tail(r, start, j)) is not None), None)
        if joined is not None:  # "make both beds this morning and don't leave this floor": the time, then
            out += [(start, joined[1]), (joined[1], joined[0])]  # the order goes on after "and"
            start = joined[0]
        tail = time_tail(r, start, end)
        reason = reason_span(r, start, end)
        if reason is not None and tail is not None and tail > reason[0]:
            tail = None  # "..., since we need milk for the morning": the reason's own time
        reason = reason if tail is None else None
        timed = time_tail(r, start, reason[0]) if reason is not None else None
        if timed is not None:  # "check the fridge before lunch so I know what to cook": the time, then why
            out.append((start, timed))
            start = timed
        out += ([(start, tail), (tail, end)] if tail is not None
                else [(start, reason[0]), reason, (reason[1], end)] if reason is not None else [(start, end)])
    return [(a, b) for a, b in out if b > a]


def said_after_joiner(r: Reader, k: int) -> bool:
    """Whether the words after *so* / *but* at ``k`` (to the next comma) are no statement and no reason, so
    that they may be an order in any words (*the dog's in the kitchen so leave it alone*, *... so upstairs is
    off limits*): a clause of their own, read or refused, never set aside with the statement before them."""
    end = next((j for j in range(k + 1, len(r)) if r.word(j) == ","), len(r))
    return (end > k + 1 and r.phrase(k, lx.REASONS) is None and statement(r, k + 1, end) is None
            and not mere_talk(r, k + 1, end))


def reason_span(r: Reader, start: int, end: int) -> tuple[int, int] | None:
    """The reason a clause gives for its order (*... because the coffee's in there*, *... so I know you made
    it*, *... to make sure they're sturdy*): from the reason word to the clause's end or its next *then*;
    ``None`` when there is none, or when it says what not to do or asks something (*because I need you to
    ...*: left to the parser)."""
    k = next((k for k in range(start, end) if r.phrase(k, lx.REASONS) or purpose(r, k, end)
              or purpose_infinitive(r, k, end) or after_order_reason(r, k)), None)
    if k is None:
        return None
    stop = next((j for j in range(k + 1, end) if r.phrase(j, lx.SEQ_WORDS)), end)
    said = range(k + len(r.phrase(k, lx.REASONS) or r.phrase(k, lx.AFTER_ORDER_REASONS)
                        or r.phrase(k, lx.STATE_RESULTS) or ("for",)), stop)
    if any(r.phrase(j, lx.NEG_STARTS) or (r.phrase(j, lx.POLITE) and not r.phrase(j, _WISH_TO_KNOW))
           or is_clock_time(r.word(j)) or r.word(j) in lx.TIME_UNITS for j in said):
        return None  # what not to do, a question to the robot, a clock time or a delay: left to the parser
        # (not "... since I need to know whether ...": why the speaker asks)
    so_you = r.at(k, "so", "you")
    if (r.phrase(k, lx.CHECK_WHETHER) or so_you) and any(
            names_place(r, j) or misspelt_name(r, j, j + 1) or (so_you and r.word(j) in lx.PRONOUNS)
            for j in said):
        return None  # "to see if the oven is off", "so you can grab the bowl": the place may be a goal too
    return k, stop


def after_order_reason(r: Reader, k: int) -> bool:
    """Whether a reason of :data:`.lexicon.AFTER_ORDER_REASONS` starts at ``k`` after an order of the same
    sentence (*check the laptop as it needs charging*), not a comparison (*the same floor as the bed*), or a
    state the order leaves things in (:func:`state_result`)."""
    return ((r.phrase(k, lx.AFTER_ORDER_REASONS) is not None or state_result(r, k))
            and any(starts_order(r, j) for j in range(k))
            and not any(w in lx.COMPARED for w in r.words[max(0, k - 4):k]))


def state_result(r: Reader, k: int) -> bool:
    """Whether a state of :data:`.lexicon.STATE_RESULTS` starts at ``k`` (*so it's tidy*, *so nothing's
    burning*), up to the clause's end or its next *then*, naming no room, object or floor (*so it's the
    kitchen next* names the next goal: left to the parser)."""
    said = r.phrase(k, lx.STATE_RESULTS)
    if said is None:
        return False
    stop = next((j for j in range(k + 1, len(r)) if r.word(j) == "," or r.phrase(j, lx.SEQ_WORDS)), len(r))
    return not any(names_place(r, j) or r.word(j) in lx.PRONOUNS for j in range(k + len(said), stop))


def purpose(r: Reader, k: int, end: int) -> bool:
    """Whether *for ...* at ``k`` says what an order is for, up to the clause's end or its *then*, with words
    of no role in the grammar (*for popcorn*, *for the guests*, *for Mum's party*): not a room or object of
    the scene, not the speaker (*for me*), not a duration (*for ten minutes*, *for a sec*)."""
    if r.word(k) != "for" or k == 0:
        return False
    stop = next((j for j in range(k + 1, end) if r.phrase(j, lx.SEQ_WORDS)), end)
    said = range(k + 1, stop)
    return 0 < len(said) <= 4 and all(
        (w := r.word(j)) in lx.ARTICLES or w in lx.POSSESSIVES or w == "'s" or w in lx.EVENT_WORDS
        or (w.isalpha() and w not in lx.LEXICON_WORDS and r.head(j) is None) for j in said) and not any(
        r.word(j) in lx.TIME_UNITS or r.word(j) in lx.SEQUENCE_TIMES for j in said)


def purpose_infinitive(r: Reader, k: int, end: int) -> bool:
    """Whether *to* at ``k``, opening a clause after a comma, says what an order is for (*..., you know, to
    rinse off*, *..., to check it*): a verb that is not one of going or staying (*, to go upstairs* may say
    where to go) and at most two words that name nothing (:data:`.lexicon.PURPOSE_TAILS`) up to the clause's
    end."""
    verb = r.word(k + 1)
    if own_upkeep(r, k, end):
        return True
    return (r.word(k) == "to" and k > 0 and r.word(k - 1) == "," and end - (k + 2) <= 2
            and verb.isalpha() and verb not in lx.GOING_VERBS and r.head(k + 1) is None
            and not misspelt_name(r, k + 1, end)
            and (verb in lx.POSITIVE_VERBS or verb not in lx.LEXICON_WORDS)
            and all(w in lx.PURPOSE_TAILS for w in r.words[k + 2:end]))


def own_upkeep(r: Reader, k: int, end: int) -> bool:
    """Whether *to* at ``k`` says a purpose about the robot's own parts, up to the clause's end or its *then*
    (*head to the kitchen afterwards to wash your wheels*, *stop at the sink to clean your wheels*): a verb
    that is not one of going, *your* / *its*, and one or two words that name nothing of the scene."""
    stop = next((j for j in range(k + 1, end) if r.phrase(j, lx.SEQ_WORDS)), end)
    words = range(k + 3, stop)
    return (r.word(k) == "to" and k > 0 and r.word(k + 1).isalpha() and r.word(k + 1) not in lx.GOING_VERBS
            and r.word(k + 1) not in lx.STRUCTURAL and r.word(k + 2) in lx.OWN_PARTS_OF
            and 1 <= len(words) <= 2
            and all(r.word(j).isalpha() and r.word(j) not in lx.LEXICON_WORDS and r.head(j) is None
                    for j in words) and not misspelt_name(r, k + 3, stop))


def counted(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` only says how many there are (*there's a few*, *there are two of
    them*): what to do with them is said around it (*..., any one's fine*)."""
    return (r.word(start) == "there" and r.word(start + 1) in ("is", "are") and end > start + 2
            and all(w in lx.HOW_MANY or w in lx.NUMBER_WORDS or w.isdigit() for w in r.words[start + 2:end]))


def aside_between(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` between two parts of an order (between dashes, brackets or commas)
    is a statement that names nothing (*Avoid the living room - the carpet's wet - and go ...*, *..., the
    kids are napping, and ...*, *- I'm worried it's dying -*): a subject and a verb (:func:`statement`), with
    no room, object, floor, negation, word of order or condition (*first*, *then*, *if*), misspelt name or
    word that takes back (*..., I mean, ...*: :mod:`.corrections` reads it or refuses it). The order around
    it reads as if it were not there; a statement naming a place is left to the parser, which refuses it."""
    return (statement(r, start, end) == "aside" and not r.says(lx.CORRECTIONS, start, end)
            and not any((names_place(r, k) and not floor_surface(r, k))
                        or r.word(k) in lx.CORRECTING_WORDS or r.phrase(k, lx.NEG_STARTS)
                        or r.word(k) in lx.WISH_STOPS or r.word(k) in lx.SEQUENCE_TIMES  # "first", "later"
                        for k in range(start, end) if not past_time(r, k))
            and not misspelt_name(r, start, end))


def floor_surface(r: Reader, k: int) -> bool:
    """Whether the word at ``k`` is the floor one walks on, said as a statement's subject (*the floor is wet*,
    *the floors are slippery*, *..., floor's wet*), not a storey (*the top floor*, *floor 2*)."""
    return (r.word(k) in ("floor", "floors") and r.word(k - 1) in ("the", ",", "")
            and r.word(k + 1) in lx.STATEMENT_VERBS)


_PAST_TIME_NOUNS = frozenset({"night", "week", "weekend", "month", "year", "time", "summer", "winter"})


def past_time(r: Reader, k: int) -> bool:
    """Whether the word at ``k`` is *last* of a time gone by (*it was dripping last night*, *she knocked it
    over last time*): a time of the statement, not the order's *last*."""
    return r.word(k) == "last" and r.word(k + 1) in _PAST_TIME_NOUNS


def manner_only(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` only says how to behave, with no place or thing (*..., so be
    gentle*, *..., and please be careful*, *Be extra quiet.*): *be* and one or two words of manner
    (:data:`.lexicon.MANNER_WORDS`); *be careful in the kitchen* names a place (keep out, or only take care?)
    and is refused by the parser."""
    k = skip_joiner(r, r.skip(start, lx.INTERJECTIONS))
    k += r.word(k) == "please"
    said = r.words[k + 1:end]
    return r.word(k) == "be" and 1 <= len(said) <= 2 and all(w in lx.MANNER_WORDS for w in said) \
        and said[-1] not in lx.MANNER_INTENSIFIERS


def is_reason(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is a reason (:func:`reason_span`) from its first word."""
    return reason_span(r, start, end) == (start, end)


def starts_order(r: Reader, k: int) -> bool:
    """Whether the words at ``k`` start an order: a prohibition, a polite wrapper, a verb; after *you* and a
    modal of an order (*you must not enter ...*; not *you won't need X*)."""
    w = r.word(k)
    if w == "you" and r.word(k + 1) in lx.ORDER_MODALS:
        return starts_order(r, k + 2)
    return (r.phrase(k, lx.NEG_STARTS) is not None or r.phrase(k, lx.POLITE) is not None or w == "please"
            or (w in lx.STAY and not w.endswith("ing"))  # "... so stay on this floor": an order to keep
            or (w in lx.POSITIVE_VERBS and w not in lx.PLACE_PREPOSITIONS and w not in lx.PARTICLES
                and not w.endswith(("ing", "ed"))))


def aside(r: Reader, start: int, end: int) -> Reader:
    """The words ``[start, end)`` of ``r`` as a reader set aside."""
    return replace(r, toks=r.toks[start:end], aside=True)


def skip_joiner(r: Reader, i: int) -> int:
    """After a clause set aside: *so* / *but* / *and* before the order (*..., so stay out of there*)."""
    return i + 1 if r.word(i) in lx.STATEMENT_JOINERS else i


def is_context(r: Reader, start: int, end: int, leading: bool) -> bool:
    """Whether the clause ``[start, end)`` only gives context: a time (opening or closing the sentence), or a
    statement that is not a need about the scene (see the module docstring)."""
    said = skip_joiner(r, r.skip(start, lx.INTERJECTIONS))  # "ok I dropped my keys somewhere, ..."
    said = said + 1 if r.word(said) in lx.EVENT_WORDS and r.word(said + 1) in lx.SUBJECT_PRONOUNS else said
    doubt = r.phrase(said, lx.UNSURE)  # "Not sure if I turned it off": the statement after 'if'
    said = said + len(doubt) + 1 if doubt and r.word(said + len(doubt)) in lx.CHECK_THAT[1:] else said
    said += len(r.phrase(said, lx.NOTICE_THAT) or ())  # "Note that the kitchen is wet"
    belief = r.phrase(said, lx.SURE_WITHOUT_SUBJECT)  # "Pretty sure we're out of milk"
    said += len(belief) + (r.word(said + len(belief)) == "that") if belief else 0
    if belief and any(r.head(k) is not None or r.word(k) in lx.RELATIVE_FLOORS for k in range(said, end)):
        return False  # "Pretty sure it's in the kitchen": a place no order may name, refused by the parser
    if orders_a_named_thing(r, start, end):
        return False  # "visit both bedrooms, we start with the kitchen": an order, never context
    taken_back = r.phrase(said, lx.CORRECTIONS)
    if not leading and taken_back and said + len(taken_back) < end:
        return False  # "..., sit on it, I mean look at the book instead": takes back, never context
    return (is_time(r, start, end) or is_time(r, skip_joiner(r, start), end) or ignored_thing(r, said, end)
            or statement(r, said, end) == "aside" or diary_past(r, said, end) or wish_to_know(r, said, end)
            or event_note(r, start, end) or is_reason(r, start, end))


_WISH_TO_KNOW = Phrases(tuple((*who, "to", know, whether) for who in (("i", "want"), ("i", "would", "like"),
                                                                      ("i", "need"), ("we", "want"))
                               for know in ("know", "see", "check")
                               for whether in ("if", "whether", "what", "how", "which")))
"""*I want to know if ...*: why the speaker asks for the order it follows (*look at both apples, I want to
know if they've gone soft*, *check the fridge, I want to know what we need*)."""


def wish_to_know(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is the speaker's wish to know something (:data:`_WISH_TO_KNOW`):
    the reason of an order, set aside and said back; alone it leaves no goal (refused as such). With a room
    or object after it (*I want to know if the TV is in the kitchen*) it is left to the parser."""
    said = r.phrase(start, _WISH_TO_KNOW)
    return said is not None and not any(names_place(r, k) for k in range(start + len(said), end))


_DIARY_VERBS = frozenset({"lost", "got", "broke", "forgot", "spilt", "spilled", "dropped", "had", "came"})
"""Past verbs a speaker opens a note about themselves with, the *I* left out (*Lost my glasses again*, *Just
got back from holiday*)."""


def diary_past(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is a note about the speaker without its *I* (*Lost my reading
    glasses AGAIN*, *Just got back from holiday and I can't find my passport*): a verb of
    :data:`_DIARY_VERBS` (after *just*), then no *you*, no room, object or floor: a statement, set aside.
    An order never opens with a past verb; with a place (*Dropped the bowl in the kitchen*) it is left to
    the parser, which refuses it."""
    k = start + (1 if r.word(start) == "just" else 0)
    return (r.word(k) in _DIARY_VERBS and r.word(k + 1) not in ("to", "it", "them")
            and "you" not in r.words[start:end]
            and not any(names_place(r, j) for j in range(start, end)) and not misspelt_name(r, k + 1, end))


def ignored_thing(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` only tells the robot to pay no heed to a thing the scene does not
    hold (*btw ignore the mess*, *just don't mind the noise*: :data:`.lexicon.IGNORED`, then a determiner and
    one to three words that name nothing, up to the clause's end); with a room, object, floor or pronoun
    (*ignore the kitchen*: skip it, or avoid it? *ignore the mess in the hall*) it is left to the parser,
    which refuses it."""
    k = r.skip(start, ("just", "please", "and", "but", "also"))
    said = r.phrase(k, lx.IGNORED)
    if said is None or r.word(k + len(said)) not in lx.DETERMINERS:
        return False
    words = range(k + len(said) + 1, end)
    return 1 <= len(words) <= 3 and not misspelt_name(r, words.start, end) and all(
        r.word(j).isalpha() and r.head(j) is None and r.word(j) not in lx.STRUCTURAL
        and r.word(j) not in lx.RELATIVE_FLOORS and r.word(j) not in lx.FLOOR_WORDS for j in words)


def orders_a_named_thing(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` says the order of a room or object of the scene (a word of the
    order, :data:`.lexicon.ORDER_HEADS`, and a noun of the scene or *one*: *we start with the kitchen*, read
    *we first the kitchen*; *... the one upstairs*), which a statement set aside would drop."""
    tail = time_tail(r, start, end)  # "the office is a mess after last night": a time, no order
    said = range(start, end if tail is None else tail)
    return (any(r.word(k) in lx.ORDER_HEADS and not past_time(r, k) for k in said)  # not "last night"
            and any(r.head(k) is not None or r.word(k) in lx.ANAPHORIC_ONE for k in range(start, end)))


def hedged_addition(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)``, after a statement set aside, only adds a guess to it (*I lost my
    glasses, probably somewhere upstairs*, *..., most likely downstairs*): a hedge
    (:data:`.lexicon.STATEMENT_HEDGES`), then words that name nothing and ask nothing (:func:`mere_talk`,
    upstairs and downstairs allowed) and have no role in the grammar (*outside*, *in*: where, or a goal?)."""
    start += r.word(start) in lx.HEDGE_INTENSIFIERS  # "most likely", "quite possibly"
    return (r.word(start) in lx.STATEMENT_HEDGES and end > start + 1
            and mere_talk(r, start + 1, end, floors=False) and not misspelt_name(r, start + 1, end)
            and not any(r.word(k) in lx.STRUCTURAL or r.phrase(k, lx.POLITE) for k in range(start + 1, end)))


def misspelt_name(r: Reader, start: int, end: int) -> bool:
    """Whether a word of ``[start, end)`` may be a misspelt name of the scene (*to kitchn*): never set aside,
    so that it is refused with its *did you mean*."""
    return r.spelling is not None and any(r.spelling.may_be_a_misspelt_name(w) for w in r.words[start:end])


def closing_only(r: Reader, start: int, end: int) -> bool:
    """Whether the words ``[start, end)`` are only remarks that ask nothing (*Oh*, *Right*, *Thanks*, *Lovely,
    cheers*, *Sorry for the trouble and thank you*)."""
    k = start if r.phrase(start, lx.CLOSING) else skip_joiner(r, start)  # "as usual", "so no rush"
    while k < end and (said := ((r.word(k),) if praise_before_closing(r, k, end) else None)
                       or apology_for(r, k, end) or r.phrase(k, lx.CLOSING) or well_wishing(r, k, end)
                       or ((r.word(k),) if r.word(k) in lx.HESITATIONS or r.word(k) == "," or signature(r, k)
                           or (r.word(k) in lx.KISSES and k == len(r) - 1)
                           or (r.word(k) == "and" and k > start and r.phrase(k + 1, lx.CLOSING)) else None)):
        k += len(said)
        k += len(r.phrase(k, lx.CLOSING_TAILS) or ()) if said != (",",) else 0  # "no rush at all"
    return start < k == end


def apology_for(r: Reader, k: int, end: int) -> tuple[str, ...] | None:
    """The words of an apology or thanks for something that names nothing and asks nothing, up to ``end``
    (*Sorry for the late notice*, *apologies about the short notice*, *Thanks for all your help this week*),
    else ``None``; *sorry about the kitchen* names a room (what of it?) and is no remark."""
    thanks = r.phrase(k, lx.THANKS_FOR)  # "Thanks for all your help this week"
    said = k + len(thanks) if thanks else k + 2
    tail = time_tail(r, said, end) or end
    kept = lx.ARTICLES | lx.POSSESSIVES | {"all"} if thanks else lx.ARTICLES
    if ((not thanks and (r.word(k) not in lx.APOLOGY_WORDS or r.word(k + 1) not in ("for", "about")))
            or tail - said > 5 or not mere_talk(r, said, end) or misspelt_name(r, said, end)
            or any(r.word(j) in lx.STRUCTURAL and r.word(j) not in kept for j in range(said, tail))):
        return None
    return tuple(r.words[k:end])


def praise_before_order(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` opening the sentence is only praise (*Lovely, now go up ...*,
    *Great - check the oven*) before a comma and an order: an interjection, not a thing called lovely (*Is
    the kitchen lovely?* asks something)."""
    words = r.words[start:end]
    after = r.skip(r.skip(end, (",",)), lx.SEQUENCE_TIMES)  # "Lovely, now go ..."
    return (start == 0 and r.word(end) == "," and any(w in lx.PRAISE for w in words)
            and all(w in lx.PRAISE or w in lx.HESITATIONS for w in words) and starts_order(r, after))


def well_wishing(r: Reader, k: int, end: int) -> tuple[str, ...] | None:
    """The words of a wish said without its subject, up to ``end`` (*hope you're charged up*, *hope your
    day's going ok*, *trust all is well*), when they name nothing (no room, object, floor or misspelt name)
    and ask nothing (no order, no negation, no verb the grammar reads but a participle: *hope you go to ...*
    is no remark), else ``None``."""
    said = range(k + 1, end)
    if r.word(k) not in lx.WELL_WISHING or not 0 < len(said) <= 8 or misspelt_name(r, k + 1, end):
        return None
    if any(r.head(j) is not None or r.word(j) in lx.RELATIVE_FLOORS or r.phrase(j, lx.NEG_STARTS)
           or r.phrase(j, lx.SEQ_WORDS) or r.word(j) in lx.WISH_STOPS
           or r.word(j).startswith(("room_", "object_")) or not (r.word(j).isalpha() or r.word(j) == "'s")
           or (r.word(j) in lx.POSITIVE_VERBS and r.word(j) not in lx.PARTICLES
               and not r.word(j).endswith(("ing", "ed")))
           or (r.word(j) in lx.STRUCTURAL and r.word(j) not in lx.AUXILIARIES | lx.DETERMINERS
               and r.word(j) not in lx.PRONOUNS)
           for j in said):
        return None
    return tuple(r.words[k:end])


def praise_before_closing(r: Reader, k: int, end: int) -> bool:
    """Whether the word at ``k`` is praise (:data:`.lexicon.PRAISE`) that only remarks before more of them
    (*Lovely, thank you.*, *Great, thank you so much!*, *Perfect - cheers*): praise alone is no remark
    inside a clause (*Is the kitchen lovely?* asks something)."""
    j = k + 1
    while j < end and (r.word(j) in lx.PRAISE or r.word(j) == ","):
        j += 1
    return r.word(k) in lx.PRAISE and j < end and closing_only(r, j, end)


def signature(r: Reader, k: int) -> bool:
    """Whether the word at ``k`` is the name a sign-off is signed with (*Regards, Tom*, *Thanks, Anna!*): a
    capitalised word the translator does not know, last in its sentence, after sign-offs and a comma."""
    w, tok = r.word(k), r.toks[k] if k < len(r) else None
    rest = [j for j in range(k + 1, len(r)) if r.word(j).isalpha()]
    return (tok is not None and w.isalpha() and r.text[tok.start].isupper()
            and (w not in lx.LEXICON_WORDS or w in lx.PEOPLE_NOUNS) and r.head(k) is None
            and r.word(k - 1) == "," and closing_only(r, 0, k - 1)
            and (not rest or closing_only(r, rest[0], len(r))))


def before_you_start(r: Reader) -> int | None:
    """Where what follows a heading of the robot's setting off starts (*Before you start:*, *Before you head
    off:*, *Once you begin,*), or ``None``: an opener of :data:`.lexicon.EVENT_OPENERS`, *you*, one or two
    words that name nothing and are no order word, and a colon or comma; said when all that follows is done,
    it asks nothing (*Before you go into the kitchen:* names a place, and is left to the parser)."""
    colon = next((k for k in (3, 4) if r.word(k) in (":", ",")), None)  # (a heading's colon joins as a comma)
    if r.word(0) not in lx.EVENT_OPENERS or r.word(1) != "you" or colon is None:
        return None
    said = range(2, colon)
    return colon + 1 if (
            all(r.word(k).isalpha() and r.head(k) is None and r.word(k) not in lx.RELATIVE_FLOORS
                    and (r.word(k) not in lx.STRUCTURAL or r.word(k) in lx.PARTICLES)
                    and r.word(k) not in ("up", "down") for k in said)  # "Before you come down,": a floor
            and not misspelt_name(r, 2, colon)) else None


def event_note(r: Reader, start: int, end: int) -> bool:
    """*Movie night later!*, *Big day tomorrow*, *Work-from-home day*: words about an event, with no room,
    object, verb or word of the grammar (but inside a compound joined by hyphens); or a day named after a
    thing (*Plant day!*), which asks nothing."""
    words = r.words[start:end]
    if not any(w in lx.EVENT_WORDS and w not in lx.SEQUENCE_TIMES for w in words):
        return False
    head = r.head(start)
    if head is not None and start + head.words == end - 1 and words[-1] in lx.NAMED_DAYS:
        return True  # "Plant day!", "Laundry day" (not "Kitchen tonight": a goal and a time)
    return not any(r.head(k) is not None or r.word(k) in lx.REFUSED_WORDS or not r.word(k).isalpha()
                   or ((r.word(k) in lx.POSITIVE_VERBS or (r.word(k) in lx.STRUCTURAL
                                                           and r.word(k) not in lx.TIME_WORDS))
                       and not hyphened(r, k))  # "Work-from-home day": one word
                   for k in range(start, end))


def hyphened(r: Reader, k: int) -> bool:
    """Whether the word at ``k`` is inside a compound joined by hyphens (*work-from-home*, *back-to-school*):
    one word of the phrase, whatever role it has alone."""
    tok, text = r.toks[k], r.text
    return ((k > 0 and text[tok.start - 1:tok.start] == "-" and r.toks[k - 1].end == tok.start - 1)
            or (k < len(r) - 1 and text[tok.end:tok.end + 1] == "-" and r.toks[k + 1].start == tok.end + 1))


def chore_note(r: Reader) -> bool:
    """*Quick tidy before bedtime.*, *Proper clean today!*: a manner word and a chore's verb said as a noun
    (:data:`.lexicon.GIVEN_MANNER`: an adjective, so the verb is no order), alone in the sentence or before a
    time; it names nothing and asks nothing. With a place (*Quick tidy of the kitchen.*) it is left to the
    parser."""
    end = time_tail(r, 0, len(r)) or len(r)
    return (end == 2 and r.word(0) in lx.GIVEN_MANNER and r.word(1) in lx.POSITIVE_VERBS
            and r.word(1) not in lx.PLACE_PREPOSITIONS and r.word(1) not in lx.PARTICLES)


def names_place(r: Reader, k: int) -> bool:
    """Whether the word at ``k`` names a room, an object or a floor (a head noun, a key, *upstairs*,
    *floor*)."""
    w = r.word(k)
    return (r.head(k) is not None or w in lx.RELATIVE_FLOORS or w in lx.FLOOR_WORDS
            or w.startswith(("room_", "object_")))


def mere_talk(r: Reader, start: int, end: int, floors: bool = True) -> bool:
    """Whether the words ``[start, end)`` (what is left after a statement) name nothing and ask nothing (*I
    left my bag somewhere, no idea where, ...*); ``floors``: *upstairs* / *downstairs* count as naming."""
    return not any(r.head(k) is not None or r.word(k) in lx.POSITIVE_VERBS or r.phrase(k, lx.NEG_STARTS)
                   or r.word(k).startswith(("room_", "object_"))
                   or (floors and r.word(k) in lx.RELATIVE_FLOORS)
                   or r.word(k) in lx.REFUSED_WORDS or r.word(k) in lx.PRONOUNS  # "so leave it alone"
                   for k in range(start, end))


def is_time(r: Reader, start: int, end: int) -> bool:
    """*Before lunch*, *this morning*, *at some point this evening*, *tonight*, *right now*: a time of day,
    meal or event (not *later* or *now* alone, which order the steps)."""
    if (event_clause(r, start, end) or tuple(r.words[start:end]) in lx.OCCASIONS
            or robot_routine(r, start, end)):  # "First thing when you wake up, ..."
        return True
    words = r.words[start:end]
    event = words[:1] in tuple((w,) for w in lx.EVENT_OPENERS)  # "before the guests arrive"
    own = named_event(r, start, end)  # "after the game tonight", "during our film tomorrow"
    gone_by = {j for k in range(start, end) if past_time(r, k) for j in (k - start, k + 1 - start)}
    said = [w in lx.TIME_WORDS or w in lx.PAST_TIMES or (own is not None and own - 1 <= start + k <= own)
            or k in gone_by  # "after last night", "last time"
            or (event and (w in lx.EVENT_VERBS or w in lx.PEOPLE or w in lx.PEOPLE_NOUNS
                           or w in lx.POSSESSIVES or w in lx.AUXILIARIES or k == 0))
            for k, w in enumerate(words)]
    if not words or not all(said):
        return False
    events = [w for k, w in enumerate(words) if (w in lx.EVENT_WORDS and w not in lx.SEQUENCE_TIMES)
              or k in gone_by or (event and (w in lx.PEOPLE or w in lx.PEOPLE_NOUNS))]
    return bool(events) or tuple(words) in lx.NOW_SAID


_ROBOT_ROUTINE = frozenset({"wake", "up", "dock", "docks", "charge", "charging", "recharge", "power", "down",
                            "shut", "do", "doing", "rounds", "round", "patrol"})  # "when you do your rounds"
"""The robot's own day (*when you wake up*, *before you dock*, *after your morning charge*): a time, never a
place. Kept here, out of the lexicon, so that its words stay unknown to the rest (*Power went out earlier.*
is a statement)."""


def robot_routine(r: Reader, start: int, end: int) -> bool:
    """Whether ``[start, end)`` is a time of the robot's own day (*when you wake up*, *before you dock
    tonight*, *once you've had your morning charge*, *before you power down for the night*): an event's
    opener, *you*, and only words of its routine (:data:`_ROBOT_ROUTINE`) and of times."""
    k = r.skip(start, lx.TIME_WORDS - frozenset(lx.EVENT_OPENERS))  # "first thing when you ..."
    if r.word(k) not in lx.EVENT_OPENERS or r.word(k + 1) != "you":
        return False
    words = r.words[k + 2:end]
    return any(w in _ROBOT_ROUTINE for w in words) and all(
        w in _ROBOT_ROUTINE or w in lx.TIME_WORDS or w in lx.AUXILIARIES or w in ("your", "had", "'ve")
        for w in words)


def named_event(r: Reader, start: int, end: int) -> int | None:
    """Where the noun of an event named by its own word is, in a time opening with an event's opener (*after
    the game tonight*, *before the match on Saturday*, *during my show this evening*): a determiner, one
    word the translator does not know and that is no misspelt name of the scene, then a day's time
    (:data:`.lexicon.EVENT_WORDS`) that says it is an event; ``None`` otherwise. Without that time (*after
    the game, ...*) the word may be a goal the scene lacks, and is left to the parser, which refuses it."""
    noun = start + 2
    opened = r.word(start) in lx.EVENT_OPENERS + lx.SPAN_OPENERS and (
        r.word(start + 1) in lx.DETERMINERS or r.word(start + 1) in lx.POSSESSIVES)
    if (not opened or not plain_subject(r, noun) or r.word(noun) in lx.LEXICON_WORDS
            or misspelt_name(r, noun, noun + 1)):
        return None
    return noun if any(r.word(k) in lx.EVENT_WORDS for k in range(noun + 1, end)) else None


def event_clause(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is an event of people, known by its shape whatever its verb
    (*before the cleaners show up*, *once my sister drops by*, *after the kids head off*): an opener of
    :data:`.lexicon.EVENT_OPENERS`, a subject that is a person (*she*, *the guests*, *my mum*, *Grandpa*; not
    *you*: where the robot goes orders the steps), one verb that is no room, object or floor, and then only
    particles or times. Any place, thing, pronoun or more words (*before the guests come to the kitchen*,
    *before the kids go to bed*) leave it to the parser, which refuses it."""
    if r.word(start) not in lx.EVENT_OPENERS:
        return False
    verb = person_subject_end(r, start + 1, end)
    if verb is None:
        return False
    verb = r.skip(verb, lx.EVENT_AUXILIARIES)  # "once the dog has been fed"
    w = r.word(verb)
    if (verb >= end or not w.isalpha() or r.head(verb) is not None or w in lx.STRUCTURAL
            or w in lx.RELATIVE_FLOORS or r.phrase(verb, lx.NEG_STARTS)):
        return False
    return all(r.word(k) in lx.EVENT_TAILS or r.word(k) in lx.EVENT_WORDS
               or (r.word(k) in lx.EVENT_LINKS and r.word(k + 1) in lx.EVENT_WORDS)  # "from work"
               for k in range(verb + 1, end))


def event_of_people_at_place(r: Reader) -> tuple[int, int] | None:
    """The ``[start, end)`` of an event of people that names a room or object of the scene (*after the kids
    are at the couch*, *before the guests sit at the dining table*, *once my mum is in the kitchen*): an
    opener of :data:`.lexicon.EVENT_OPENERS`, a person (:func:`person_subject_end`), a verb and a room or
    object before the clause ends; ``None`` when there is none. What people do at a place is no goal of
    the robot's, and other rules could read the place as one: refused."""
    for k in range(len(r)):
        verb = person_subject_end(r, k + 1, len(r), events=False) if r.word(k) in lx.EVENT_OPENERS else None
        if verb is None or r.head(verb) is not None or not r.word(verb).isalpha():
            continue
        end = next((j for j in range(verb + 1, len(r))  # up to the order after it ("... leave check X")
                    if r.word(j) == "," or r.phrase(j, lx.SEQ_WORDS) or starts_order(r, j)), len(r))
        if any(r.head(j) is not None for j in range(verb + 1, end)):
            return k, end
    return None


def person_subject_end(r: Reader, start: int, end: int, events: bool = True) -> int | None:
    """Where the verb after a person as subject starts (*she* | *drops*, *the cleaners* | *show*, *my
    mum* | *gets*), or ``None``: a pronoun of people, or a noun of no role in the grammar with at most a
    determiner or possessive and one more such noun before it (*the new cleaners*, *my sister*);
    an event word counts too (*the party* | *kicks off*, *the guests*), but without ``events`` not a bare one
    (*lunch* in *Before lunch check the oven*)."""
    if r.word(start) in lx.PEOPLE:
        return start + 1
    k = start + (r.word(start) in lx.DETERMINERS)
    nouns = 0
    while k < end and nouns < 2 and (plain_subject(r, k) or r.word(k) in lx.PEOPLE_NOUNS
                                     or r.word(k) in lx.EVENT_WORDS) \
            and not (r.word(k) in lx.EVENT_WORDS and k == start and not events) \
            and not misspelt_name(r, k, k + 1):
        k, nouns = k + (r.word(k + 1) == "'s") + 1, nouns + 1  # "my mum's friends"
        if r.word(k) in lx.PEOPLE_NOUNS or r.word(k - 1) in lx.PEOPLE_NOUNS:
            break
    return k if nouns else None


def time_tail(r: Reader, start: int, end: int) -> int | None:
    """Where a time expression closing the clause ``[start, end)`` starts (*go to the kitchen tonight*, *...
    before dinner*), or ``None``."""
    if is_time(r, start, end):
        return None  # the whole clause is one
    later = while_later(r, start, end)
    if later is not None:
        return later
    # an event of people, whole: "... before the cleaners show up", "... before the kids leave for school"
    event = next((k for k in range(max(start + 1, end - 7), end) if event_clause(r, k, end)), None)
    if event is not None:
        return event
    for k in range(max(start + 1, end - 4), end):
        if r.word(k) in lx.TIME_OPENERS and r.word(k - 1) not in lx.UNTIL_WORDS and is_time(r, k, end):
            return k
    return None


def while_later(r: Reader, start: int, end: int) -> int | None:
    """Where *later* (*later on*) closing a *while* clause ``[start, end)`` starts (*While you're in the
    office later, ...*): when the robot is there, not an order of the goals; else ``None``."""
    later = 2 if r.words[end - 2:end] == ("later", "on") else 1 if r.word(end - 1) == "later" else 0
    opens = r.word(r.skip(start, (",", "and"))) == "while"
    return end - later if later and opens and end - later > start + 1 else None


def times_of_parts(readers: list[Reader]) -> list[str]:
    """The times of events said by the words set aside from ``readers``, whole (*Before lunch*) or closing
    them (*Jobs before lunch*, *Quick tidy after dinner*), as said: two of them may put the parts of the
    mission in an order of times (*Jobs before lunch: A. Jobs after lunch: B.*), which no formula keeps."""
    return [r.quote(0, len(r)) for r in readers if r.aside and (
        (r.word(0) in lx.EVENT_OPENERS and is_time(r, 0, len(r)))
        or ((tail := time_tail(r, 0, len(r))) is not None and r.word(tail) in lx.EVENT_OPENERS
            and not any(w in lx.PAST_TIMES or w == "last" for w in r.words[tail:])))]  # "after last night"


def timed_heading(r: Reader) -> list[Reader]:
    """The words before a colon that announce how many things follow or name the list, without the time of
    day, event or aside asking nothing they end with (*A couple of things before I get back:*, *Three jobs for
    tonight:*, *Two things when you get a chance:*; a list of things to do: *Things to grab before dinner:*,
    *To do before dinner:*), after that time set aside (said back; first, so that the heading stays right
    before what it announces); words pointing to the list lose an aside asking nothing only (*Could you do
    these when you get a chance:*; *Avoid these before noon:* keeps its time, and is refused); ``[r]``
    otherwise."""
    if not r.words or r.words[-1] != ":" or r.aside:
        return [r]
    timed = time_tail(r, 0, len(r) - 1)
    hedged = hedge_tail(r, len(r) - 1)  # "Three things when you get a chance:"
    tail = timed if timed is not None else hedged
    if tail is None:
        return [r]
    said = r.words[:tail]
    counted = any(w in lx.NUMBER_WORDS or w in lx.FEW or w.isdigit() for w in said)
    listed = (bool(said[:1]) and said[0] in lx.LIST_NOUNS and said[1:2] == ("to",)) or said == ("to", "do")
    pointed = said[-1:] == ("these",) and timed is None
    if not counted and not listed and not pointed:
        return [r]  # a label with its time (*Route for this afternoon:*) is said back whole
    return [aside(r, tail, len(r) - 1), replace(r, toks=r.toks[:tail] + r.toks[-1:])]


def hedge_tail(r: Reader, end: int) -> int | None:
    """Where an aside that asks nothing (:data:`.lexicon.CLOSING`: *when you get a chance*, *no rush*)
    ending exactly at ``end`` starts, after at least one word, or ``None``."""
    return next((k for k in range(1, end) if len(r.phrase(k, lx.CLOSING) or ()) == end - k), None)


def time_head(r: Reader, start: int, end: int) -> int | None:
    """Where the order after a time of day opening the clause ``[start, end)`` without a comma starts (*This
    evening stay on this floor*, *Tonight check the oven*, *After breakfast go ...*), or ``None``; only a
    day's time (opening with :data:`.lexicon.DAY_OPENERS`, or a meal after *before* / *after*): an event
    (*before the party go ...*, *the guests arrive ...*) is left to the parser, as are *later* and *now*,
    which order the steps."""
    if (r.word(start) not in lx.DAY_OPENERS and r.word(start) not in lx.SPAN_OPENERS
            and not (r.word(start) in ("before", "after") and r.word(start + 1) in lx.MEALS)):
        return None  # ("After breakfast go ...": a meal, a time of day like "this morning")
    said = lx.HESITATIONS | lx.MANNER_INTENSIFIERS  # "for now just head ...", "Tonight really check ..."
    return next((k for k in range(start + 1, min(start + 5, end)) if is_time(r, start, k) and (
        starts_order(r, r.skip(k, said)) or r.word(r.skip(k, said)) in lx.STAY)), None)


def statement(r: Reader, start: int, end: int) -> str | None:
    """``"aside"`` when the clause ``[start, end)`` is a statement to set aside, ``"need"`` for a need about a
    room or object of the scene (left to the parser, which refuses it), ``None`` when it is no statement."""
    if (start >= end or "you" in r.words[start:end] or r.phrase(start, lx.POLITE)
            or r.phrase(start, lx.CLOSING)):
        return None  # a clause about the robot ("I'd be grateful if you ...") may ask something of it
    if r.word(start) in lx.CHOOSERS_OF_KIND and any(
            r.word(j) in lx.LOCATIVE and (h := r.head(j + 1) or r.head(j + 2)) is not None
            and h.kind == "room" for j in range(start, end)):
        return None  # "..., any of the vases in the dining room is fine": a goal said as a remark
    k = subject_end(r, start, end)
    aside_of = r.phrase(start - 1, lx.ASIDE)  # "the couch, it's in the kitchen": a qualifier of the couch
    qualifies = aside_of is not None and r.word(start - 1 + len(aside_of)) in lx.ASIDE_QUALIFIERS
    located = locates(r, start, k, end) and not left_there(r, start, k) if k is not None else False
    if (k is None or r.phrase(k, lx.OFF_LIMITS) or qualifies or located
            or (any(w in lx.LIST_NOUNS for w in r.words[start:k]) and not vague_talk(r, start, end))
            or (r.word(k) in lx.STATEMENT_LINKS and r.word(k + 1) == "to")):
        # "the kitchen is off limits", "the couch, it's in the kitchen", "the bowl is in the sink", "the next
        # task is to ...": not mere context
        return None
    if any(r.word(j) == "and" and r.word(j + 1) not in lx.SUBJECT_PRONOUNS and starts_order(r, j + 1)
           for j in range(k, end)):
        return None  # "the bathroom is wet and avoid it": an order after the statement, never set aside
    if r.word(start) in lx.DEICTIC_SUBJECTS and r.np_starts(k + 1) and any(
            r.head(j) is not None for j in range(k + 1, min(k + 4, end))):
        return None  # "Actually, it was the kitchen": says which place is meant, never context
    need = next((j for j in range(k, end) if r.word(j) in lx.NEED_WORDS), None)
    needs = need is not None
    said = r.words[need + 1:end] if need is not None else ()  # what is needed, and where
    wanted_at = any(w in lx.PRONOUNS for w in said) and any(  # "my son wants it upstairs": a goal, maybe
        w in lx.RELATIVE_FLOORS or w in lx.WANTED_WHERE or w in lx.FLOOR_WORDS for w in said)
    names = wanted_at or any(r.head(j) is not None and not (j + 1 == k and r.words[j - 1:j + 1] in _HOME)
                             for j in range(start, end))  # "the place needs a once-over": the home
    return "need" if needs and names else "aside"


_HOME = frozenset({("the", "place")})
"""The home as a whole, in a statement about it (*the place needs a once-over*), not one of its rooms."""


def locates(r: Reader, start: int, verb: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` (its verb at ``verb``) says where an object of the scene is (*the
    bowl is in the kitchen*, *I left my book in the bedroom*; not *the vase in the hall is dusty*): that may
    tell which one is meant, so it is left to the parser (which refuses it)."""
    objects = [j for j in range(start, end) if (h := r.head(j)) is not None and h.kind == "object"]
    return bool(objects) and any(r.word(j) in lx.LOCATIVE and r.np_starts(j + 1) and not contained(r, j)
                                 for j in range(max(objects[0] + 1, verb), end))


def contained(r: Reader, j: int) -> bool:
    """Whether *in it* at ``j`` closes a room's contents (*the bedroom with the vase in it*): the room says
    what it holds, no object is placed."""
    return r.word(j + 1) == "it" and "with" in r.words[max(0, j - 4):j]


def left_there(r: Reader, start: int, verb: int) -> bool:
    """Whether a clause that locates an object of the scene (its subject ``[start, verb)``) says where a
    person left it (*I think I left my book in the bedroom with the chair*): set aside, its phrases kept as
    mentions, which *it* and *there* point back to (*... Fetch it.*: that book); a place the scene does not
    hold it in is then refused where *it* is grounded."""
    objects = [j for j in range(verb, len(r)) if (h := r.head(j)) is not None and h.kind == "object"]
    person = r.word(start) in lx.PEOPLE or (r.word(start) in lx.POSSESSIVES and verb - start <= 3 and not any(
        r.head(j) is not None for j in range(start, verb)))  # "my nephew left his teddy bear in ..."
    return person and bool(objects) and any(w in lx.LEFT_THERE for w in r.words[verb:objects[0]])


_RUN_ON_SUBJECTS = frozenset({"the"}) | lx.POSSESSIVES - {"your"}
"""The first words of a statement run on after an order without a mark (*... at all the floor is wet*)."""
_RUN_ON_AFTER = frozenset({"all", "please", "pls", "ok", "okay", "there", "here", "too", "though", "upstairs",
                           "downstairs", "today", "tonight", "now", "anyway", "again", "afterwards"})
"""Words an order may end with right before a statement run on after it (*don't go in the kitchen at all the
floor is wet*, *check the toilet please the flush is broken*)."""
_BE_HAVE = frozenset({"is", "are", "was", "were", "'s", "'re", "has", "have", "had"})


def run_on_statements(r: Reader) -> Reader:
    """``r`` with commas around each statement run on after an order without a mark, as dictation types it
    (*dont go in the kitchen at all the floor is like wet*, *... at all the floor is wet and check the
    couch*): a subject (*the* or a possessive and its noun phrase) and a verb of being or having, right after
    an order's last word (:data:`_RUN_ON_AFTER`) or a room or object, to *and* and an order or the end, naming
    no room, object or floor after its verb; the clause is then read (set aside, or refused) as any statement
    between commas is."""
    cuts: list[int] = []
    for k in range(2, len(r)):
        if (r.word(k) not in _RUN_ON_SUBJECTS or r.word(k - 1) == ","
                or not (r.word(k - 1) in _RUN_ON_AFTER or r.head_before(k) is not None)):
            continue
        verb = subject_end(r, k, len(r))
        if verb is None or verb <= k or r.word(verb) not in _BE_HAVE or relative_clause(r, verb):
            continue
        end = next((j for j in range(verb, len(r)) if r.word(j) == ","
                    or (r.word(j) == "and" and starts_order(r, j + 1))), len(r))
        if not any(names_place(r, j) and not floor_surface(r, j) for j in range(verb, end)):
            cuts += [k, end] if r.word(end) == "and" else [k]  # "... and check the couch": an order again
    return r.with_commas(cuts)


def relative_clause(r: Reader, verb: int) -> bool:
    """Whether the clause of the verb at ``verb`` ends with a preposition (*the room the bottle is in, then
    ...*): a relative clause of the noun before it, no statement."""
    end = next((j for j in range(verb, len(r)) if r.word(j) in (",", "and", "then")), len(r))
    return r.word(end - 1) in lx.LOCATIVE or r.word(end - 1) in lx.PLACE_PREPOSITIONS


def subject_end(r: Reader, start: int, end: int) -> int | None:
    """Where the verb after the subject of a statement starts (*we* | *'re hosting*, *the cat* | *keeps*, *my
    mum* | *'s staying*), or ``None`` when the clause does not start with a subject and a verb."""
    w = r.word(start)
    if (r.words[start:start + 3] in _ONE_OF_THEM and finite_verb(r.word(start + 3))
            and r.phrase(start + 3, lx.REMARK_FINE) is None and r.phrase(start + 3, _ENOUGH) is None
            and not any(names_place(r, k) for k in range(start, end))):  # (not "one of them is fine")
        return start + 3  # "..., one of them got knocked": a statement about the things named (not where)
    if w in lx.SUBJECT_PRONOUNS:
        verb = r.word(start + 1)
        if w in lx.DEICTIC_SUBJECTS and verb not in lx.STATEMENT_VERBS:
            return None
        return start + 1 if start + 1 < end and verb not in lx.CLAUSE_ENDS else None
    if w in lx.DETERMINERS or w in lx.POSSESSIVES:
        said = noun_phrase(r, start, "qualifier") if r.np_starts(start) else None
        while isinstance(said, Match) and r.word(said.end) == "and" and r.np_starts(said.end + 1):
            more = noun_phrase(r, said.end + 1, "qualifier")  # "the garage and the office are a mess"
            if not isinstance(more, Match):
                break
            said = more
        if isinstance(said, Match) and said.end < end and (r.word(said.end) in lx.STATEMENT_VERBS
                                                             or state_verb_last(r, said.end, end)):
            return said.end  # "the plants are looking sad", "the bathroom with two toilets smells"
        if (isinstance(said, Match) and (r.word(said.end) in lx.ROOM_PARTS or (
                plain_subject(r, said.end) and not misspelt_name(r, said.end, said.end + 1)))
                and r.word(said.end + 1) in lx.STATEMENT_VERBS):
            return said.end + 1  # "the lobby floor is still wet", "the laptop battery is dead": a part of it
        if (r.word(start + 1) in lx.ROOM_PARTS and r.word(start + 2) in ("in", "of")
                and r.np_starts(start + 3)):
            room = noun_phrase(r, start + 3, "qualifier")  # "the floor in the lobby is wet": a part of it
            if isinstance(room, Match) and r.word(room.end) in lx.STATEMENT_VERBS:
                return room.end
        if not plain_word(r, start + 1):
            return None  # "the kitchen and the office": goals
        found = next((j for j in range(start + 2, min(start + 5, end)) if finite_verb(r.word(j))), None)
        return start + 2 if found is None and person_did(r, start, end) else found
    if r.head(start) is not None:  # "office wet - avoid it", "NB: lobby busy rn": a note's statement
        said = noun_phrase(r, start, "qualifier")
        state = said.end if isinstance(said, Match) else end
        if r.word(state) in lx.ROOM_PARTS and r.word(state + 1) in lx.STATEMENT_VERBS:
            return state + 1  # "Kitchen floor is wet": a part of it, the article left out
        return state if r.word(state) in lx.STATES and r.skip(state + 1, lx.NOW_WORDS) == end else None
    verb_at = start + 1 + (r.word(start + 1) in lx.STATED_ADVERBS)  # "Groceries just got delivered"
    verb = r.word(verb_at)
    if (w.isalpha() and r.head(start) is None and w not in lx.SEQUENCE_TIMES  # not "later come back to X"
            and (plain_subject(r, start) or w in lx.RELATIVE_FLOORS or w in lx.EVENT_WORDS
                 or w in lx.PEOPLE_NOUNS or w in _VAGUE_SUBJECTS or floor_surface(r, start))
            and (finite_verb(verb) or (verb.endswith("ed") and verb not in lx.LEXICON_WORDS))):
        return verb_at  # "Grandpa's napping", "Mom called", "downstairs needs to look nice", "floor's wet"
    return None


def vague_talk(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is about the day in general (:data:`_VAGUE_SUBJECTS`: *things are
    piling up*), naming no room, object or floor (*the things to check are ...* lists goals)."""
    return r.word(start) in _VAGUE_SUBJECTS and not any(names_place(r, k) for k in range(start, end))


_VAGUE_SUBJECTS = frozenset({"things", "stuff", "everything"})
"""Subjects of a statement about the day in general (*things are piling up*, *everything is a mess*), which
the lexicon knows in lists too (*things to do:*), so no bare noun."""
_ENOUGH = Phrases((("is", "enough"), ("'s", "enough"), ("suffices",)))
_ONE_OF_THEM = frozenset(("one", "of", them) for them in ("them", "those", "these"))


def state_verb_last(r: Reader, k: int, end: int) -> bool:
    """Whether the word at ``k`` is a verb the translator does not know that ends the clause ``[k, end)``
    after its subject (*the bathroom smells*, *the fridge hums*, *the oven beeped*): a third-person or past
    form (*-s*, *-ed*), no word of the lexicon, the scene or a misspelt name (*the office sinks* is refused
    with its *did you mean*)."""
    w = r.word(k)
    return k == end - 1 and (w in lx.SENSED_STATES or (
        w.isalpha() and w.endswith(("s", "ed")) and w not in lx.LEXICON_WORDS and r.head(k) is None
        and not misspelt_name(r, k, k + 1)))


_HOW_OFTEN = frozenset({"always", "usually", "often", "sometimes", "constantly", "regularly"})
"""Between a statement's subject and its verb (*the kids always rock on them*): the verb follows."""


def person_did(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is a person (*my mum*, *the neighbours*) and a verb the translator
    does not know (*gave*, *bought*, *fixed*) or any verb in the past (*flooded*), or anything else (*the
    cat*) and such a verb in the past (*knocked*), naming no room, object or floor but where it happened (*my
    mum gave it to me*, *my son flooded it*, *the dog knocked something over in the bedroom*: the bedroom
    kept as a mention): a statement about people or things; with a place otherwise (*my mum expects it
    upstairs*) it is left to the parser, which refuses it."""
    often = r.word(start + 2) in _HOW_OFTEN  # "the kids always rock on them", "the cat often knocks it over"
    verb = r.word(start + 2 + often)
    person = (r.word(start) in lx.POSSESSIVES or r.word(start + 1) in lx.PEOPLE_NOUNS
              or ((verb.endswith("ed") or (often and verb.endswith("s"))) and plain_subject(r, start + 1)))
    places = [k for k in range(start, end) if names_place(r, k)]
    where = next((j for j in range(start + 3, end) if r.word(j) in lx.LOCATIVE), None)
    known = verb in lx.LEXICON_WORDS and not verb.endswith("ed") and not (
        often and verb not in lx.STRUCTURAL and verb not in lx.POSITIVE_VERBS)
    return (person and verb.isalpha() and not known
            and not misspelt_name(r, start + 1, start + 3)
            and (not places or (where is not None and all(k > where for k in places))))


def plain_word(r: Reader, i: int) -> bool:
    """Whether the word at ``i`` is a word of no role in the grammar (the noun of *the guests*, *my mum*)."""
    w = r.word(i)
    return w.isalpha() and (w not in lx.STRUCTURAL or w in lx.FLOOR_WORDS) and w not in lx.POSITIVE_VERBS \
        and r.head(i) is None  # "the floor's still wet": the floor of a room


def plain_subject(r: Reader, i: int) -> bool:
    """Whether the word at ``i`` can be a bare noun subject (*Laundry's done*, *people are asleep*): a word of
    no role in the grammar, which the lexicon knows as a noun if at all."""
    w = r.word(i)
    return plain_word(r, i) and (w not in lx.LEXICON_WORDS or w in lx.NOUN_WORDS)


def finite_verb(word: str) -> bool:
    """Whether ``word`` is the verb of a statement after its subject (*the guests arrive*, *the kids
    made*)."""
    return word in lx.STATEMENT_VERBS or word in lx.STATED_VERBS


def mentions(r: Reader) -> tuple[NounPhrase, ...]:
    """The rooms and objects a statement names (*the bedroom with the teddy bear*), which *there* may point
    back to."""
    found: list[NounPhrase] = []
    k = 0
    while k < len(r):
        said = noun_phrase(r, k, "qualifier") if r.np_starts(k) and r.word(k) not in lx.PRONOUNS else None
        if isinstance(said, Match) and isinstance(said.node, Described):
            found.append(said.node)
            k = said.end
        else:
            k += 1
    return tuple(found)
