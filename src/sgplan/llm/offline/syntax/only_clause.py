"""*..., and only go into the dining room after you've been to the kitchen*: a restriction said as a clause of
its own at the end of a sentence is read as a sentence of its own (*Only go into the dining room after ...*),
which the grammar reads at a sentence's start.

Only when the clause is *only*, a verb, and later *after* / *once* (the words of :data:`.lexicon.ONLY_AFTER`
without *only*); the sentence before it keeps its meaning: the clauses of a sentence joined by *and* are
goals of their own, as sentences are.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.reader import Reader

_AFTER = ("after", "once")


def only_clause(r: Reader) -> list[Reader]:
    """``r``, with a closing *, and only <verb> ... after ...* clause split off as a sentence of its own."""
    for k in range(3, len(r)):
        if (r.word(k) == "only" and r.word(k - 1) == "and" and r.word(k - 2) == ","
                and r.word(k + 1) in lx.POSITIVE_VERBS
                and any(w in _AFTER for w in r.words[k + 2:]) and "," not in r.words[k + 2:]):
            return [replace(r, toks=r.toks[:k - 2]), replace(r, toks=r.toks[k:], marker=None)]
    return [r]
