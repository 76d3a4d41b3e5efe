"""Syntax rules for the items of a sentence body: actions, prohibitions, sequence words, *first*, *via*,
*stay on this floor*, *X is off limits*, *after all three* ...

:func:`body` reads items with the rules of :data:`ITEMS` (tried in order at each position) until the body
ends: at the end of the sentence, or before a condition (*if*, *whenever*, *only after*), which the
sentence rules read.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Literal

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.syntax.actions import (
    action,
    action_after_then,
    action_then_ahead,
    after_conjunction,
    times_before_place,
)
from sgplan.llm.offline.syntax.links import closing_at, done_closing, done_words, is_gerund, link, near_said
from sgplan.llm.offline.syntax.negation import negation, off_limits, stay_on_floor
from sgplan.llm.offline.syntax.phrases import there_then_verb
from sgplan.llm.offline.syntax.qualifiers import names_rooms
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal
from sgplan.llm.offline.syntax.rules import RuleSet
from sgplan.llm.offline.syntax.tree import (
    Action,
    AfterAll,
    Body,
    CommaSequence,
    DoneWith,
    GoalsFirst,
    InlineAfter,
    InlineBefore,
    Item,
    Link,
    Negation,
    PlainAction,
    Waypoint,
)


class Skip:
    """Words of a body that say nothing here (a conjunction, a trailing *after*)."""


class End:
    """The body ends here (a condition follows)."""


ITEMS: RuleSet[Item | Skip | End] = RuleSet("body item")
Said = tuple[Item, ...]
"""The items read before, in the body."""
ItemParse = Parse[Item | Skip | End]


def body(r: Reader, i: int, only_verb: bool = False) -> Parse[Body]:
    """The items from ``i`` to the end of the body (``only_verb``: the body of *only <do X> after Y*, which
    ends at *after*)."""
    items: list[Item] = []
    while i < len(r):
        found = ITEMS.first(r, i, tuple(items), only_verb)
        if not isinstance(found, Match):
            return found if found is not None else Refusal(rf.cannot_understand(r.rest(i)))
        if isinstance(found.node, End):
            break
        if not isinstance(found.node, Skip):
            items.append(found.node)
        i = found.end
    restated = restated_first(r, items)
    return Refusal(rf.restated_first(restated)) if restated else Match(Body(tuple(items)), i)


def restated_first(r: Reader, items: list[Item]) -> str | None:
    """The words of a goal said again with *first* after the body put it in a sequence (*A, then B, but do B
    first*: B before A only, or B twice?), or ``None``. Without a sequence (*A and B, B first*) it only says
    the order."""
    said: set[str] = set()
    ordered = False
    for item in items:
        ordered = ordered or (isinstance(item, Link) and item.sequence)
        if not isinstance(item, PlainAction) or item.action.phrases is None:
            continue
        words = {r.text[np.span.start:np.span.end].lower() for np in item.action.phrases.items}
        if item.action.first and ordered and words & said:
            return r.text[item.action.span.start:item.action.span.end]
        said |= words
    return None


@ITEMS.rule("after all of them")
def after_all(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*(and / ,) after all three / after all of them / once you've done those (,)*."""
    k = i + (2 if r.at(i, ",", "and") else 1 if r.word(i) in (",", "and") else 0)
    phrase = r.phrase(k, lx.AFTER_ALL)
    if phrase is None:
        return None
    n = k + len(phrase)
    number = lx.NUMBER_WORDS.get(r.word(n))
    n += 1 if number is not None else 0
    n += 2 if r.at(n, "of", "them") or r.at(n, "of", "those") else 0
    if number is None and n == k + len(phrase) and phrase[-1] in ("all", "both") and r.np_starts(n):
        return None  # "after all the bedrooms": an ordinary noun phrase
    if number is None and phrase[-1] == "both":
        number = 2  # "once you've done both": two goals, checked as a number said
    return Match(AfterAll(r.quote(k, n), number), n + (1 if r.word(n) == "," else 0))


@ITEMS.rule("the whole time, avoid X")
def whole_time_first(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*..., and while you're out and about, avoid X* / *..., and the whole time, keep out of X*: words of
    the whole mission before a prohibition, inside a sentence, make it hold for the whole mission."""
    k = i + (2 if r.at(i, ",", "and") else 1 if r.word(i) in (",", "and", "but") else 0)
    said = r.phrase(k, lx.WHOLE_MISSION)
    if not before or said is None or r.word(k + len(said)) != "," or said[0] in lx.WAYPOINT_OPENERS:
        return None
    found = negation(r, k + len(said) + 1)
    if not isinstance(found, Match) or not isinstance(found.node, Negation):
        return found  # not a prohibition ("don't forget X"): read as it is
    return Match(replace(found.node, whole=True), found.end)


@ITEMS.rule("only after that")
def strict_link(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*..., and only after that B*: B strictly after what came before. Closing its clause (*..., and go to
    B only after that.*) it is refused: which goal waits is not said where the reading expects it."""
    said = r.phrase(i, lx.STRICT_SEQ)
    if said is None:
        return None
    after = r.word(i + len(said))
    opens = r.word(i - 1) in ("", ",", "and", "but", "then") or said[0] != "only"
    if after == "" or (after == "," and not opens):
        words = " ".join(w for w in said if w not in (",", "and", "but"))
        return Refusal(rf.strict_closing(r.quote(0, i + len(said)), words))
    return link(r, i)


@ITEMS.rule("conjunction before only after")
def before_only_after(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*..., but only after X* / *..., but not before X*: the conjunction says nothing."""
    if r.word(i) in ("but", "and", ",") and r.phrase(i + 1, lx.ONLY_AFTER):
        return Match(Skip(), i + 1)
    return None


@ITEMS.rule("when done with X")
def done_with(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*... when done with X*: X before the step it is said in."""
    done = done_words(r, i)
    if (not done or r.word(i + done) not in lx.DONE_WITH or not r.np_starts(i + done + 1)
            or done_closing(r, i)):
        return None  # not "... once you're finished with that.": a closing order
    found = action(r, i + done + 1)
    return Match(DoneWith(found.node), found.end) if isinstance(found, Match) else found


@ITEMS.rule("on the way / once done")
def way_link(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*on the way, X* / *and on your way back, X* / *once you're done, X*: a sequence link."""
    way = r.phrase(i + (1 if r.word(i) in ("and", ",") else 0), lx.ON_THE_WAY)
    if (not done_words(r, i) and way is None) or done_closing(r, i):
        return None  # "... when you're done.": a closing order (:func:`trailing_after`)
    found = link(r, i)
    return found if not isinstance(found, Match) or found.node.sequence else None


@ITEMS.rule("sign-off or aside")
def closing(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*thanks a lot*, *cheers*, *if possible*, *no rush* closing a clause: nothing to do (before a condition
    is looked for: *if possible* is none)."""
    end = closing_at(r, i)
    return Match(Skip(), end) if end else None


@ITEMS.rule("condition follows")
def condition_follows(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """The body ends before *if*, *when*, *only if*, *whenever*, *only after* (and, in *only <do X> after
    Y*, before *after*); not before a closing *when you're done* (:func:`trailing_after`)."""
    if done_closing(r, i):
        return None
    if (r.at(i, *lx.ONLY_IF) or r.phrase(i, lx.CONDITION_WORDS) or r.phrase(i, lx.ONLY_AFTER)
            or r.phrase(i, lx.WHENEVER) or (only_verb and r.word(i) in ("after", "once"))):
        return Match(End(), i)
    return None


@ITEMS.rule("trailing after")
def trailing_after(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*Go to the dining room after.*, *... when you're done.*: nothing more in the body (a sentence that
    ends so follows the one before it, :func:`.sentences.mission_sentence`). After two goals of the body
    (*the office and the kitchen afterwards*, *A, then B after*) it could be about the last or all of them:
    refused."""
    length = r.trailing_after(i) or done_closing(r, i)
    if not length:
        return None
    actions = [item for item in before if isinstance(item, PlainAction)]
    phrases = actions[-1].action.phrases if actions else None
    then_said = len(before) > 1 and isinstance(before[-2], Link) and before[-2].sequence  # "then B after"
    if ((len(actions) > 1 and not then_said and not after_one_goal(before[:-1]) and not actions[-1].goes_back)
            or (phrases is not None and len(phrases.items) > 1)):
        return Refusal(rf.trailing_after(r.quote(0, i + length)))
    return Match(Skip(), i + length)


def one_goal_said(before: Said) -> bool:
    """Whether ``before`` holds one action with one phrase, and nothing else that is a goal."""
    actions = [item for item in before if isinstance(item, PlainAction)]
    phrases = actions[0].action.phrases if len(actions) == 1 else None
    return phrases is not None and len(phrases.items) == 1


def after_one_goal(before: Said) -> bool:
    """Whether the last step of ``before`` is one action with one phrase, after a sequence word (*A, then
    B, and C afterwards*: after B is after A too, so both readings of *afterwards* agree)."""
    last: list[PlainAction] = []
    for item in reversed(before):
        if (isinstance(item, Link) and item.sequence) or isinstance(item, CommaSequence):
            break
        if isinstance(item, PlainAction):
            last.append(item)
    else:
        return False
    phrases = last[0].action.phrases if len(last) == 1 else None
    return phrases is not None and len(phrases.items) == 1


@ITEMS.rule("but first")
def goals_first(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*..., but first (go to) X* / *..., and before that X*: X before the steps said so far. *before it* /
    *before this*, as learners write *before that*, only after one goal (which *it* is then certain)."""
    before_it = r.word(i) == "before" and r.word(i + 1) in lx.BEFORE_PRONOUNS
    if before_it and before and (not one_goal_said(before) or i + 2 == len(r)):  # "... before it."
        return Refusal(rf.before_pronoun(r.quote(i, i + 2)))
    before_that = r.at(i, *lx.BEFORE_THAT) or before_it
    if not before or not (r.word(i) in lx.FIRST or before_that):
        return None
    j = i + (2 if before_that else 1)
    j += 2 if r.at(j, "of", "all") else 0
    j += 1 if r.word(j) == "," else 0
    found = after_conjunction(r, j)
    if not isinstance(found, Match):
        return found
    obliged = before_that and r.says(lx.OBLIGED, j, found.end)  # "but before this you must pass by X"
    return Match(GoalsFirst(before_that, found.node, r.rest(i), obliged), found.end)


@ITEMS.rule("A, then B, and C afterwards")
def and_then_afterwards(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*A, then B, and C afterwards* / *..., and C when you're done*: after one goal that ends a sequence
    (:func:`after_one_goal`), the conjunction before a clause closing the sentence with *afterwards* is a
    sequence word, since C comes after B either way."""
    n = 2 if r.at(i, ",", "and") else 1 if r.word(i) in (",", "and") else 0
    if not n or not after_one_goal(before):
        return None
    for k in range(i + n + 1, len(r)):
        if r.word(k) in (",", "then", "and", "or"):
            return None
        if r.trailing_after(k) == len(r) - k or done_closing(r, k):
            return Match(Link(True), i + n)
    return None


@ITEMS.rule("A, B, then C")
def comma_sequence(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """At a comma between two actions (*go to the kitchen, pop up to the bedroom, then ...*, *A, then B, C,
    and D*): a *then* in the sentence makes the comma-joined actions a sequence too, as people write them."""
    if not before or not (action_then_ahead(r, i) or action_after_then(r, i)):
        return None
    return Match(CommaSequence(), i + (2 if r.at(i, ",", "and") else 1))


@ITEMS.rule("where you X")
def where_you(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*enter the bathroom on floor 0, where you check the sink*: in that room, X (as *and check the sink
    there*: the action's objects are looked for in the room). After anything but one room (*the couch,
    where you ...*, *the kitchen and the office, where you ...*) it is refused: in which room?"""
    if not r.at(i, ",", "where", "you"):
        return None
    k = r.skip(i + 3, lx.MODALS)
    k += 2 if r.word(k) in lx.NEGATED_NEED_WORDS and r.word(k + 1) == "to" else 0  # "where you need to"
    if k >= len(r) or r.np_starts(k) or r.word(k) in lx.STRUCTURAL:
        return None
    if r.word(k) in lx.FINDING_VERBS:  # "the kitchen, where you can find the bowl": a hint, or a goal?
        return Refusal(rf.where_you_find(r.quote(i + 1, min(len(r), k + 3))))
    if not after_one_room(before):
        return Refusal(rf.where_after_no_room(r.quote(i + 1, min(len(r), k + 3))))
    return Match(Skip(), k)


@ITEMS.rule("and there X")
def and_there(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*go to the kitchen and there take the bowl*: *there* before the verb, as *take the bowl there* (in that
    room: the step's room context); after anything but one room it is refused (where is there?)."""
    if r.word(i - 1) != "and" or not there_then_verb(r, i):
        return None
    if not after_one_room(before[:-1] if before and isinstance(before[-1], Link) else before):
        return Refusal(rf.where_after_no_room(r.quote(i, min(len(r), i + 4))))
    return Match(Skip(), i + 1)


def after_one_room(before: Said) -> bool:
    """Whether the item said last is an action on one room (*go to the kitchen*)."""
    last = before[-1] if before else None
    phrases = last.action.phrases if isinstance(last, PlainAction) else None
    return phrases is not None and len(phrases.items) == 1 and names_rooms(phrases.items[0])


@ITEMS.rule("and have a look")
def and_have_a_look(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*go down to the lobby and have a (quick) look (around)*: a look at nothing named after one room is a
    look at that room, which its visit already asks (the words say nothing more); after anything but one
    room it is left to the action, which refuses it (a look at what?)."""
    if r.word(i - 1) != "and" or r.word(i) not in lx.LOOK_LIGHT_VERBS or not after_one_room(before):
        return None
    look = r.phrase(i + 1, lx.VERB_IDIOMS)
    if look is None or look[-1] not in lx.LOOK_NOUNS:
        return None
    k = i + 1 + len(look)
    k += 1 if r.word(k) in lx.LOOK_AROUND else 0
    return Match(Skip(), k) if r.word(k) in ("", ",", "then") else None


@ITEMS.rule("in between")
def in_between_link(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*A, then B, and in between (,) Y*: Y right before B, as *on the way, Y* puts it (B one goal after a
    sequence word; after a step of several goals the waypoint rule refuses). Not after *twice*
    (:func:`.actions.in_between`)."""
    k = r.skip(i, (",", "and"))
    if k == i or not r.at(k, "in", "between") or not any(isinstance(item, Link) and item.sequence
                                                           for item in before):
        return None
    end = k + 2 + (1 if r.word(k + 2) == "," else 0)
    if r.phrase(end, lx.NEG_STARTS) is not None or r.word(end) in lx.STAY:  # for part of the mission only
        return Refusal(rf.prohibition_in_between(r.quote(k, min(len(r), end + 4))))
    return Match(Link(True, waypoint=True), end)


@ITEMS.rule("link")
def link_item(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """Fillers and sequence words (*then*, *after that*, *please*)."""
    found = link(r, i)
    if not isinstance(found, Match) or found.end == i:
        return found if isinstance(found, Refusal) else None
    return found if found.node.sequence else Match(Skip(), found.end)


@ITEMS.rule("stay on this floor")
def stay_item(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*stay on this floor*, *keep to floor 1* (:func:`.negation.stay_on_floor`)."""
    return stay_on_floor(r, i, negated=False)


@ITEMS.rule("off limits")
def off_limits_item(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*X is off limits* (:func:`.negation.off_limits`)."""
    return off_limits(r, i)


@ITEMS.rule("negation")
def negation_item(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*never enter X*, *avoid X*, *without X* (:func:`.negation.negation`)."""
    return negation(r, i)


@ITEMS.rule("after X")
def inline_after(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*... after / once X*: X before the step it is said in."""
    if r.word(i) not in ("after", "once") or r.phrase(i, lx.AFTER_THAT):
        return None
    found = after_conjunction(r, i + 1)
    if not isinstance(found, Match):
        return found
    if between_clauses(r, i, found.end, before):
        return Refusal(rf.after_clause_between(r.quote(i - 1, found.end), r.quote(0, i - 1).rstrip(" ,")))
    return Match(InlineAfter(found.node), found.end)


def between_clauses(r: Reader, i: int, end: int, before: Said) -> bool:
    """Whether *after / once X* at ``i`` (ending at ``end``) stands between two clauses, after a goal and a
    conjunction: *A, and once you've been to X, B* (X before B only, or before A too?) or, at the end, *A
    and after going to X* (X after A, as learners write *and then*, or before it?)."""
    joined = r.word(i - 1) in ("and", "but") or (r.word(i - 1) == "," and r.word(end) == ",")
    said = any(isinstance(item, PlainAction) for item in before)
    return joined and said and ((r.word(end) == "," and end + 1 < len(r)) or end == len(r))


@ITEMS.rule("before X")
def inline_before(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*A before B*: B a step after A. Not *A, (but) before go to B*, which learners write for *before that,
    go to B* (B first), nor *A, and / but before B* closing the sentence (all that before B, or before that,
    B?), nor *A, and before you go to B, C* (is A before B too?): refused."""
    if r.word(i) != "before":
        return None
    nxt = r.word(i + 1)
    if nxt in lx.BEFORE_PRONOUNS:  # "A before it": which goal 'it' is, and whether it means 'before that'
        return Refusal(rf.before_pronoun(r.quote(i, i + 2)))
    if (r.word(i - 1) in (",", "and", "but") and nxt in lx.POSITIVE_VERBS and not is_gerund(nxt)
            and not r.np_starts(i + 1) and nxt not in lx.VERB_STOPS):
        return Refusal(rf.before_bare_verb(r.quote(i, i + 2)))
    found = after_conjunction(r, i + 1)
    if isinstance(found, Match) and near_said(r, i, found.end):
        return Refusal(rf.before_near(r.quote(i, found.end)))  # "check X before you go anywhere near Y"
    if isinstance(found, Match) and r.word(found.end) not in lx.CLAUSE_ENDS and (
            r.word(found.end) in lx.POSITIVE_VERBS or r.word(found.end) in lx.SUBJECT_FILLERS):
        # "A, but before you go to X you have to visit Y" (no comma): Y before X, or X then Y?
        said = i - 1 if r.word(i - 1) in ("and", "but") else i
        return Refusal(rf.before_clause_between(r.quote(i, found.end), r.quote(0, said).rstrip(" ,")))
    clause_after = isinstance(found, Match) and r.word(found.end) == "," and found.end + 1 < len(r)
    if (isinstance(found, Match) and found.node.phrases is not None and found.node.phrases.comma_list
            and r.word(i - 1) in (",", "and", "but", "then")):  # "A, then before X, Y": a list, or Y first?
        return Refusal(rf.before_clause_between(r.quote(i, found.end), r.quote(0, i - 1).rstrip(" ,")))
    if isinstance(found, Match) and (between_clauses(r, i, found.end, before)
                                     or (r.word(i - 1) == "then" and clause_after)):
        if found.end == len(r):  # "A, and before the couch.": all that before it, or before that, it?
            return Refusal(rf.before_bare_verb(r.quote(i, found.end)))
        return Refusal(rf.before_clause_between(r.quote(i - 1, found.end), r.quote(0, i - 1).rstrip(" ,")))
    return Match(InlineBefore(found.node), found.end) if isinstance(found, Match) else found


@ITEMS.rule("via")
def waypoint(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*go to Y via X* / *..., passing through X*: X on the way, before the goal Y just named."""
    k = i + (1 if r.word(i) == "," else 0)
    words = r.phrase(k, lx.WAYPOINT)
    if words is None or not before:
        return None
    if r.word(k - 1) in lx.PRONOUNS and lx.CARRY_VERBS & set(r.words[max(0, k - 4):k]):
        return Refusal(rf.carried_through(r.quote(k - 1, k + len(words))))  # "carry it through X": after it
    found = action(r, k + len(words))
    if not isinstance(found, Match):
        return found
    return Match(Waypoint(words, found.node, r.rest(k + len(words))), found.end)


@ITEMS.rule("conjunction")
def conjunction(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """*and*, *but*, *while*, *as* between actions say nothing more; *or* between actions is refused."""
    if r.word(i) == "or":
        return Refusal(rf.or_between_actions(r.rest(i)))
    during = r.phrase(i, lx.WHOLE_MISSION) if r.word(i) == "while" else None
    if during is not None:  # "X, and while you're at it, (sit on) Y": a joining word (Y too), never at 'it'
        end = i + len(during)
        if set(r.words[:i]) & {"then", "after"}:  # "A, then B, and while ..., C": after B, or at any time?
            return Refusal(rf.any_time_in_sequence(r.quote(0, end)))
        return Match(Skip(), end + (1 if r.word(end) == "," else 0))
    return Match(Skip(), i + 1) if r.word(i) in ("and", "but", "while", "as") else None


@ITEMS.rule("action")
def plain_action(r: Reader, i: int, before: Said, only_verb: bool) -> ItemParse:
    """An action, and what the words around it say of its place: *first* / *before that* after it, *X on
    the way*, *come back to X*."""
    if r.word(i) in lx.REFUSED_WORDS and not r.np_starts(i) and times_before_place(r, i) is None:
        # not "other bdrm" (a phrase), not "go twice to X" (the verb's)
        return Refusal(rf.cannot_understand(lx.REFUSED_WORDS[r.word(i)]))
    found = action(r, i)
    if not isinstance(found, Match):
        return found
    if before and isinstance(before[-1], PlainAction) and (refused := move_after_goal(r, i, found)):
        return refused
    j, on_the_way = found.end, False
    way = r.phrase(j, lx.ON_THE_WAY)
    if way is not None:
        direction = r.word(j + len(way))
        n = j + len(way) + (1 if direction in ("there", "up", "down") else 0)
        if direction in ("up", "down") and r.word(n) in lx.ON_THE_WAY_ENDS and not any(
                w in (direction, direction + "stairs") for w in r.words[:i]):
            # "check the kitchen, and the plant on your way up": on the way to what?
            return Refusal(rf.way_of_no_goal(r.quote(j, n)))
        if r.word(n) in lx.ON_THE_WAY_ENDS:  # "go up to X, and Y on your way up": Y, then X
            j, on_the_way = n, True
    rest = r.rest(j)
    trailing_word: Literal["first", "before that"] | None = None
    if not on_the_way and r.word(j) in lx.FIRST:
        trailing_word, j = "first", j + 1
    elif not on_the_way and r.at(j, *lx.BEFORE_THAT) and r.word(j + 2) in ("", ",", "and", "then"):
        trailing_word, j = "before that", j + 2
    j += 2 if trailing_word and r.at(j, "of", "all") else 0
    after = link(r, found.end, sequence_too=False)
    more = r.rest(after.end) if isinstance(after, Match) and after.end < len(r) else ""
    return Match(PlainAction(found.node, moved_first(r, i), goes_back(r, i), on_the_way, trailing_word, rest,
                             more), j)


def move_after_goal(r: Reader, i: int, found: Match[Action]) -> Refusal | None:
    """The refusal of a floor move said at ``i`` right after a goal: with no joining word (*go to the lobby
    all the way down, ...*: where the lobby is, or a move?), or after *and* with a *then* of its own (*check
    the oven and go upstairs, then the laptop*: the laptop after the oven too?); ``None`` otherwise."""
    said_before = i - 1
    while said_before > 0 and r.word(said_before) in lx.POSITIVE_VERBS:
        said_before -= 1  # ("and go all the way up": joined)
    if found.node.verbs.floor is not None and r.word(said_before) not in _JOINED:
        said = next((k for k in range(i, found.end) if r.word(k) in (",", "then")), found.end)
        return Refusal(rf.floor_move_after_goal(r.quote(i, said)))
    if found.node.moved is not None and r.word(said_before) == "and":
        return Refusal(rf.floor_move_then_after_goal(r.quote(said_before, found.end)))
    return None


_JOINED = frozenset({",", "and", "then", "but", "while", "as", ";", "next", "after", "before", "first"})
"""Words before an action that join it to the one before it; without one, a floor move said right after a
goal (*the lobby all the way down*) may say where that goal is rather than make a step of its own."""


def moved_first(r: Reader, i: int) -> bool:
    """Whether the action at ``i`` ends with *first* / *before that* / *on the way* (looked ahead, up to the
    next comma, *then* or *but*): it is then done before the step it is written after."""
    for j in range(i, len(r)):
        w = r.word(j)
        if w in lx.FIRST or (w == "before" and r.word(j + 1) == "that"):
            return True
        way = r.phrase(j, lx.ON_THE_WAY)
        if way is not None and r.word(j + len(way)) in lx.ON_THE_WAY_ENDS:
            return True  # "check the couch on the way": before the step
        if w in (",", "then", "but", "after", "before", "if", "until", "when", "whenever"):
            return False
    return False


def goes_back(r: Reader, i: int) -> bool:
    """Whether the verb words at ``i`` say *back* / *return* (*come back to the couch*)."""
    while r.word(i) in lx.POSITIVE_VERBS | lx.REVISIT_VERBS:
        if r.word(i) in lx.REVISIT_VERBS:
            return True
        i += 1
    return False

