"""Clauses that say a goal is not needed: *No need to go into the living room.*, *Check the oven, you don't
have to open it.*

Such a clause neither asks for its goal nor forbids it, so it is no part of the mission: it is set aside
like context (:class:`.tree.SetAside`) and said back as not part of the mission, never dropped silently --
unless it names a room, an object or a floor (*no need to go into the living room*): careful readers take
that one as "keep out of it" as often as "it is not needed", so it is parsed, and refused. A
clause is set aside whole (a sentence, or the words between commas), and only when it says nothing but
that: with a condition or an order word in it (*no need to go there unless ...*, *... before the office*),
or an *and* before anything but a room or object (*no need to go to the kitchen and check the oven*: is the
oven needed?), it is parsed, and so refused, naming the words (:func:`.refusals.not_needed`).
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.links import closing_at
from sgplan.llm.offline.syntax.reader import Reader


def split_not_needed(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each clause that only says a goal is not needed split off as a reader set aside."""
    out: list[Reader] = []
    for r in readers:
        out += [r] if r.aside else split(r)
    return out


def split(r: Reader) -> list[Reader]:
    """One sentence, its not-needed clauses set aside (in place: the explanation says them back in order)."""
    starts = [0, *(k + 1 for k, w in enumerate(r.words) if w == ",")]
    ends = [*(k for k, w in enumerate(r.words) if w == ","), len(r)]
    cut = [(a, b) for a, b in zip(starts, ends) if only_not_needed(r, skip_joiner(r, a), b)]
    if not cut:
        return [r]
    # each clause goes with the comma before it (the one after it when it opens the sentence)
    gone = [(a - 1, b) if a else (a, b + 1) for a, b in cut]
    kept = [k for k in range(len(r)) if not any(a <= k < b for a, b in gone)]
    out = [replace(r, toks=r.toks[a:b], aside=True) for a, b in cut]
    return ([replace(r, toks=tuple(r.toks[k] for k in kept))] if kept else []) + out


def skip_joiner(r: Reader, i: int) -> int:
    """*and* / *but* before the clause (*..., and no need to go upstairs*)."""
    return i + 1 if r.word(i) in ("and", "but") else i


def only_not_needed(r: Reader, start: int, end: int) -> bool:
    """Whether the clause ``[start, end)`` is a not-needed marker and words that say nothing more."""
    marker = r.phrase(start, lx.NOT_NEEDED)
    if marker is None or start + len(marker) >= end or closing_at(r, start) == end:
        return False  # not "no need to rush": a remark of its own, skipped (lexicon.CLOSING)
    said = range(start + len(marker), end)
    if any(r.head(k) is not None or r.word(k) in lx.RELATIVE_FLOORS for k in said):
        return False  # "no need to go into the living room": keep out of it, or only not needed? Refused
    return not any(r.word(k) in lx.NOT_NEEDED_STOPS or (r.word(k) == "and" and not r.np_starts(k + 1))
                   for k in said)
