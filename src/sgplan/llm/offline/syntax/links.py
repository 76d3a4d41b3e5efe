"""Syntax rules for the words between clauses: fillers (*please*, *also*, *at some point*, *could you*),
sequence words (*then*, *after that*, *finally*, *only after that*, *once you're done*), *on the way,*.

:func:`link` reads a run of such words; the :class:`.tree.Link` it returns says whether they ordered what
follows after what came before (and how). Only the words listed in the lexicon are skipped, so nothing
with a meaning is ever dropped here.
"""

from __future__ import annotations

import re

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.syntax.learner import learner_english
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal
from sgplan.llm.offline.syntax.tree import Link


def link(r: Reader, i: int, sequence_too: bool = True) -> Parse[Link]:
    """The fillers and, with ``sequence_too``, the sequence words from ``i``; always a match (possibly of
    no words), except for *on your way there* without what is on the way, which is refused."""
    sequence = strict = waypoint = False
    while i < len(r):
        step = link_word(r, i, sequence_too)
        if isinstance(step, Refusal):
            return step
        if step is None:
            break
        kind, i = step
        sequence = sequence or kind != "filler"
        strict = strict or kind == "strict"
        waypoint = waypoint or kind == "waypoint"
    return Match(Link(sequence, strict, waypoint), i)


def link_word(r: Reader, i: int, sequence_too: bool) -> tuple[str, int] | Refusal | None:
    """One filler or sequence phrase at ``i``: its kind (``filler``, ``sequence``, ``strict``,
    ``waypoint``) and where it ends; ``None`` when the words here are not one."""
    if sequence_too and (strict := r.phrase(i, lx.STRICT_SEQ)) is not None:
        return "strict", i + len(strict)  # "..., and only after that B": B strictly after
    closing = closing_at(r, i)
    if closing:
        return "filler", closing
    way = r.phrase(i, lx.ON_THE_WAY)
    if way is not None:
        return on_the_way(r, i, way, sequence_too)
    if sequence_too and (done := done_sequence(r, i)) is not None:
        return "sequence", done
    if sequence_too and (seq := r.phrase(i, lx.SEQ_WORDS)) is not None:
        if seq == ("next",) and r.word(i - 1) not in ("", ",", "and", "then") and r.np_starts(i + 1):
            return Refusal(rf.next_without_to(r.quote(i, i + 3)))  # "the corridor next the dining room"
        return "sequence", i + len(seq)
    if sequence_too and (after := after_as_then(r, i)) is not None:
        return after
    said = r.phrase(i, lx.TIME_FILLERS) or r.phrase(i, lx.POLITE)
    if said in lx.ANY_TIME and r.word(i - 1) in (",", "and") and set(r.words[:i]) & {"then", "after"}:
        return Refusal(rf.any_time_in_sequence(r.quote(0, i + len(said))))  # "A, then B, and at some point C"
    if said is not None and not checks_a_state(r, i, said):
        return "filler", i + len(said)
    w = r.word(i)
    if w == "only" and i == 0 and only_as_but(r):
        return "filler", 1
    if w in lx.FIRST and r.word(i + 1) in lx.PLACE_PREPOSITIONS and r.word(i - 1) not in ("", ","):
        return None  # "go first to the kitchen": the action's (it comes first)
    said_before = i - 1 - (r.word(i - 1) in lx.CONTACT_SUBJECTS)  # "visit X, you begin with Y"
    if w in lx.FIRST and i > 1 and r.word(said_before) == "," and (r.np_starts(i + 1)
                                                                   or r.word(i + 1) in lx.POSITIVE_VERBS):
        return Refusal(rf.first_mid_sentence(r.quote(0, i + 1)))  # "check X, first the oven": first of all?
    if w in lx.SOFTENERS and softened_step(r, i):
        return "filler", i + 1
    if w == "," or (w in lx.FILLERS and w not in lx.NOT_FILLERS_HERE) or w in lx.HESITATIONS:
        return "filler", i + 1
    return None


_SAID_OPTIONAL = re.compile(
    r"\b(?:optional|optionally|no pressure|definitely|certainly|not (?:\w+ )?sure|if possible|priority|"
    r"important|urgent|nice[- ]to[- ]have|needed|necessary|required|essential|spare|"
    r"if you(?:'re| are)? (?:want|like|feel|have|can|get|free)|if there'?s time|if not)\b",
    re.IGNORECASE)
"""Words of the mission that say a step may be left out (*..., then maybe the oven, no pressure*), or that
another step is surer than a softened one (*maybe the oven, then definitely the couch*): *maybe* is then no
softener (the remark itself may be set aside, so the whole text is searched). Not *when you get a minute*,
which wraps the whole mission (*When you get a minute, ... maybe have a look at the vase*)."""


def softened_step(r: Reader, i: int) -> bool:
    """Whether *maybe* / *perhaps* at ``i`` softens the step after it: a verb (not a preposition: *maybe on
    the couch* guesses where something is) follows it at the start of a sentence or after a comma or *and*
    (*Perhaps look in on the office*, *..., and maybe have a peek at the couch*), or a step follows *then*
    (*and then maybe the bed*), and nothing in the mission says a step may be left out (*..., then maybe the
    oven, no pressure*). *A and maybe B*, with no verb, stays an optional B (refused)."""
    before, after = r.word(i - 1), r.word(i + 1)
    if _SAID_OPTIONAL.search(r.text) or after in _NOT_VERBS:
        return False
    if before == "then":
        return after in lx.POSITIVE_VERBS or after in lx.DETERMINERS
    return before in ("", ",", "and") and after in lx.POSITIVE_VERBS


_NOT_VERBS = lx.PLACE_PREPOSITIONS | frozenset({"onto", "off", "up", "down", "out", "over", "from", "for",
                                                "near", "under", "behind", "somewhere", "upstairs",
                                                "downstairs"})
"""Words of :data:`.lexicon.POSITIVE_VERBS` that are no verb: after *maybe* they say where a thing may be."""


def checks_a_state(r: Reader, i: int, said: tuple[str, ...]) -> bool:
    """Whether the wrapper ``said`` at ``i`` is the verb of a check of a thing's state (*make sure (that) the
    oven is off*): a noun phrase and a state verb follow it in its clause (it is then read as *check*)."""
    k = i + len(said)
    if r.phrase(i, lx.CHECK_WRAPPERS) != said or not r.np_starts(k):
        return False
    end = next((j for j in range(k, len(r)) if r.word(j) in ("", ",", "then")), len(r))
    if set(r.words[k:end]) & lx.KEPT_AWAY_STATES or any(r.phrase(j, lx.OFF_LIMITS) for j in range(k, end)):
        return False  # "make sure the kitchen is off limits": a prohibition, read as one
    return any(r.word(j) in lx.STATE_VERBS for j in range(k, end))


def only_as_but(r: Reader) -> bool:
    """Whether the sentence's first word *only* is the joiner *but* (*Only please stay out of the dining
    room*, *Only, don't go upstairs*): a prohibition follows it (after *please* or a comma), and no order
    word is in the sentence (*only please go to X after Y* stays *only <do X> after Y*; *only go to X* may
    mean nowhere else, so it is not read as *but*)."""
    k = 1 + sum(1 for w in r.words[1:3] if w in lx.ONLY_AS_BUT_AFTER)
    return r.phrase(k, lx.NEG_STARTS) is not None and not set(r.words) & lx.ONLY_ORDER_WORDS


def on_the_way(r: Reader, i: int, way: tuple[str, ...],
               sequence_too: bool) -> tuple[str, int] | Refusal | None:
    """*On the way (there), stop at X* (X before the goal named last), *on your way back (up)* (after what
    came before, like *then*), not *on your way up to Y* (a destination: a sentence opener); *on your way
    there* with nothing on the way is refused."""
    n = len(way) + (1 if r.word(i + len(way)) == "there" else 0)
    after = r.word(i + n)
    verb = after in lx.POSITIVE_VERBS and after not in lx.WAY_BACK | {"to", "into"}
    if sequence_too and (after == "," or verb):
        return "waypoint", i + n
    to = i + n + (after in lx.WAY_TOWARDS and r.word(i + n + 1) in ("to", "into"))  # "on your way up to"
    if (sequence_too and n == len(way) and r.word(to) in ("to", "into") and r.np_starts(to + 1)
            and r.word(i - 1) not in ("", ",", "and", "then")):
        return "sequence", to  # "swing by X on your way (up) to the kitchen": X, then the kitchen
    if r.word(i + len(way)) == "there":
        return Refusal(rf.on_your_way_there())
    if i > 0 and r.word(to) in ("to", "into") and r.np_starts(to + 1):
        return Refusal(rf.way_back_to(r.quote(i, to + 1)))  # "A, and on your way (up) to X, Y": Y before X
    if to > i + n and r.np_starts(to + 1):
        return None  # "On your way up to X, grab Y": Y, then X (.sentences.on_the_way_first)
    back_end = r.skip(i + len(way), lx.WAY_BACK)
    if r.word(back_end) == "from":  # "On your way back from X, Y": X, then Y
        return None if i == 0 else Refusal(rf.way_back_from_mid(r.quote(i, back_end + 1)))
    if back_end > i + len(way) and r.word(back_end) in ("to", "into") and r.np_starts(back_end + 1):
        return Refusal(rf.way_back_to(r.quote(i, back_end + 1)))  # "on your way back to X, Y": Y before X
    if sequence_too and r.word(i + len(way)) in lx.WAY_BACK:
        return "sequence", back_end
    return None


def after_as_then(r: Reader, i: int) -> tuple[str, int] | Refusal | None:
    """*go first to the kitchen, after to the bedroom*, *and after you touch the toilet*: *after* between
    clauses, with no place after it, is *then* (as learners of English write it); *, after you go to X* and
    *, after the X* could also mean before it, which is refused unless the mission bears a learner's mark
    (:mod:`.learner`: *go in kitchen, after the living room*). Opening a sentence it is *then* before
    an obligation (*After you must go to X.*) and, in a sentence with no comma after it (no main clause to
    come), before a plain verb or a preposition of place (*After go to X.*, *After to the office.*)."""
    if r.word(i) != "after":
        return None
    # ", after it you must X" (not opening a sentence): "it" is the clause before, as "after that" is
    obliged = obliged_after(r, i + 1 if r.word(i + 1) == "it" and r.word(i - 1) in (",", "and") else i)
    if obliged is not None and r.word(i - 1) in ("", ",", "and"):
        return "sequence", obliged  # "after you have to check X": after that, you have to check X
    if r.word(i - 1) == "" and "," not in r.words[i + 1:] and (
            r.word(i + 1) in lx.AFTER_AS_THEN - {","} or (r.word(i + 1) in lx.POSITIVE_VERBS
                                                        and not is_gerund(r.word(i + 1)))):
        return "sequence", i + 1  # "Go to X. After go to Y.": no clause of its own, so no "after Y"
    if r.word(i - 1) not in ("", "and") and r.word(skip_subject(r, i + 1)) in lx.FUTURE_AUXILIARIES:
        # "Check the oven, after you will go to the office": learners' "afterwards you will", or "after"?
        return Refusal(rf.after_before_or_then(r.quote(i, min(len(r), skip_subject(r, i + 1) + 3))))
    if r.word(i - 1) not in (",", "and"):
        return None
    nxt = r.word(i + 1)
    if nxt in lx.AFTER_AS_THEN or (nxt in lx.POSITIVE_VERBS and not is_gerund(nxt)
                                   and not has_main_clause(r, i + 1)):
        return "sequence", i + 1  # "after to the bedroom", "after go up in the dining room", "after again"
    k = skip_subject(r, i + 1)
    verb = r.word(k) in lx.POSITIVE_VERBS or r.word(k) in lx.AVOID_VERBS
    # "First the living room, after the dining room": after a sentence opening with "first" (and no other
    # order word), "after" is the next step of the count (before it, what "first" names would not be first)
    counted = (r.word(0) in lx.FIRST and r.word(i - 1) == ","
               and not any(r.phrase(j, lx.SEQ_WORDS) for j in range(1, i)))
    if k > i + 1 and verb and not has_main_clause(r, k):
        if r.word(i - 1) == "and" or counted or carried_after_taking(r, i, k) or learner_english(r.text):
            return "sequence", k  # "and after you touch the toilet": and then
        return Refusal(rf.after_before_or_then(r.quote(i, min(len(r), k + 4))))
    if r.np_starts(i + 1) and r.word(i + 1) not in lx.DETERMINERS - lx.ARTICLES and not has_main_clause(r, i):
        if counted or learner_english(r.text):  # "go in kitchen, after the living room": then
            return "sequence", i + 1
        # "go to the office and after the kitchen": the kitchen after (as learners write) or before?
        return Refusal(rf.after_before_or_then(r.quote(i, min(len(r), i + 5))))
    return None


def carried_after_taking(r: Reader, i: int, k: int) -> bool:
    """Whether *, after you bring it to Y* (the carry verb at ``k``, *after* at ``i``) follows a clause that
    opens with taking a thing (*Take the bowl from the kitchen, after you bring it in the bedroom*): *it* is
    the thing taken, carried only once taken, so *after* is *then*; a clause that opens otherwise (*wash the
    cup, after you bring it to the sink*) may be done after the carrying (refused)."""
    if (r.word(k) not in lx.CARRY_ON_VERBS - lx.PAST_CARRY_VERBS or r.word(k + 1) not in ("it", "them")
            or set(r.words[i + 1:k]) - {"you"}):
        return False  # "after you have brought it": done before (refused)
    start = max((j for j in range(i - 1) if r.word(j) in (",", "and", "then")), default=-1) + 1
    return r.word(start) in lx.TAKING_VERBS


def obliged_after(r: Reader, i: int) -> int | None:
    """Where the verb is in *after you must / have to / need to X* at ``i`` (as learners write *after that,
    you must X*: a clause of time never says what must be done); ``None`` otherwise, and when X keeps out of
    something (*after you must not go to X*: a prohibition for part of the mission, left to be refused)."""
    k = i + 1 + (1 if r.word(i + 1) in lx.OBLIGED_SUBJECTS else 0)
    said = r.phrase(k, lx.OBLIGED)
    verb = k + len(said) if said is not None and k > i + 1 else None
    if verb is None or r.phrase(verb, lx.NEG_STARTS) or r.word(verb) not in lx.POSITIVE_VERBS:
        return None
    return verb


def near_said(r: Reader, start: int, end: int) -> bool:
    """Whether *near* was said in ``[start, end)`` where the lexicon reads it as *into* (*go (anywhere) near
    Y*): after *before*, it may mean staying out of Y until then, or going there after (refused)."""
    return any(r.word(k) == "into" and "near" in r.quote(k, k + 1).lower() for k in range(start, end))


def is_gerund(word: str) -> bool:
    """Whether ``word`` is a verb's *-ing* form (*going*), not a plain form ending so (*bring*)."""
    return word.endswith("ing") and word not in lx.BASE_VERBS_IN_ING


def working(word: str) -> bool:
    """Whether ``word`` is a verb of the grammar in its *-ing* form (*once done checking X*)."""
    return is_gerund(word) and word in lx.POSITIVE_VERBS


def has_main_clause(r: Reader, i: int) -> bool:
    """Whether a clause after *after you ...* at ``i`` is followed by its main clause (*after you go to X,
    check Y*: a comma then an order, not a remark such as *, whatever one*)."""
    return any(r.word(k) == "," and (r.word(k + 1) in lx.AVOID_VERBS - {"to", "in", "at", "on", "into"}
                                     or r.phrase(k + 1, lx.NEG_STARTS) is not None) for k in range(i, len(r)))


def closing_at(r: Reader, i: int) -> int:
    """The end of a sign-off or an aside that asks nothing at ``i`` (*thanks a lot*, *if possible*), which
    must close its clause (a comma or the end of the sentence follows; for an aside starting with *if* /
    *when*, a noun phrase may follow too: *then if you can the oven*, as no condition has no verb); 0 if there
    is none."""
    said = r.phrase(i, lx.CLOSING)
    if said is None:
        return 0
    end = i + len(said)
    closes = r.word(end) in ("", ",") or (said[0] in lx.CONDITION_OPENERS_OF_ASIDES and r.np_starts(end))
    return end if closes else 0


def done_words(r: Reader, i: int) -> int:
    """How many words at ``i`` say the previous step is over: *once you're done*, *when you have finished*,
    *after that is done* (0 if they do not); *with X* after them is not counted."""
    if r.word(i) not in lx.DONE_OPENERS:
        return 0
    n = r.skip(i + 1, lx.SUBJECT_FILLERS | lx.DONE_FILLERS) - i
    return n + 1 if r.word(i + n) in lx.DONE else 0


def done_sequence(r: Reader, i: int) -> int | None:
    """The end of *once you're done (with that) (,)* at ``i`` when it refers back to the step before (a
    sequence word then); ``None`` when it names what is done (*when done with the garage*) or is not
    there."""
    n = done_words(r, i)
    back = r.word(i + n) in lx.DONE_BACK and r.word(i + n + 1) in lx.DONE_BACK_ENDS
    if not n or (r.np_starts(i + n) and not back) or working(r.word(i + n)):
        return None  # "after finishing the kitchen", "once done checking X": what is done is said
    if r.word(i + n) in lx.DONE_WITH and (r.word(i + n + 1) not in lx.DONE_BACK or r.np_starts(i + n + 2)):
        return None
    k = i + n + (1 if r.word(i + n) in lx.DONE_WITH else 0)
    return k + (1 if r.word(k) in lx.DONE_BACK else 0)


def done_closing(r: Reader, i: int) -> int:
    """The length of *when you're done* / *once you've finished (with that)* at ``i`` ending the sentence
    (what it ends comes after what was said before, as with a closing *afterwards*), else 0."""
    n = done_words(r, i)
    if n and r.word(i + n) in lx.DONE_WITH and r.word(i + n + 1) in lx.DONE_BACK:
        n += 2  # "once you're finished with that"
    elif n and r.word(i + n) in lx.DONE_BACK:
        n += 1  # "once you're finished there"
    return n if n and i + n == len(r) else 0


def skip_subject(r: Reader, i: int) -> int:
    """After a conjunction (*after you have been to X*): the subject and auxiliaries before the verb."""
    while r.word(i) in lx.SUBJECT_FILLERS and not r.np_starts(i):
        i += 1
    return i


def skip_until_subject(r: Reader, i: int) -> int:
    """After *until* / *till*: the subject and auxiliaries, and a *not* between them that negates nothing
    (*until you have not seen the couch*, *till you not have been in X*: how French, Italian and Spanish
    writers say *until you have seen it*, their *tant que ... ne ... pas*; in English the negated reading
    asks for nothing that can happen, so the positive one is the only one meant)."""
    if r.at(i, "to", "have") or r.at(i, "to", "be"):
        return skip_subject(r, i + 1)  # "before to have seen the couch" (French "avant d'avoir vu")
    k = skip_subject(r, i)
    if k > i and r.word(k) == "not":
        return skip_subject(r, k + 1)
    return k


def comma_or_then(r: Reader, i: int) -> int:
    """After a condition or a prefix clause: the comma and *then* that close it."""
    i += 1 if r.word(i) == "," else 0
    return i + (1 if r.word(i) == "then" else 0)


def at_end(r: Reader, i: int) -> Parse[None]:
    """The end of a clause that must close the sentence: only fillers may follow."""
    rest = link(r, i, sequence_too=False)
    if not isinstance(rest, Match):
        return rest
    if rest.end < len(r):
        return Refusal(rf.cannot_understand(r.rest(rest.end)))
    return Match(None, rest.end)
