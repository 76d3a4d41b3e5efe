"""*..., and only go into the dining room after you've been to the kitchen*: a restriction said as a clause of
its own at the end of a sentence is read as a sentence of its own (*Only go into the dining room after ...*),
which the grammar reads at a sentence's start.

Only when the clause is *only*, a verb, and later *after* / *once* (the words of :data:`.lexicon.ONLY_AFTER`
without *only*); the sentence before it keeps its meaning: the clauses of a sentence joined by *and* are
goals of their own, as sentences are.

A restriction that goes on with *, (and) then ...* after its *after* clause (*Only go into the living room
after you've been to the kitchen, then sit on the couch.*, *Go into X only after Y, and then Z.*) is read as
two sentences, the second opening with *Then*: it goes on from the place the restriction lets the robot
into, as a sentence of its own does (*... after Y. Then Z.*).
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.reader import Reader

_AFTER = ("after", "once")
_ONLY_AFTER = (("only", "after"), ("only", "once"))
_OPENING = lx.HESITATIONS | lx.GREETINGS | frozenset({",", "okay", "ok", "robot", "so"})
"""Words before a sentence's restriction (*ok so um, only go in the living room after ...*)."""


def only_clause(r: Reader) -> list[Reader]:
    """``r``, with a closing *, and only <verb> ... after ...* clause split off as a sentence of its own, and
    the *then ...* that goes on after a restriction's *after* clause (see the module docstring)."""
    for k in range(3, len(r)):
        if (r.word(k) == "only" and r.word(k - 1) == "and" and r.word(k - 2) == ","
                and r.word(k + 1) in lx.POSITIVE_VERBS
                and any(w in _AFTER for w in r.words[k + 2:]) and "," not in r.words[k + 2:]):
            return [replace(r, toks=r.toks[:k - 2]), replace(r, toks=r.toks[k:], marker=None)]
    then = then_after_restriction(r)
    if then is not None:
        comma, k = then
        return [replace(r, toks=r.toks[:comma]), replace(r, toks=r.toks[k:], marker=None)]
    return [r]


def then_after_restriction(r: Reader) -> tuple[int, int] | None:
    """Where the restriction of ``r`` ends (its comma) and the *then ...* after it starts, when ``r`` is a
    restriction (*only <verb> ... after*, *... only after ...*) whose *after* clause goes on with *, (and)
    then*; ``None`` otherwise."""
    start = r.skip(0, _OPENING)
    only_first = r.word(start) == "only" and r.word(start + 1) in lx.POSITIVE_VERBS
    after = next((k for k in range(start, len(r))
                  if (only_first and r.word(k) in _AFTER) or r.phrase(k, lx.ONLY_AFTER) in _ONLY_AFTER), None)
    if after is None or after == start:
        return None  # "Only after Y, A, then B": is B restricted too? (refused by the grammar)
    for comma in range(after + 1, len(r)):
        k = r.skip(comma + 1, ("and",))
        if r.word(comma) == "," and r.word(k) == "then" and k > comma:
            return comma, k
    return None
