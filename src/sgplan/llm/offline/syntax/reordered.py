"""Corrections said as a sentence of their own that change the order of the steps before them.

Spoken missions fix the order after the fact: *Go to the dining room and sit on a chair. Actually, first get
a bowl from the kitchen.*; *Go to the bed, then the couch. No wait, the couch first.*; *Go to the garage.
Then the office. No wait, office first, then the garage.* Each is read only in the shape in which a careful
reader takes one meaning; the correction words are set aside and said back:

- **a step added first**: *Actually,* (*Oh,*), then an order with *first* (at its start or its end)
  that names only rooms and objects the mission has not named before, and no other word of order,
  condition, negation or addition: it is read as *First, <order>.*, which comes before every goal said so
  far (or is refused as such, :mod:`.sentences`); after *No wait* or *I mean* a step may be taken back;
- **a prohibition added**: *Actually,* (*Oh,*), then a prohibition of places the mission has not
  named (*Actually, don't go through the kitchen.*): read without the correction words;
- **a later step moved first**: a correction, then a noun phrase (after *make it* / *do*, or not) and
  *first*, right after the mission's first goal sentence when that is goal phrases in a row (*A, then B*,
  one verb for all) and the phrase names what only one of them after the first names (its head, or the room
  that tells two of one kind apart): the sentence is read without it, and the phrase after it as *First,
  <phrase>* (*go to A. First, B.*); over three phrases or more, only when each says where it is (a room or
  a floor), since a bare object may be the one in the room of the phrase before it;
- **the last two steps swapped**: *(do) X before Y*, X and Y said word for word as the last goal phrase
  of the sentence before and the one before it, each phrase saying where it is: the sentence is read
  with the two swapped;
- **a phrase said instead**: *(make that) X instead of Y* or *forget (about) Y, (just) <verb> X*, where Y is
  the noun phrase the sentence before ends with, said word for word, and X names the same kind: that
  sentence is read with X in its place;
- **a correction heading**: correction words alone before a colon (*No, other way round: office first, then
  garage.*) are read with the sentence after it;
- **an order said again over several sentences**: a correction and a whole order said again that names
  again exactly the places of the sentences right before it (two or more, each saying nothing but places
  to go): those sentences are joined with it, and :mod:`.corrections` reads it as one
  sentence that says the order again.

Anything else is left as it was: read by :mod:`.corrections`, or refused there.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import NamedTuple

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.phrases import Phrases
from sgplan.llm.offline.syntax.corrections import (
    FORGET,
    goal_heads,
    joined,
    named_heads,
    order_start,
    order_verb,
    said_instead,
)
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.text import Tok

_ENDS = frozenset({"", ".", "!", "please", "thanks"})
"""Words a correction may close with after its *first* (*No wait, the couch first please.*)."""
_BEYOND_ORDER = (lx.NOT_A_SEQUENCE | frozenset(lx.NEGATING)
                 | frozenset({"instead", "too", "also", "again", "before", "after", "afterwards", "either",
                              "or", "each", "every", "only"}))
"""Words that make a correction say more than an order of places (read, or refused, by
:mod:`.corrections`)."""
_SAYS_MORE = _BEYOND_ORDER | (lx.ORDER_HEADS - lx.FIRST)
"""Words that make a correction say more than one step to put first."""
_ADDING = frozenset({"actually", "oh", ","})
"""The only correction words before a step added first: *No wait, check X first*, *I mean, check X first*
say something before was wrong (X instead of a step?), so they are not read as adding."""
_MORE_THAN_A_RULE = (_SAYS_MORE - frozenset(lx.NEGATING)) | lx.FIRST | frozenset({",", ";", "and", "just"})
"""Words after which a prohibition said after *Actually,* may say more than the rule it adds (a goal, *just*
X, *not first*)."""
_STEP_JOINERS = ((",", "then"), ("then",), (",", "and", "then"), ("and", "then"), (",", "after", "that", ","),
              ("and", "after", "that"), (",", "then", "after", "that"))
"""The words between the goal phrases of a sentence whose order a correction changes."""
_PUT = Phrases((("make", "it"), ("make", "that"), ("do",)))
"""Words before the phrase a correction moves (*Actually make it the couch first*, *do the living room before
the dining room*)."""
_STEP_WORDS = lx.HESITATIONS | lx.GREETINGS | lx.PLACE_PREPOSITIONS | frozenset(
    {"the", "a", "an", ",", ".", "!", "then", "and", "next", "up", "down", "over", "back", "please", "robot",
     "ok", "okay"})
"""Words a sentence of an order said again over several sentences may hold besides verbs of going and noun
phrases (an article too, of a phrase started again: *Go to the, uh, the empty room.*): anything else (*wait
there for five minutes*, *stay there*, *turn off the lights*) is something asked that the correction does
not say again, so the sentence is not taken back with the others."""


def reordered(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each correction sentence that changes the order of the steps before it applied (see
    the module docstring): the sentences it reorders rewritten, its correction words set aside."""
    out: list[Reader] = []
    joined_readers = correction_headings_joined(readers)
    for n, r in enumerate(joined_readers):
        start = said_instead(r) if out and not r.aside and r.marker is None else None
        if start is None:
            out.append(r)
            continue
        i = order_start(r, r.skip(start, (":",)))  # "No, other way round: office first, then ..."
        taken = r.toks[:i]
        first = added_first(r, start, i, out) or added_prohibition(r, start, i, out)
        if first is not None:
            out += [replace(r, toks=taken, aside=True), first]
            continue
        # "A, then B. No wait, B first. Then the clock.": right after B, or after all? Not read
        later_goals = goals_before(joined_readers[n + 1:])
        moved = moved_first(r, i, out) if not later_goals else None
        if moved is not None:
            out[-1:] = [moved.rest, replace(r, toks=r.toks[:moved.aside_end], aside=True), moved.first]
            continue
        ahead = moved_before(r, i, out) if not later_goals else None
        if ahead is not None:
            out[-1:] = [ahead, replace(r, aside=True)]
            continue
        swapped = substituted(r, i, out)
        if swapped is not None:
            out[-1] = swapped.sentence  # and "Actually, make that", "instead of Y" said back
            out += [replace(r, toks=r.toks[:swapped.said], aside=True),
                    replace(r, toks=r.toks[swapped.said_end:], aside=True)]
            continue
        run = restated_run(r, i, out)
        if run:
            both = out[-run]
            for more in [*out[len(out) - run + 1:], r]:
                both = joined(both, more)
            out[-run:] = [both]
            continue
        out.append(r)
    return out


def correction_headings_joined(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each sentence that is only correction words before a colon (*No, other way round:*)
    joined to the one after it when that says an order again (two places or more, with *first* or *then*):
    the heading corrects the order (not *No wait: check the couch.*, which may add a step)."""
    out: list[Reader] = []
    for r in readers:
        before = out[-1] if out else None
        start = said_instead(before) if before is not None and not before.aside and not r.aside else None
        order = len(named_heads(r, 0, len(r))) >= 2 and any(w in lx.FIRST or w == "then" for w in r.words)
        if before is not None and start is not None and order and before.skip(start, (":",)) >= len(before):
            out[-1] = joined(before, r)
            continue
        out.append(r)
    return out




def said_first(first: Tok, toks: Sequence[Tok]) -> tuple[Tok, ...]:
    """The words ``toks`` said as *First, <toks>*, with the *first* token ``first`` moved before them."""
    return (first, Tok(",", first.end, first.end), *toks)


def closing_start(r: Reader, start: int = 0) -> int:
    """Where the words of :data:`_ENDS` that close the sentence ``r`` start (not before ``start``)."""
    end = len(r)
    while end > start and r.word(end - 1) in _ENDS:
        end -= 1
    return end


def only_new_places(r: Reader, start: int, end: int, before: list[Reader]) -> bool:
    """Whether the words ``[start, end)`` of ``r`` name rooms or objects, none of them named in a sentence of
    ``before`` not set aside, and a sentence of ``before`` names a goal."""
    new = {h.categories for h in named_heads(r, start, end)}
    said = {h.categories for b in before if not b.aside for h in named_heads(b, 0, len(b))}
    return bool(new) and not new & said and goals_before(before)


def goals_before(before: Sequence[Reader]) -> bool:
    """Whether a sentence of ``before`` not set aside names a goal."""
    return any(goal_heads(b, 0, len(b)) for b in before if not b.aside)


def added_first(r: Reader, start: int, i: int, before: list[Reader]) -> Reader | None:
    """The order of the correction ``r`` (its correction words before ``start``, its order from ``i``) said as
    *First, <order>* when it adds a step before all (see the module docstring), else ``None``."""
    lead = r.word(i) in lx.FIRST
    end = closing_start(r, i)
    trailing = not lead and r.word(end - 1) in lx.FIRST
    order = r.skip(i + 1, (",",)) if lead else i
    words = range(order, end - 1 if trailing else end)
    if not (lead or trailing) or not set(r.words[:start]) <= _ADDING or not order_verb(r, order) or any(
            r.word(k) in _SAYS_MORE or r.word(k) in lx.FIRST for k in words):
        return None
    if not only_new_places(r, order, words.stop, before):
        return None
    if lead:
        return replace(r, toks=r.toks[i:])
    return replace(r, toks=said_first(r.toks[end - 1], (*r.toks[order:end - 1], *r.toks[end:])))


def added_prohibition(r: Reader, start: int, i: int, before: list[Reader]) -> Reader | None:
    """The prohibition of the correction ``r`` (its correction words before ``start``, its order from ``i``)
    without its *Actually,* when it forbids only places the mission has not named (*Go to the dining room.
    Actually, don't go through the kitchen.*): it adds a rule and takes nothing back; else ``None``."""
    if (not set(r.words[:start]) <= _ADDING or r.phrase(i, lx.NEG_STARTS) is None
            or r.words[i:i + 2] == ("never", "mind")):  # "Actually, never mind, ...": takes back
        return None
    if any(w in _MORE_THAN_A_RULE for w in r.words[i:]):
        return None  # "Actually, don't go in the kitchen, just go to the office": instead of the couch?
    return replace(r, toks=r.toks[i:]) if only_new_places(r, i, len(r), before) else None


class Moved(NamedTuple):
    """A goal phrase a correction moves first: the sentence without it, the phrase said as *First, <phrase>*,
    and where the correction's own words end (they are set aside)."""

    rest: Reader
    first: Reader
    aside_end: int


def moved_first(r: Reader, i: int, out: list[Reader]) -> Moved | None:
    """The goal phrase of the last sentence of ``out`` that the correction ``r`` (its order from ``i``) moves
    first, when no sentence before names a goal (see the module docstring); else ``None``. Over three
    phrases or more, every phrase must place itself (:func:`places_itself`)."""
    lead = r.word(i) in lx.FIRST
    at = put_at(r, r.skip(i + 1, (",",)) if lead else i)
    phrase = noun_phrase(r, at, "goal")
    before = out[-1]
    if before.aside or before.marker is not None or not isinstance(phrase, Match) or goals_before(out[:-1]):
        return None  # "Check the fridge. Then the couch, then the oven. No wait, the oven first.": before
        # the fridge too?
    after = phrase.end if lead else phrase.end + 1
    if (not lead and r.word(phrase.end) not in lx.FIRST) or closing_start(r, after) > after:
        return None
    spans = goal_phrases(before)
    if spans is None or (len(spans) > 2 and not all(places_itself(before, span) for span in spans)):
        return None
    b = named_phrase(before, spans, r, at, phrase.end)
    if b is None or b == 0:  # not named, or already first
        return None
    t = before.toks
    (_, a_end), (b_start, b_end) = spans[b - 1], spans[b]
    return Moved(replace(before, toks=(*t[:a_end], *t[b_end:])),
                 replace(r, toks=said_first(r.toks[i if lead else phrase.end], t[b_start:b_end])), at)


def moved_before(r: Reader, i: int, out: list[Reader]) -> Reader | None:
    """The last sentence of ``out`` with its last two goal phrases swapped, when the correction ``r`` (its
    order from ``i``) is *(do) X before Y*, X and Y said word for word as the last of them and the one before
    it, and every phrase of the sentence places itself (*Go to the kitchen, then the dining room, then the
    living room. Actually, do the living room before the dining room.*); else ``None``. The two are read in
    the correction's words (the same words), so the order of the words read stays the order of the text."""
    at = put_at(r, i)
    x = noun_phrase(r, at, "goal")
    if not isinstance(x, Match) or r.word(x.end) != "before":
        return None
    y = noun_phrase(r, x.end + 1, "goal")
    before = out[-1]
    if (not isinstance(y, Match) or closing_start(r, y.end) > y.end or before.aside
            or before.marker is not None):
        return None
    spans = goal_phrases(before)
    if spans is None or not all(places_itself(before, span) for span in spans):
        return None  # "A-room, then B-room, then the sink. Actually, do the sink before B-room": whose sink?
    (q_start, q_end), (p_start, p_end) = spans[-2:]
    if before.words[p_start:p_end] != r.words[at:x.end] or before.words[q_start:q_end] != r.words[
            x.end + 1:y.end]:
        return None  # "do C before A" ("B after C as well?"), or said otherwise (a qualifier lost?)
    t = before.toks
    return replace(before, toks=(*t[:q_start], *r.toks[at:x.end], *t[q_end:p_start], *r.toks[x.end + 1:y.end],
                                 *t[p_end:]))


def places_itself(r: Reader, span: tuple[int, int]) -> bool:
    """Whether the goal phrase of ``r`` at ``span`` says where it is: it names a room (*the dining room*,
    *the clock in the bedroom*) or a floor (*the sink upstairs*). A bare object (*the sink*) may be the one
    in the room of the phrase before it, which a move would change."""
    words = r.words[span[0]:span[1]]
    return (any(head.kind == "room" for head in named_heads(r, *span))
            or any(w in lx.RELATIVE_FLOORS or w in ("floor", "up", "down") for w in words))


def put_at(r: Reader, i: int) -> int:
    """Where the phrase a correction moves starts, past :data:`_PUT` at ``i`` (or the *it* of *make it* when
    *make* closed the correction words, :data:`.lexicon.CORRECTIONS`: *Actually make it the couch first.*)."""
    if r.word(i - 1) == "make" and r.word(i) in ("it", "that"):
        return i + 1
    return i + len(r.phrase(i, _PUT) or ())


def named_phrase(before: Reader, spans: list[tuple[int, int]], r: Reader, start: int, end: int) -> int | None:
    """The index in ``spans`` (the goal phrases of ``before``) of the one phrase the words ``[start, end)``
    of ``r`` name: what it names (its head, or the room that tells it from a phrase of the same kind), and
    no other phrase names all of it; ``None`` otherwise."""
    said = {h.categories for h in named_heads(r, start, end)}
    if not said:
        return None
    kinds = [{h.categories for h in goal_heads(before, *at)} for at in spans]
    named = [{h.categories for h in named_heads(before, *at)} for at in spans]
    # "garage first" after "the office chair, then the garage chair": the room tells the two chairs apart
    found = [k for k in range(len(spans)) if said <= kinds[k] or (
        kinds.count(kinds[k]) > 1 and said <= named[k])]
    if len(found) != 1 or any(said <= named[k] for k in range(len(spans)) if k != found[0]):
        return None  # "the kitchen first" after "the couch, then the bowl in the kitchen": the room itself?
    return found[0]


def goal_phrases(r: Reader) -> list[tuple[int, int]] | None:
    """The spans of the goal phrases of a sentence that is one verb and two or more goals in a row (*go to the
    bed, then the couch, then the oven*), the last closing it; ``None`` for any other sentence."""
    a = next((k for k in range(len(r)) if r.head(k) is not None
              or (r.word(k) in lx.DETERMINERS and r.head(k + 1) is not None)), None)
    first = noun_phrase(r, a, "goal") if a is not None else None
    if a is None or not isinstance(first, Match) or any(r.head(k) is not None for k in range(a)):
        return None
    spans = [(a, first.end)]
    while (joiner := next((j for j in _STEP_JOINERS if r.words[spans[-1][1]:spans[-1][1] + len(j)] == j),
                          None)) is not None:
        b = spans[-1][1] + len(joiner)
        more = noun_phrase(r, b, "goal")
        if not isinstance(more, Match):
            return None
        spans.append((b, more.end))
    last = spans[-1][1]
    return spans if len(spans) >= 2 and closing_start(r, last) == last else None


def restated_run(r: Reader, i: int, before: list[Reader]) -> int:
    """How many sentences at the end of ``before`` the correction ``r`` (its order from ``i``) says again as a
    whole order (see the module docstring): two or more, or 0."""
    said = {h.categories for h in named_heads(r, i, len(r))}
    if len(said) < 2 or not (order_verb(r, i) or r.word(i) in lx.FIRST or r.np_starts(i)) or any(
            r.word(k) in _BEYOND_ORDER for k in range(i, len(r))):
        return 0
    run: set[frozenset[str]] = set()
    n = 0
    for b in reversed(before):
        heads = {h.categories for h in goal_heads(b, 0, len(b))}
        if b.aside or b.marker is not None or not heads or not heads <= said or not only_steps(b):
            break
        run |= heads
        n += 1
    return n if n >= 2 and run == said else 0


def only_steps(r: Reader) -> bool:
    """Whether the sentence ``r`` says nothing but places to go, in order: after a polite opening, verbs of
    going, noun phrases and :data:`_STEP_WORDS` only."""
    k = order_start(r, 0)
    while k < len(r):
        phrase = noun_phrase(r, k, "goal") if r.np_starts(k) else None
        if isinstance(phrase, Match) and phrase.end > k:
            k = phrase.end
        elif r.word(k) in _STEP_WORDS or r.word(k) in lx.POSITIVE_VERBS:
            k += 1
        else:
            return False
    return True


class Substitution(NamedTuple):
    """A phrase said instead of another: the sentence read with it, and where it is in the correction."""

    sentence: Reader
    said: int
    said_end: int


def substituted(r: Reader, i: int, before: list[Reader]) -> Substitution | None:
    """The last sentence of ``before`` with its closing noun phrase Y replaced by X, when the order of the
    correction ``r`` (from ``i``) says X instead of Y (:func:`said_instead_of`), Y said word for word as that
    phrase, and X names the same kind (a room for a room, an object for an object); else ``None``. (Y said
    earlier is not read: X would be said after the goals it was to come before.)"""
    said = said_instead_of(r, i)
    if said is None:
        return None
    (new, new_end), (old, old_end) = said
    kinds = {h.kind for h in named_heads(r, new, new_end)[:1] + named_heads(r, old, old_end)[:1]}
    words, b = r.words[old:old_end], before[-1]
    end = closing_start(b)
    j = end - len(words)
    phrase = noun_phrase(b, j, "goal") if j >= 0 and b.words[j:end] == words else None
    if len(kinds) != 1 or b.aside or not isinstance(phrase, Match) or phrase.end != end:
        return None  # "the vase" of "the vase in the hall": not the whole phrase
    return Substitution(replace(b, toks=(*b.toks[:j], *r.toks[new:new_end], *b.toks[end:])), new, new_end)


Spans = tuple[tuple[int, int], tuple[int, int]]
"""The spans of X and of Y in a correction that says X instead of Y."""


def said_instead_of(r: Reader, i: int) -> Spans | None:
    """The spans of X and of Y in a correction whose order (from ``i``) is *(make that) X instead of Y* or
    *forget (about) Y, just / <verb> X*, closing it; else ``None``."""
    return forget_then(r, i) if r.phrase(i, FORGET) is not None else instead_of(r, i)


def forget_then(r: Reader, i: int) -> Spans | None:
    """*forget (about) Y, just (<verb>) X* / *forget Y, <verb> X* at ``i``, X closing the sentence (not
    *forget Y and Z*: both taken back)."""
    at_old = i + len(r.phrase(i, FORGET) or ())
    old = noun_phrase(r, at_old, "goal")
    if not isinstance(old, Match):
        return None
    k = r.skip(old.end, (",",))
    just = r.word(k) == "just"
    k += 1 if just else 0
    if not just and not order_verb(r, k):
        return None
    k = r.skip(k + 1, lx.PLACE_PREPOSITIONS) if order_verb(r, k) else k  # "do the microwave", "go to X"
    new = noun_phrase(r, k, "goal")
    if not isinstance(new, Match) or closing_start(r, new.end) > new.end:
        return None
    return (k, new.end), (at_old, old.end)


def instead_of(r: Reader, i: int) -> Spans | None:
    """*(make that / it) X instead of Y* at ``i``, Y closing the sentence."""
    k = i + 2 if r.word(i) == "make" and r.word(i + 1) in ("that", "it") else i
    new = noun_phrase(r, k, "goal")
    if not isinstance(new, Match) or r.words[new.end:new.end + 2] != ("instead", "of"):
        return None
    old = noun_phrase(r, new.end + 2, "goal")
    if not isinstance(old, Match) or closing_start(r, old.end) > old.end:
        return None
    return (k, new.end), (new.end + 2, old.end)
