"""A goal said *at some point* after the steps of a recurring condition: *Whenever you go into the kitchen,
check the living room afterwards, and at some point get to the office*, *... and check the fridge at some
point*, *... - and do pop into the garage at least once*. *At some point* frees the goal from the steps
around it, so it is no step of each visit: it is read as a sentence of its own (a goal of the mission). Only
after *whenever* / *every time* (after *if*, a goal of the condition could be meant as well) and only for the
last clause, joined by *and*.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.reader import Reader

LEAD_WORDS = frozenset({"and", "oh", "also", "so", ","})
"""Words a sentence may open with before its *whenever* (*Oh, and whenever you ...*)."""
CLAUSE_BREAKS = frozenset({",", "and", "then", "but", "or", ";"})


def any_time_goal(r: Reader) -> list[Reader]:
    """``r`` split before its last clause when it opens with *whenever* / *every time* and that clause,
    joined by *and*, says *at some point* first or last; ``[r]`` otherwise (what is left before it is read
    as the condition's sentence, or refused as one)."""
    start = r.skip(0, LEAD_WORDS)
    if r.aside or r.phrase(start, lx.WHENEVER) is None:
        return [r]
    end = len(r) - (1 if r.word(len(r) - 1) in (".", "!") else 0)
    k = max((j for j in range(start + 3, end) if r.word(j) == "and"), default=None)
    if k is None or set(r.words[k + 1:end]) & CLAUSE_BREAKS or not any_time_said(r, k + 1, end):
        return [r]
    cut = k - (1 if r.word(k - 1) in (",", "-") else 0)
    return [replace(r, toks=r.toks[:cut]), replace(r, toks=r.toks[k:], marker=None, announced=None)]


def any_time_said(r: Reader, start: int, end: int) -> bool:
    """Whether the words ``[start, end)`` open or end with *at some point* (*at least once*, *at any
    time*)."""
    if r.phrase(start, lx.TIME_FILLERS) in lx.ANY_TIME:
        return True
    said = ((j, r.phrase(j, lx.TIME_FILLERS)) for j in range(start + 1, end))
    return any(words in lx.ANY_TIME and j + len(words or ()) == end for j, words in said)
