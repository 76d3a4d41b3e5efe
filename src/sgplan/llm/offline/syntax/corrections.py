"""Self-corrections: *go to the kitchen, no wait, the dining room*, *the chair in the office, sorry, I mean
the chair in the bedroom*.

A speaker who takes back a place right after naming it, with a correction word (:data:`.lexicon.CORRECTIONS`)
between the old and the new noun phrase, means the new one in the old one's place. The sentence is read
with the new phrase only; the old phrase and the correction words are set aside and said back (*not part of
the mission*). Only that shape is read: when the words after the correction are not one noun phrase closing
the clause, or no noun phrase ends right before it, the correction stays in the sentence and is refused
(which part stands is not known).
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax.phrases import noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.syntax.tree import Described, NounPhrase

_AROUND = frozenset({",", "sorry"})
"""Words between the old phrase, the correction and the new phrase (*the office, sorry, I mean ...*)."""
_CLAUSE_ENDS = ("", ",", "and", "then")


def corrected(r: Reader) -> list[Reader]:
    """``r`` with each self-correction applied (the sentence to read, then the words set aside), or ``[r]``
    when it has none that can be read."""
    for k in range(1, len(r)):
        said = r.phrase(k, lx.CORRECTIONS)
        if said is not None:
            fixed = replaced(r, k, k + len(said))
            return [r] if fixed is None else [*corrected(fixed[0]), fixed[1]]
    return [r]


def replaced(r: Reader, k: int, after: int) -> tuple[Reader, Reader] | None:
    """The sentence with the noun phrase ending before the correction words ``[k, after)`` replaced by the
    one after them, and the words taken back set aside; ``None`` when the shape is not that."""
    end = k
    while end > 0 and r.word(end - 1) in _AROUND:
        end -= 1
    old = next((found for j in range(max(0, end - 10), end) if (found := phrase_to(r, j, end))), None)
    if old is None:
        return None
    start_new = r.skip(after, _AROUND)  # "the one upstairs": one of the old phrase's kind
    head = old.head if isinstance(old, Described) and isinstance(old.head, Head) else None
    new = noun_phrase(r, start_new, "goal", head)
    if not isinstance(new, Match) or r.word(new.end) not in _CLAUSE_ENDS:
        return None
    start = r.toks.index(next(t for t in r.toks if t.start == old.span.start))
    kept = replace(r, toks=r.toks[:start] + r.toks[start_new:])
    return kept, replace(r, toks=r.toks[start:start_new], aside=True)


def phrase_to(r: Reader, i: int, end: int) -> NounPhrase | None:
    """The noun phrase starting at ``i`` when it ends at ``end``, else ``None``."""
    found = noun_phrase(r, i, "goal")
    return found.node if isinstance(found, Match) and found.end == end else None
