"""Corrections said as a sentence of their own that change the order of the steps before them.

Spoken missions fix the order after the fact: *Go to the dining room and sit on a chair. Actually, first get
a bowl from the kitchen.*; *Go to the bed, then the couch. No wait, the couch first.*; *Go to the garage.
Then the office. No wait, office first, then the garage.* Each is read only in the shape in which a careful
reader takes one meaning; the correction words are set aside and said back:

- **a step added first**: a correction, then an order with *first* (at its start or its end) that names only
  rooms and objects the mission has not named before, and no other word of order, condition, negation or
  addition: it is read as *First, <order>.*, which comes before every goal said so far (or is refused as
  such, :mod:`.sentences`);
- **the second of two steps moved first**: a correction, then a noun phrase and *first*, right after a
  sentence of exactly two goal phrases in a row (*A, then B*, one verb for both) when the phrase names
  what only the second of them names: the sentence is read without it, and the phrase after it as *First,
  <phrase>* (*go to A. First, B.*);
- **a phrase said instead**: *(make that) X instead of Y*, where Y is said word for word once before, as a
  whole noun phrase, and X names the same kind: the sentence of Y is read with X in its place;
- **an order said again over several sentences**: a correction and a whole order said again that names
  again exactly the places of the sentences right before it (two or more, each naming a goal, none a
  prohibition or condition): those sentences are joined with it, and :mod:`.corrections` reads it as one
  sentence that says the order again.

Anything else is left as it was: read by :mod:`.corrections`, or refused there.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.corrections import (
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
_SAYS_MORE = frozenset({"then", "instead", "before", "after", "afterwards", "until", "unless", "if", "when",
                        "whenever", "again", "last", "lastly", "next", "not", "never", "only", "too", "also",
                        "either", "or", "each", "every"})
"""Words that make a correction say more than one step to put first (read, or refused, by
:mod:`.corrections`)."""
_TWO_STEPS = ((",", "then"), ("then",), (",", "and", "then"), ("and", "then"), (",", "after", "that", ","),
              ("and", "after", "that"), (",", "then", "after", "that"))
"""The words between the two goal phrases of a sentence whose second one a correction moves first."""
_GOAL_FREE = frozenset({"if", "when", "whenever", "until", "unless", "before", "after", "every", "each",
                        "never", "not", "avoid", "only", "except"})
"""Words that keep a sentence out of an order said again over several sentences (it says more than goals)."""


def reordered(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each correction sentence that changes the order of the steps before it applied (see
    the module docstring): the sentences it reorders rewritten, its correction words set aside."""
    out: list[Reader] = []
    for r in readers:
        start = said_instead(r) if out and not r.aside and r.marker is None else None
        if start is None:
            out.append(r)
            continue
        i = order_start(r, start)
        taken = r.toks[:i]
        first = added_first(r, i, out)
        if first is not None:
            out += [replace(r, toks=taken, aside=True), first]
            continue
        moved = moved_first(r, i, out[-1])
        if moved is not None:
            out[-1:] = [moved[0], replace(r, toks=taken, aside=True), moved[1]]
            continue
        swapped = substituted(r, i, out)
        if swapped is not None:
            k, sentence, (said, said_end) = swapped
            out[k] = sentence
            out += [replace(r, toks=r.toks[:said], aside=True),  # "Actually, make that", "instead of Y"
                    replace(r, toks=r.toks[said_end:], aside=True)]
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


def added_first(r: Reader, i: int, before: list[Reader]) -> Reader | None:
    """The order of the correction ``r`` (from ``i``) said as *First, <order>* when it adds a step before all
    (see the module docstring), else ``None``."""
    lead = r.word(i) in lx.FIRST
    end = len(r)
    while end > i and r.word(end - 1) in _ENDS:
        end -= 1
    trailing = not lead and r.word(end - 1) in lx.FIRST
    order = r.skip(i + 1, (",",)) if lead else i
    words = range(order, end - 1 if trailing else end)
    if not (lead or trailing) or not order_verb(r, order) or any(
            r.word(k) in _SAYS_MORE or r.word(k) in lx.FIRST for k in words):
        return None
    new = {h.categories for h in named_heads(r, order, words.stop)}
    said = {h.categories for b in before if not b.aside for h in named_heads(b, 0, len(b))}
    if not new or new & said or not any(goal_heads(b, 0, len(b)) for b in before if not b.aside):
        return None
    if lead:
        return replace(r, toks=r.toks[i:])
    first_tok = r.toks[end - 1]  # moved to the front, so that the sentence opens with "First,"
    comma = Tok(",", first_tok.end, first_tok.end)
    return replace(r, toks=(first_tok, comma, *r.toks[order:end - 1], *r.toks[end:]))


def moved_first(r: Reader, i: int, before: Reader) -> tuple[Reader, Reader] | None:
    """The sentence ``before`` without its second goal phrase, and that phrase said as *First, <phrase>*, when
    the correction ``r`` (its order from ``i``) moves it first (see the module docstring), else ``None``."""
    lead = r.word(i) in lx.FIRST
    phrase = noun_phrase(r, r.skip(i + 1, (",",)) if lead else i, "goal")
    if before.aside or before.marker is not None or not isinstance(phrase, Match):
        return None
    after = phrase.end if lead else phrase.end + 1
    if (not lead and r.word(phrase.end) not in lx.FIRST) or any(w not in _ENDS for w in r.words[after:]):
        return None
    two = two_goal_phrases(before)
    if two is None:
        return None
    (a, a_end), (b, b_end) = two
    said = {h.categories for h in named_heads(r, i, phrase.end)}
    if not said or not said <= {h.categories for h in named_heads(before, b, b_end)} or said <= {
            h.categories for h in named_heads(before, a, a_end)}:
        return None
    t, first_tok = before.toks, r.toks[i if lead else phrase.end]
    comma = Tok(",", first_tok.end, first_tok.end)
    return replace(before, toks=(*t[:a_end], *t[b_end:])), replace(r, toks=(first_tok, comma, *t[b:b_end]))


def two_goal_phrases(r: Reader) -> tuple[tuple[int, int], tuple[int, int]] | None:
    """The spans of the two goal phrases of a sentence that is one verb and two goals in a row (*go to the
    bed, then the couch*), the second closing it; ``None`` for any other sentence."""
    a = next((k for k in range(len(r)) if r.head(k) is not None
              or (r.word(k) in lx.DETERMINERS and r.head(k + 1) is not None)), None)
    first = noun_phrase(r, a, "goal") if a is not None else None
    if a is None or not isinstance(first, Match) or any(r.head(k) is not None for k in range(a)):
        return None
    joiner = next((j for j in _TWO_STEPS if r.words[first.end:first.end + len(j)] == j), None)
    b = first.end + len(joiner) if joiner is not None else None
    second = noun_phrase(r, b, "goal") if b is not None else None
    if b is None or not isinstance(second, Match) or any(w not in _ENDS for w in r.words[second.end:]):
        return None
    return (a, first.end), (b, second.end)


def restated_run(r: Reader, i: int, before: list[Reader]) -> int:
    """How many sentences at the end of ``before`` the correction ``r`` (its order from ``i``) says again as a
    whole order (see the module docstring): two or more, or 0."""
    said = {h.categories for h in named_heads(r, i, len(r))}
    if len(said) < 2 or not (order_verb(r, i) or r.word(i) in lx.FIRST or r.np_starts(i)) or any(
            r.word(k) in _GOAL_FREE or r.word(k) in ("instead", "too", "also") for k in range(i, len(r))):
        return 0
    run: set[frozenset[str]] = set()
    n = 0
    for b in reversed(before):
        heads = {h.categories for h in goal_heads(b, 0, len(b))}
        if b.aside or b.marker is not None or not heads or not heads <= said or any(
                w in _GOAL_FREE for w in b.words):
            break
        run |= heads
        n += 1
    return n if n >= 2 and run == said else 0


def substituted(r: Reader, i: int, before: list[Reader]) -> tuple[int, Reader, tuple[int, int]] | None:
    """The index in ``before`` of the sentence whose noun phrase the correction ``r`` replaces, that sentence
    with it replaced, and where X is in ``r``, when the order of ``r`` (from ``i``) is *(make that) X instead
    of Y*, Y said word for word once before as a whole noun phrase, and X names the same kind (a room for a
    room, an object for an object); else ``None``."""
    k = i + 2 if r.word(i) == "make" and r.word(i + 1) in ("that", "it") else i
    new = noun_phrase(r, k, "goal")
    if not isinstance(new, Match) or r.words[new.end:new.end + 2] != ("instead", "of"):
        return None
    old = noun_phrase(r, new.end + 2, "goal")
    if not isinstance(old, Match) or any(w not in _ENDS for w in r.words[old.end:]):
        return None
    kinds = {h.kind for h in named_heads(r, k, new.end)[:1] + named_heads(r, new.end + 2, old.end)[:1]}
    words = r.words[new.end + 2:old.end]
    found = [(n, j) for n, b in enumerate(before) if not b.aside for j in range(len(b))
             if b.words[j:j + len(words)] == words]
    if len(kinds) != 1 or len(found) != 1:
        return None
    n, j = found[0]
    b = before[n]
    said = noun_phrase(b, j, "goal")
    if not isinstance(said, Match) or said.end != j + len(words):
        return None  # "the vase" of "the vase in the hall": not the whole phrase
    return n, replace(b, toks=(*b.toks[:j], *r.toks[k:new.end], *b.toks[said.end:])), (k, new.end)
