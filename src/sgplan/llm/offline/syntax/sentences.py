"""Syntax rules for a whole sentence: how it opens (*Whenever X, ...*, *If X, ...*, *Until Y, ...*, *After
X, ...*, *Only after X, ...*, *Before Y, ...*, *On your way to Y, ...*, *In the kitchen, ...*), its body,
and the condition that may close it (*... if X*, *... whenever X*, *... only after X*).

A sentence is read to its last word, or refused naming the words left over: no part of a mission is ever
dropped (:func:`mission_sentence`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.syntax.actions import action, after_conjunction
from sgplan.llm.offline.syntax.body import after_all, body
from sgplan.llm.offline.syntax.context import negated
from sgplan.llm.offline.syntax.floors import floor_words
from sgplan.llm.offline.syntax.links import (
    at_end,
    comma_or_then,
    done_closing,
    done_words,
    link,
    near_said,
    skip_subject,
    skip_until_subject,
    working,
)
from sgplan.llm.offline.syntax.negation import passive_end
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.qualifiers import head_kind
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal
from sgplan.llm.offline.syntax.rules import RuleSet
from sgplan.llm.offline.syntax.tree import (
    Action,
    AfterAll,
    Body,
    Described,
    FloorPlace,
    FloorSpec,
    IfRule,
    Link,
    MissionSentence,
    Negation,
    OnlyAfterPost,
    OnlyAfterSentence,
    OnlyIfPost,
    PlainAction,
    PlainSentence,
    Postfix,
    PrefixedSentence,
    Pronoun,
    RelativeFloor,
    Rule,
    RuleSentence,
    RulesPost,
    SentenceBody,
    UntilSentence,
    UpThere,
    WheneverRule,
)
from sgplan.llm.offline.text import Tok

OPENINGS: RuleSet[SentenceBody] = RuleSet("sentence opening")


def mission_sentence(r: Reader) -> Parse[MissionSentence]:
    """A sentence of the mission, read to its last word (else refused, naming what is left)."""
    delay = next((k for k in range(1, len(r)) if r.word(k) in lx.TIME_UNITS and (
        r.word(k - 1).isdigit() or r.word(k - 1) in lx.NUMBER_WORDS or r.word(k - 1) in lx.FEW)), None)
    if delay is not None:  # "wait 5 min", "in ten minutes", "for a few minutes"
        return Refusal(rf.left_over(r.quote(max(delay - 2, 0), delay + 1)))
    r = strict_order_first(while_there_as_once(r))
    contradicted = order_remark_after_then(r)
    if contradicted is not None:
        return contradicted
    i, opener = 0, None
    # "And the whole time, ..."; not "And while you're at it, ...", which also adds goals (as *also*)
    lead_and = 1 if r.word(0) in ("and", "but", "also") and r.word(1) != "while" else 0
    said = r.phrase(lead_and, lx.WHOLE_MISSION)
    if said is not None and r.word(lead_and + len(said)) == "," and said[0] not in lx.WAYPOINT_OPENERS:
        i = lead_and + len(said) + 1  # "The whole time, keep out of X."
        opener = r.quote(0, i - 1)
    if i == 0 and r.word(0) in ("and", "but", "so") and ordered_opening(r, 1):
        i = 1  # "And after that, X." / "But before that, X." / "And once you're done, X.": as without "and"
    precedes = None
    if r.at(i, *lx.BEFORE_THAT) or r.word(i) in lx.FIRST:
        i += 2 if r.at(i, *lx.BEFORE_THAT) else 1
        i += 1 if r.word(i) == "," else 0
        precedes = r.quote(0, i)
    opened = after_all_opening(r, i)
    if opened is not None:
        i = opened.end
    lead = link(r, i)
    if not isinstance(lead, Match):
        return lead
    if opened is not None:
        lead = Match(Link(True), lead.end)
    floor, start = floor_opening(r, lead.end)
    said_body = sentence_body(r, start)
    if not isinstance(said_body, Match):
        return said_body
    if isinstance(floor, RelativeFloor) and not floor.robot_there and leaves_floor_first(said_body.node):
        # "Go upstairs, then come back down to the kitchen": the visit upstairs names no place
        return Refusal(rf.floor_left_at_once(r.quote(0, start)))
    if (precedes is not None or lead.node.sequence or r.word(0) in lx.LAST) and isinstance(
            said_body.node, PlainSentence) and not said_body.node.body.items:
        return Refusal(rf.order_without_goal(r.quote(0, len(r))))  # "Last: the office" is not set aside
    if (precedes is None and not lead.node.sequence and isinstance(said_body.node, PlainSentence)
            and (any(r.trailing_after(k) == len(r) - k for k in range(max(0, len(r) - 4), len(r)))
                 or closes_done(r)
                 or carries_it(said_body.node.body))):
        lead = Match(Link(True), lead.end)  # "Go to the office. Visit the kitchen afterwards.": as "Then ..."
    rest = link(r, said_body.end, sequence_too=False)
    if not isinstance(rest, Match):
        return rest
    if rest.end < len(r):
        return Refusal(rf.left_over(r.quote(rest.end, len(r))))
    return Match(MissionSentence(opener, precedes, lead.node, said_body.node, "order" in r.words,
                                 r.span(0, len(r)), r.announced, r.after_item, floor,
                                 opened.node if opened is not None else None, order_free(r),
                                 r.marker is not None), len(r))


def leaves_floor_first(said: SentenceBody) -> bool:
    """Whether the first action of a sentence opened by a floor move (*Upstairs, ...*, *Go upstairs, then
    ...*) goes off that floor (*... then come back down to the kitchen*): no goal is said on it (not *heat
    something up*: no verb of going)."""
    first = next((item for item in said.body.items if isinstance(item, PlainAction)), None) \
        if isinstance(said, PlainSentence) else None
    verbs = set(first.action.verbs.words) if first is not None else set()
    return bool(verbs & lx.FLOOR_CHANGES) and bool(verbs & lx.GOING_VERBS)


def strict_order_first(r: Reader) -> Reader:
    """A sentence of one clause that closes with its strict order (*Go into the dining room only after
    that.*, *Sit on the couch only then.*, *Only go into the dining room after that.*) with the order words
    moved before the clause, as *Only after that, go into the dining room.* says it: the clause is the one
    goal that waits. ``r`` itself when it is not such a sentence (a comma, a joiner or an order word in the
    clause leaves which goal waits open: refused by the body's rules)."""
    closing = next((k for k in range(len(r)) if (said := r.phrase(k, lx.STRICT_SEQ)) is not None
                    and said[0] == "only" and k + len(said) == len(r)), None)
    if closing is not None:
        start, end, order = 0, closing, r.toks[closing:]
    elif r.word(0) == "only" and len(r) > 3 and r.phrase(len(r) - 2, lx.AFTER_THAT) is not None:
        start, end, order = 1, len(r) - 2, (r.toks[0], *r.toks[len(r) - 2:])
    else:
        return r
    if start == end:
        return r
    if set(r.words[start:end]) & (lx.LIST_JOINERS | lx.STRICT_WORDS):
        return strict_closing_after_and(r, closing) if closing is not None else r
    comma = Tok(",", order[-1].end, order[-1].end)
    return replace(r, toks=(*order, comma, *r.toks[start:end]))


def strict_closing_after_and(r: Reader, closing: int) -> Reader:
    """*A, and go to B only after that* (B's own clause, a verb after the last *and*, closes with the strict
    order): *A, and only after that, go to B*, which it says with its words moved; ``r`` itself unless the
    clause of B holds no other joiner or order word (*A and B only after that*, with no verb of its own, is
    left to the body's rules, which refuse it: does only B wait, or both?) and nothing before it negates
    (*A without touching X, and B only after that*: does B wait for the not touching too?)."""
    joined = max((k for k in range(1, closing) if r.word(k) == "and"), default=None)
    if (joined is None or r.word(joined + 1) not in lx.POSITIVE_VERBS
            or set(r.words[joined + 1:closing]) & (lx.LIST_JOINERS | lx.STRICT_WORDS)
            or negated(r, joined)):
        return r  # a negation before it ("A without touching X, and B only after that"): after what?
    order = r.toks[closing:]
    comma = Tok(",", order[-1].end, order[-1].end)
    return replace(r, toks=(*r.toks[:joined + 1], *order, comma, *r.toks[joined + 1:closing]))


def ordered_opening(r: Reader, i: int) -> bool:
    """Whether the words at ``i`` open a sentence with its place in the order (*after that*, *before that*,
    *first*, *once you're done*, *after all that*)."""
    lead = link(r, i)
    return (r.at(i, *lx.BEFORE_THAT) or r.word(i) in lx.FIRST or after_all_opening(r, i) is not None
            or (isinstance(lead, Match) and lead.node.sequence))


def order_free(r: Reader) -> bool:
    """Whether *in either / any order* closes a clause of the sentence (before a comma or its end), other than
    one about a group said in one phrase (:func:`group_remark`)."""
    return any((said := r.phrase(k, lx.ANY_ORDER)) is not None and r.word(k + len(said)) in ("", ",")
               and not group_remark(r, k) for k in range(len(r)))


def group_remark(r: Reader, k: int) -> bool:
    """Whether the order remark at ``k`` closes an action joined by *and* to the one before it that acts on
    one group (*go to the dining room and check both chairs in any order*): the remark is about the group,
    and the actions stay one clause (the chairs of the dining room), not independent tasks."""
    end = k - (1 if r.word(k - 1) == "," else 0)
    verb = max((j for j in range(1, end) if r.word(j - 1) == "and" and r.word(j) in lx.POSITIVE_VERBS),
               default=None)
    if verb is None or set(r.words[verb:end]) & {",", "and", "then", "or"}:
        return False
    return any(w in ("both", "all", "each", "every") or w.isdigit() or w in lx.NUMBER_WORDS
               or ((head := r.head(j)) is not None and head.plural)
               for j, w in enumerate(r.words[verb:end], verb))


def order_remark_after_then(r: Reader) -> Refusal | None:
    """*Go to the kitchen, then the office, in any order*: a remark leaving the order free right after one
    goal said after *then* contradicts it (the order, or the remark?): refused. After several goals (*...,
    then the office and the bedroom in any order*) the remark is about them, and read."""
    for k in range(len(r)):
        said = r.phrase(k, lx.ANY_ORDER)
        if said is None or r.word(k + len(said)) not in ("", ","):
            continue
        start = k - (1 if r.word(k - 1) == "," else 0)
        then = max((j for j in range(start) if r.phrase(j, lx.THEN_NEXT) is not None), default=None)
        if then is not None and not set(r.words[then + 1:start]) & (lx.LIST_JOINERS - {"then"}):
            return Refusal(rf.order_remark_after_then(r.quote(0, k + len(said))))
    return None


def after_all_opening(r: Reader, i: int) -> Match[AfterAll] | None:
    """*After all that, ...* / *Once you've done both, ...* / *When all three are done, ...* opening the
    sentence at ``i`` (the same words as in a sentence: :func:`.body.after_all`), or ``None``."""
    found = after_all(r, i, (), False)
    return found if isinstance(found, Match) and isinstance(found.node, AfterAll) else None


def closes_done(r: Reader) -> bool:
    """Whether the sentence ends in *when you're done* / *once you've finished* (*Go to the office when
    you're done.*): it follows the sentence before it."""
    return any(done_closing(r, k) for k in range(1, len(r)))


def while_there_as_once(r: Reader) -> Reader:
    """``r`` with *While you're (still) (in) there,* opening it read as *Once there,*: at the place named
    last, so after it (*... then go to the office. While you're there, check the laptop.*); *up there* is its
    floor (:func:`floor_opening`)."""
    if r.word(0) != "while":
        return r
    k = r.skip(skip_subject(r, 1), ("still",))
    k += r.word(k) == "in"
    if not r.at(k, "there", ","):
        return r
    return replace(r, toks=(Tok("once", r.toks[0].start, r.toks[0].end), *r.toks[k:]))


def carries_it(said: Body) -> bool:
    """Whether ``said`` starts by carrying what was named before (*Bring it to the table.*, a list item
    *bring them to the kitchen*, *Carry to the table.*): it was taken in the sentence before, so the
    destination follows it."""
    first = said.items[0] if said.items else None
    return (isinstance(first, PlainAction) and first.action.phrases is not None
            and bool(set(first.action.verbs.words) & lx.CARRY_VERBS)
            and (first.action.carried_on or all(isinstance(p, Pronoun) for p in first.action.phrases.items)))


def floor_opening(r: Reader, i: int) -> tuple[FloorSpec | None, int]:
    """*On the top floor, ...*, *Upstairs, ...*, *While you're upstairs, ...*, *While you're (up) on floor 2,
    ...*: the floor of the sentence's goals, and where its body starts; *While you're in the kitchen, ...* is
    *In the kitchen, ...* (the body starts at *in*)."""
    k = r.skip(skip_subject(r, i + 1), ("still",)) if r.word(i) == "while" else i  # "while you're still up"
    if k > i and r.word(k) in lx.BACK_THERE and r.word(k + 1) in lx.FLOOR_PREPOSITIONS:
        k += 1  # "while you're up on the top floor"
    if r.word(k) in lx.RELATIVE_FLOORS and r.word(k + 1) == ",":
        return RelativeFloor(r.word(k), robot_there=k > i), k + 2  # "while you're upstairs": where it is
    if k > i and r.word(k) in lx.BACK_THERE and r.at(k + 1, "there", ","):
        return UpThere(r.word(k)), k + 3  # "while you're up there, ...": the floor of the goal named last
    j = k + 1 if r.word(k) in lx.FLOOR_PREPOSITIONS else k
    said = floor_words(r, j + (1 if r.word(j) == "the" else 0)) if j > k else None
    if said is not None and r.word(said.end) == ",":
        return said.node, said.end + 1
    if k > i and r.word(k) in lx.SCOPE_IN and r.np_starts(k + 1):
        return None, k  # "while you're in the kitchen, ...": the room of the sentence
    return None, i


def sentence_body(r: Reader, i: int) -> Parse[SentenceBody]:
    """The sentence after its lead words: an opening rule of :data:`OPENINGS`, else a plain body."""
    comma = r.skip(i + 1, frozenset({","})) - i - 1  # "And, uh, whenever you ...": the sound is dropped
    condition = r.phrase(i + 1 + comma, lx.WHENEVER) or r.phrase(i + 1 + comma, lx.CONDITION_WORDS)
    if r.word(i) in lx.CONDITION_OPENERS and condition:
        i += 1 + comma  # "And whenever you ...", "But if you ...": a new condition, not a continuation
    found = OPENINGS.first(r, i)
    return found if found is not None else plain(r, i)


@OPENINGS.rule("whenever X, Y")
def whenever_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*Whenever / every time X, Y* and the rules joined to it."""
    if r.phrase(i, lx.WHENEVER) is None:
        return None
    return rules_sentence(r, i)


@OPENINGS.rule("when done with X, Y")
def done_with_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*When done with the garage, Y*: the garage, then Y."""
    done = done_words(r, i)
    if not done or r.word(i + done) not in lx.DONE_WITH or not r.np_starts(i + done + 1):
        return None
    return with_main_clause(r, i, prefixed(r, i + done + 1, prefix_last=False))


@OPENINGS.rule("if X, Y")
def condition_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*If / when / in case X, Y* and the rules joined to it."""
    return rules_sentence(r, i) if r.phrase(i, lx.CONDITION_WORDS) is not None else None


@OPENINGS.rule("until Y, X")
def until_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*Until / till (you have reached) Y, stay out of X*."""
    if r.word(i) not in lx.UNTIL_OPENERS and not r.at(i, "up", "until"):
        return None
    target = action(r, skip_until_subject(r, i + (2 if r.word(i) == "up" else 1)), in_condition=True)
    if not isinstance(target, Match):
        return target
    rest = body(r, comma_or_then(r, target.end))
    return rest if not isinstance(rest, Match) else Match(UntilSentence(target.node, rest.node), rest.end)


@OPENINGS.rule("only after X, Y")
def only_after_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*Only after / only once / not before / not until X, Y* and the rules joined to it."""
    if r.phrase(i, lx.ONLY_AFTER) is None:
        return None
    before = after_conjunction(r, i + 2)
    if not isinstance(before, Match):
        return before
    rest = body(r, comma_or_then(r, before.end))
    if not isinstance(rest, Match):
        return rest
    rules = more_rules(r, rest.end)
    if not isinstance(rules, Match):
        return rules
    return Match(OnlyAfterSentence(before.node, rest.node, rules.node, True), rules.end)


@OPENINGS.rule("after X, Y")
def after_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*After / once X, Y*: X, then Y (see :func:`with_main_clause`)."""
    if r.word(i) not in ("after", "once") or r.phrase(i, lx.AFTER_THAT):
        return None
    if at_time(r, i + 1):
        return Refusal(rf.order_by_a_time(r.quote(i, at_time(r, i + 1))))
    end = r.words.index(",", i) if "," in r.words[i:] else len(r)
    if set(r.words[i + 1:end]) & lx.COPULAS and not_inside(r, i + 1, end):
        return Refusal(rf.condition_not_inside(r.quote(i, end)))  # "Once you're down by the garage, ..."
    return with_main_clause(r, i, prefixed(r, i + 1, prefix_last=False))


def with_main_clause(r: Reader, i: int, said: Parse[SentenceBody]) -> Parse[SentenceBody]:
    """``said``, a sentence opened at ``i`` by *after / once / when done with / before X*, refused when
    nothing follows X (no comma, no *then*, no goal): *Go to the kitchen. After the office.* is the next
    step, as learners write *after*, or the sentence before it, after X? So is one whose X took the goal after
    its comma as a list (*Before the office, the fridge.*: the fridge first, or both after?)."""
    if not (isinstance(said, Match) and isinstance(said.node, PrefixedSentence) and not said.node.body.items
            and said.node.postfix is None):
        return said
    phrases = said.node.prefix.phrases
    if phrases is not None and len(phrases.items) > 1 and any(
            t.text == "," and phrases.span.start <= t.start < phrases.span.end for t in r.toks):
        return Refusal(rf.prefix_took_the_goals(r.quote(i, len(r))))
    if not {",", "then"} & set(r.words[i + 1:]):
        return Refusal(rf.after_before_or_then(r.quote(i, len(r))))
    return said


def at_time(r: Reader, i: int) -> int:
    """The end of a time or an event named at ``i`` after *before* / *after* / *once* opening a sentence
    (*lunch*, *the guests*), which orders nothing the plan knows (with a comma after it, it is set aside
    before the sentence is read); 0 when there is none."""
    k = i + (1 if r.word(i) in lx.ARTICLES else 0)
    return k + 1 if r.word(k) in lx.EVENT_WORDS else 0


@OPENINGS.rule("on your way to Y, X")
def on_the_way_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*On your way (up / down / over) to the lobby, check the couch*: the couch, then the lobby."""
    way = r.phrase(i, lx.ON_THE_WAY)
    j = i + len(way or ()) + (r.word(i + len(way or ())) in lx.WAY_TOWARDS)
    if way is None or r.word(j) not in ("to", "into") or not r.np_starts(j + 1):
        return None
    said = prefixed(r, j, prefix_last=True)
    if not isinstance(said, Match) or not isinstance(said.node, PrefixedSentence):
        return said
    return Match(replace(said.node, on_the_way=True), said.end)


@OPENINGS.rule("on your way back from X, Y")
def way_back_from_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*On your way back (up / down) from the office, check the oven*: the office, then the oven."""
    way = r.phrase(i, lx.ON_THE_WAY)
    j = i + len(way or ())
    if way is None or r.word(j) != "back":
        return None
    j += 1 + (r.word(j + 1) in lx.WAY_TOWARDS)
    if r.word(j) != "from" or not r.np_starts(j + 1):
        return None
    return prefixed(r, j + 1, prefix_last=False)


@OPENINGS.rule("before Y, X")
def before_first(r: Reader, i: int) -> Parse[SentenceBody]:
    """*Before going to Y, X*: X, then Y; *before you enter Y, you must / have to / need to X*: Y, and not
    before X. Not *before Y, A, then B* (does B come before Y too?), nor *before you go (anywhere) near Y, X*
    (stay out of Y until X, or go there after X?)."""
    if r.word(i) != "before":
        return None
    if r.word(i + 1) in lx.BEFORE_PRONOUNS:  # "Before it, X.": the goal named last, or all said so far?
        return Refusal(rf.before_pronoun(r.quote(i, i + 2)))
    if at_time(r, i + 1):
        return Refusal(rf.order_by_a_time(r.quote(i, at_time(r, i + 1))))
    end = next((k for k in range(i, len(r)) if r.word(k) == ","), len(r))
    if near_said(r, i, end):
        return Refusal(rf.before_near(r.quote(i, end)))
    said = with_main_clause(r, i, prefixed(r, i + 1, prefix_last=True))
    if not isinstance(said, Match) or not isinstance(said.node, PrefixedSentence):
        return said
    move = said.node.prefix
    if (move.verbs.floor is not None and move.phrases is None) or move.moved is not None or (
            move.phrases is not None and all(isinstance(p, FloorPlace) for p in move.phrases.items)):
        # "before you go upstairs, check the bathroom": the goals are done before the move, on the floor
        # left (the move would single them out on the floor reached), and where the move ends is no goal;
        # so for "before you come up from down here, grab X, then ...": the move took X along
        return Refusal(rf.before_floor_move(r.quote(i, end)))
    items = said.node.body.items
    if r.word(i + 1) != "to" and any(isinstance(item, Link) and item.sequence for item in items):
        return Refusal(rf.before_then(r.quote(i, said.end)))
    kept_out = kept_out_before(r, i, said.node, said.end)
    if kept_out is not None:
        return kept_out
    if r.says(lx.OBLIGED, i + 1, said.end) or r.phrase(i + 1, lx.BEFORE_ENTERING) is not None:
        # "before you enter Y, you must go to X", "before you go into Y, X": Y, and not before X
        return Match(replace(said.node, strict=True), said.end)
    return said


def kept_out_before(r: Reader, i: int, said: PrefixedSentence, end: int) -> Parse[SentenceBody]:
    """*Before you go to Y, avoid X* / *b4 kit, no liv rm* (the sentence read from ``i`` to ``end``): X kept
    out of until Y, as *don't enter X until Y*; with goals beside the prohibition, or a prohibition of its
    own time (*the whole time*, *until Z*), refused (before Y too?). ``None`` when it prohibits nothing."""
    negations = [item for item in said.body.items if isinstance(item, Negation)]
    if not negations:
        return None
    if len(negations) != len(said.body.items) or any(n.until is not None or n.whole for n in negations):
        return Refusal(rf.before_with_prohibition(r.quote(i, end)))
    kept = Body(tuple(replace(n, until=said.prefix) for n in negations))
    return Match(PlainSentence(None, kept, said.postfix), end)


@OPENINGS.rule("only <do X> after Y")
def only_verb_after(r: Reader, i: int) -> Parse[SentenceBody]:
    """*Only enter the living room after you have been to the kitchen*, *only pop into X once you've been to
    Y* (any verb, as in any action): as *... only after ...*."""
    w = r.word(i + 1)
    verb = w in lx.POSITIVE_VERBS or (w.isalpha() and not r.np_starts(i + 1) and w not in lx.STRUCTURAL
                                      and w not in lx.ONLY_FOLLOWERS)
    if r.word(i) != "only" or not verb:
        return None
    said = body(r, i + 1, only_verb=True)
    if not isinstance(said, Match):
        return said
    if r.word(said.end) not in ("after", "once"):
        return Refusal(rf.only_before_a_verb(r.rest(said.end)))
    before = after_conjunction(r, said.end + 1)
    if not isinstance(before, Match):
        return before
    kept = kept_out_after(r, before.end)  # "..., and keep out of the bathroom (the entire time)"
    if kept is not None:
        body_kept = Body(said.node.items + kept.node.items)
        return Match(OnlyAfterSentence(before.node, body_kept, (), False), kept.end)
    return Match(OnlyAfterSentence(before.node, said.node, (), False), before.end)


def kept_out_after(r: Reader, i: int) -> Match[Body] | None:
    """*, and keep out of X (the whole time)* / *, and never enter X* closing the sentence at ``i`` after a
    condition: prohibitions of the whole mission only, read beside it; ``None`` when the words there are
    not that."""
    if not r.at(i, ",", "and"):
        return None
    said = body(r, i + 2)
    if not isinstance(said, Match) or said.end != len(r) or not said.node.items:
        return None
    kept = all(isinstance(item, Negation) and item.until is None for item in said.node.items)
    return said if kept else None


def prefixed(r: Reader, i: int, prefix_last: bool) -> Parse[SentenceBody]:
    """The prefix clause at ``i`` (up to its comma; a passive of the grammar's verbs may close it: *once the
    oven is checked, ...*), the body after it and a closing condition."""
    prefix = after_conjunction(r, i)
    if not isinstance(prefix, Match):
        return prefix
    passive = passive_end(r, prefix.end)  # "once the oven is checked, ..." (not "... checked and X, ...")
    state = state_said(r, prefix.node) if passive == prefix.end else None
    if state is not None:  # "once the kitchen is fine, ..."
        return Refusal(rf.state_condition(r.quote(i, min(state + 2, len(r)))))
    if (r.word(prefix.end) == "," and r.text[r.toks[prefix.end].start:r.toks[prefix.end].start + 1] == "("
            and r.word(prefix.end + 1) in lx.POSITIVE_VERBS):
        # "When you're done in the kitchen (check the microwave), ...": what is done there, or a step after?
        close = next((k for k in range(prefix.end + 1, len(r)) if r.word(k) == ","), len(r))
        return Refusal(rf.aside_after_prefix(r.quote(i, prefix.end), r.quote(prefix.end + 1, close)))
    gerund = prefix.end + (1 if r.word(prefix.end) == "," else 0)
    if working(r.word(gerund)):
        # "when you're done in the kitchen (,) checking the oven, Y": part of what is done first, or a step?
        close = next((k for k in range(gerund, len(r)) if r.word(k) in (",", "then")), len(r))
        return Refusal(rf.work_after_prefix(r.quote(i, prefix.end), r.quote(gerund, close)))
    rest = body(r, comma_or_then(r, passive if r.word(passive) in (",", "then") else prefix.end))
    if not isinstance(rest, Match):
        return rest
    post = postfix(r, rest.end, 0)
    if not isinstance(post, Match):
        return post
    return Match(PrefixedSentence(prefix.node, prefix_last, rest.node, post.node), post.end)


def plain(r: Reader, i: int) -> Parse[SentenceBody]:
    """A body, after *In the kitchen,* (the room of the sentence) when said, and a closing condition."""
    scope = None
    if r.word(i) in lx.SCOPE_IN and r.np_starts(i + 1) and r.word(i - 1) not in lx.POSITIVE_VERBS:
        room = noun_phrase(r, i + 1, "qualifier")
        if isinstance(room, Refusal):
            return room
        assert room is not None
        if r.word(room.end) == "," and isinstance(room.node, Described) and head_kind(room.node) == "room":
            scope, i = room.node, room.end + 1
    said = body(r, i)
    if not isinstance(said, Match):
        return said
    tail = trailing_prohibitions(r, said.end)
    post = postfix(replace(r, toks=r.toks[:tail.end]) if tail else r, said.end, said.node.actions)
    if not isinstance(post, Match):
        return post
    if tail is None:
        return Match(PlainSentence(scope, said.node, post.node), post.end)
    return Match(PlainSentence(scope, said.node, post.node, tail.node), len(r))


def trailing_prohibitions(r: Reader, i: int) -> Match[Body] | None:
    """After a closing condition at ``i`` (*X, but only after Y*): *, and stay out of Z (the whole time)* /
    *, and never enter Z* closing the sentence, as a body of whole-mission prohibitions only (``end``: where
    the condition ends); ``None`` when there is none (then the condition must close the sentence)."""
    if not (r.phrase(i, lx.ONLY_AFTER) or r.at(i, *lx.ONLY_IF)):
        return None
    for k in range(len(r) - 1, i, -1):
        if not r.at(k, ",", "and"):
            continue
        said = body(r, k + 2)
        if not isinstance(said, Match) or said.end != len(r) or not said.node.items:
            return None
        whole = all(isinstance(item, Negation) and item.until is None
                    and (item.whole or lx.GLOBAL_NEG & set(item.marker)) for item in said.node.items)
        return Match(said.node, k) if whole else None
    return None


def rules_sentence(r: Reader, i: int) -> Parse[SentenceBody]:
    """*Whenever X, Y* / *If X, Y* at ``i``, and the rules joined to it."""
    first = condition_rule(r, i)
    if not isinstance(first, Match):
        return first
    rules = more_rules(r, first.end)
    if not isinstance(rules, Match):
        return rules
    return Match(RuleSentence((first.node, *rules.node)), rules.end)


def more_rules(r: Reader, i: int) -> Parse[tuple[Rule, ...]]:
    """Further condition rules joined by *and*, *but* or commas from ``i`` (*whenever you enter the kitchen,
    go to the living room, and whenever ...*; *if X, Y, and if Z, W*). Anything else after them is left to
    the end check (it is never dropped)."""
    rules: list[Rule] = []
    while i < len(r):
        k = r.skip(i, lx.RULE_JOINERS)
        if k == i and r.word(i - 1) not in lx.RULE_JOINERS:
            break
        rule = condition_rule(r, k)
        if not isinstance(rule, Match):
            if rule is None:
                break
            return rule
        rules.append(rule.node)
        i = rule.end
    return Match(tuple(rules), i)


def antecedent(r: Reader, i: int) -> Parse[Action]:
    """The condition of the rule at ``i`` (after *whenever* / *if* ...), or ``None`` if no rule starts
    there."""
    whenever = r.phrase(i, lx.WHENEVER)
    word = r.phrase(i, lx.CONDITION_WORDS)
    if whenever is None and word is None:
        return None
    start = i + len(whenever or word or ())
    ever = r.phrase(start, lx.EVER)
    j = start + (len(ever) if ever else 0)
    k = skip_subject(r, j)
    if set(r.words[j:k]) & lx.THING_SUBJECTS:  # "if it is open, ...": a state, not where the robot is
        return Refusal(rf.state_condition(r.quote(i, min(k + 2, len(r)))))
    if r.word(k) in lx.WISH_VERBS:  # "and if you want the office": an optional goal
        return Refusal(rf.optional_condition(r.quote(i, k + 1)))
    return trigger(r, start) if whenever else condition(r, start)


def condition_rule(r: Reader, i: int) -> Parse[Rule]:
    """One rule at ``i``: *whenever X, Y* or *if X, Y* (Y one action)."""
    said = antecedent(r, i)
    if not isinstance(said, Match):
        return said
    rest = consequent(r, comma_or_then(r, said.end))
    if not isinstance(rest, Match):
        return rest
    rule = make_rule(r, i, said, rest.node, comma_or_then(r, said.end), rest.end)
    return rule if isinstance(rule, Refusal) else Match(rule, rest.end)


def make_rule(r: Reader, i: int, said: Match[Action], consequent: Body, after_start: int,
              after_end: int) -> Rule | Refusal:
    """The rule at ``i`` with condition ``said`` and ``consequent``; the consequent follows the condition
    when the words ``[after_start, after_end)`` say *afterwards*, or a *then* opens it (*if you go into X,
    then Y*, *..., would you then Y*). *If you ever go into X, Y* is refused: people read it as once and as
    on each visit of X alike (*if you go into X at any point, Y* is read once). A consequent that says
    *first* (*..., check the fridge first*: before the visit, or first on it?) is refused."""
    word = r.phrase(i, lx.CONDITION_WORDS)
    if any(isinstance(item, PlainAction) and (item.trailing == "first" or item.action.first)
           for item in consequent.items):
        return Refusal(rf.first_in_consequent(r.quote(i, after_end)))
    if r.phrase(i, lx.WHENEVER) is not None or word is None:
        return WheneverRule(said.node, consequent)
    if r.says(lx.EVER_UNCLEAR, i + len(word), said.end):
        return Refusal(rf.once_or_each_visit(r.quote(i, said.end)))
    # "if you go into X, then Y" / "..., would you then Y": the consequent after that visit, as the words say
    then = word != ("when",) and "then" in r.words[said.end:min(said.end + 4, after_end)]  # (not "when")
    afterwards = r.says(lx.AFTERWARDS, after_start, after_end) or then
    return IfRule(" ".join(word), said.node, consequent, afterwards)


def trigger(r: Reader, i: int) -> Parse[Action]:
    """The place of *whenever you enter the kitchen* (not a negative one)."""
    k = skip_subject(r, i)
    if r.word(k) in lx.NEGATING:
        return Refusal(rf.negative_trigger())
    return after_conjunction(r, k, in_condition=True)


def condition(r: Reader, i: int) -> Parse[Action]:
    """The condition of *if you go to the kitchen*: one action (*ever* skipped here, refused by
    :func:`make_rule`); more (*... and open the fridge*, *... after the office*) is refused."""
    ever = r.phrase(i, lx.EVER)
    k = skip_subject(r, i + (len(ever) if ever else 0))
    if r.word(k) in lx.NEGATING:
        return Refusal(rf.negative_condition())
    if (r.word(k) in _PERCEIVING or r.words[k:k + 2] == ("come", "across")) and r.word(k + 1) != "yourself":
        return Refusal(rf.state_condition(r.quote(i, min(k + 3, len(r)))))  # "if you see a bowl": sensed
    said = after_conjunction(r, k, in_condition=True)
    if not isinstance(said, Match):
        return said
    if not_inside(r, k, said.end):  # "if you go near / past the kitchen"
        return Refusal(rf.condition_not_inside(r.quote(i, said.end)))
    if "again" in r.words[k:said.end]:  # "if you go there again": a second visit, not expressed
        return Refusal(rf.condition_again(r.quote(i, said.end)))
    visited = said.end + (1 if r.word(said.end) in lx.UNTIL_DONE_LINKS else 0)
    if r.word(visited) in lx.VISIT_PARTICIPLES and r.word(visited + 1) in ("", ",", "then"):
        said = Match(said.node, visited + 1)  # if LR visited -> ...: the robot was there
    elif (state := state_said(r, said.node)) is not None:  # "if the kitchen is ok, ..."
        return Refusal(rf.state_condition(r.quote(i, min(state + 2, len(r)))))
    if r.word(said.end) in lx.CONDITION_END or r.phrase(said.end, lx.NEG_STARTS):
        return Refusal(rf.condition_goes_on(r.rest(said.end)))
    return said


_PERCEIVING = frozenset({
    "see", "sees", "saw", "seen", "seeing", "notice", "notices", "noticed", "noticing", "spot", "spots",
    "spotted", "spotting", "find", "finds", "found", "finding", "hear", "hears", "heard", "hearing", "smell",
    "smells", "smelled", "smelt"})
"""Verbs of what the robot senses, which a condition cannot be about (*if you see a bowl, bring it ...*,
*if you come across the bowl*; *if you find yourself in X* is a visit). Kept here, not in the lexicon, whose
words all count as read."""
_NOT_INSIDE = frozenset({"near", "past", "by", "beside", "outside"})
"""Words of a condition's place that say the robot is not inside it (*if you go near the kitchen*)."""
_STOPPING = frozenset({"stop", "stops", "drop", "swing", "pop", "come"})
"""Verbs after which *by* is a visit (*if you stop by the kitchen*)."""


def not_inside(r: Reader, start: int, end: int) -> bool:
    """Whether the words ``[start, end)`` of a condition say the robot is near a place, not in it (*near*,
    *past*, *by*, not *stop by*), as typed: an alias reads *go near* as *go into*, for a place to keep away
    from."""
    typed = r.quote(start, end).lower().split()
    return any(w in _NOT_INSIDE and (k == 0 or typed[k - 1] not in _STOPPING) for k, w in enumerate(typed))


def state_said(r: Reader, said: Action) -> int | None:
    """Where the copula is when ``said``, read as a visit from a bare noun phrase, is its subject (*if the
    kitchen is ok*, *once the kitchen's fine*): a state of the place, which the robot cannot sense (whatever
    words after the copula the action's tail took as fillers); ``None`` otherwise."""
    if said.verbs.words or said.phrases is None:
        return None
    end = next((k for k, t in enumerate(r.toks) if t.start >= said.phrases.span.end), len(r))
    return end if r.word(end) in lx.COPULAS or r.word(end) == "'s" else None


def consequent(r: Reader, i: int) -> Parse[Body]:
    """What a condition asks for: one action, or one errand (:func:`one_errand`); with several it is not
    clear which belong to it (refused)."""
    said = body(r, i)
    if isinstance(said, Match) and said.node.actions > 1 and not one_errand(r, said.node):
        return Refusal(rf.several_actions_after_condition())
    return said


def one_errand(r: Reader, said: Body) -> bool:
    """Whether ``said`` is a visit of one room and, after *and*, an action on things named without a room
    (*swing by the kitchen afterwards and check the microwave*): one errand in that room, the things looked
    for there, so both belong to the condition (after *then*, or with a room named in the second action,
    which actions belong to it stays unclear)."""
    actions = [item.action for item in said.items if isinstance(item, PlainAction)]
    links = [item for item in said.items if isinstance(item, Link)]
    if len(actions) != 2 or len(actions) + len(links) != len(said.items) or any(
            link.strict or link.waypoint for link in links):
        return False
    visit, act = actions
    if visit.phrases is None or act.phrases is None or len(visit.phrases.items) != 1:
        return False
    visited = [h for k in range(len(r)) if r.toks[k].start >= visit.phrases.span.start
               and r.toks[k].end <= visit.phrases.span.end and (h := r.head(k)) is not None]
    acted = [h for k in range(len(r)) if r.toks[k].start >= act.span.start and r.toks[k].end <= act.span.end
             and (h := r.head(k)) is not None]
    joined = r.text[visit.span.end:act.span.start].lower().replace(",", " ").split()
    rest = [r.word(k) for k in range(len(r)) if r.toks[k].start >= act.span.start]
    if {"too", "also"} & set(rest) or any(rest[k:k + 2] == ["as", "well"] for k in range(len(rest))):
        return False  # "..., and have a look at the oven too": a goal of its own, or of that errand?
    return (joined[-1:] == ["and"] and all(w in lx.CONDITION_AFTERWARDS for w in joined[:-1])
            and len(visited) == 1 and visited[0].kind == "room" and bool(acted)
            and all(h.kind == "object" for h in acted))


def postfix(r: Reader, i: int, body_actions: int) -> Parse[Postfix]:
    """A condition closing a body: *only after X*, *only if X*, *whenever X* / *if X* (the body its
    consequent), or, after *and* / *but*, a rule with its own consequent (*S, and whenever X, T*)."""
    if i >= len(r):
        return Match(None, i)
    joined = r.word(i - 1) in ("and", "but")
    if body_actions > 1 and not joined and (r.phrase(i, lx.WHENEVER) or r.phrase(i, lx.CONDITION_WORDS)
                                            or r.at(i, *lx.ONLY_IF)):
        return Refusal(rf.several_actions_before_condition(r.rest(i)))
    if r.phrase(i, lx.ONLY_AFTER):
        found = after_conjunction(r, i + 2)  # a passive may close it: "only after the plant is watered"
        return closed(r, Match(found.node, passive_end(r, found.end)) if isinstance(found, Match) else found,
                      OnlyAfterPost)
    if r.at(i, *lx.ONLY_IF):
        return closed(r, condition(r, i + 2), OnlyIfPost)
    said = antecedent(r, i)
    if not isinstance(said, Match):
        return said if said is not None else Refusal(rf.cannot_understand(r.rest(i)))
    if joined and said.end < len(r) and (r.word(said.end) not in (",", "then") or r.word(said.end + 1)):
        # "S, and whenever X(,) T": the rule has its own consequent (spoken, often with no comma)
        own = condition_rule(r, i)
        if not isinstance(own, Match):
            return own
        first, end, body_is_consequent = own.node, own.end, False
    else:  # "S whenever X" / "S if X": the body is the consequent
        # "S afterwards, when X": said right before the condition (not "A, after that B, and when X")
        k = i
        while k > 0 and r.word(k - 1) in (",", "and", "but"):
            k -= 1
        rule = make_rule(r, i, said, Body(()), max(0, k - 2), k)
        if isinstance(rule, Refusal):
            return rule
        first, end, body_is_consequent = rule, said.end, True
    rules = more_rules(r, end)
    if not isinstance(rules, Match):
        return rules
    return closed(r, Match((first, *rules.node), rules.end),
                  lambda more: RulesPost(more, body_is_consequent))


def closed(r: Reader, found: Parse[Any], make: Callable[[Any], Postfix]) -> Parse[Postfix]:
    """``make(found.node)`` when ``found`` matched and only fillers follow it to the end of the sentence."""
    if not isinstance(found, Match):
        return found
    end = at_end(r, found.end)
    if not isinstance(end, Match):
        return end
    return Match(make(found.node), end.end)
