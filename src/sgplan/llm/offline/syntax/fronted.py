"""A prohibition said with the place first and the verb last, as learners whose languages put the verb at the
end write it: *Living room never go.*, *Lobby don't go.*, *Kitchen you will not enter.*, *In living room not
enter never.*, *The dining room please avoid.*

Such a sentence is read as *never enter <place>* (the place's words kept where they were said, so that
refusals quote them). Only a whole sentence is read so: a place (with *in* / *into* / *to* before it), then
*please* or *you* (*will* / *must* / *should*) at most, a negation and a verb of going, or *avoid* with no
negation, and nothing after it but *never* or *in* / *there*. *Kitchen do not visit until you have the
bowl* says more, and is left to the parser, which refuses it.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline.syntax.noun_slot import place_phrase
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.text import Tok

_INTO = frozenset({"in", "into", "to"})
_WHO = (("please",), ("you", "will"), ("you", "must"), ("you", "should"), ("you",), ())
_NEGATIONS = (("never",), ("not",), ("do", "not"), ("no",))
_GOING = frozenset({"go", "enter", "visit", "pass", "use", "touch", "come"})
_CLOSING = frozenset({"never", "in", "into", "there", "please"})


def fronted_prohibition(r: Reader) -> Reader:
    """``r`` read as *never enter <place>* when it is a prohibition with the place first (see the module
    docstring), else ``r``."""
    start = 1 if r.word(0) in _INTO else 0
    place = place_phrase(r, start, "avoid")
    if place is None:
        return r
    k = place.end
    for who in _WHO:
        if r.at(k, *who):
            k += len(who)
            break
    if r.word(k) == "avoid":
        k += 1
    else:
        negation = next((n for n in _NEGATIONS if r.at(k, *n)), None)
        if negation is None or r.word(k + len(negation)) not in _GOING:
            return r
        k += len(negation) + 1
    end = len(r) - (r.word(len(r) - 1) in (".", "!"))
    if any(r.word(j) not in _CLOSING for j in range(k, end)):
        return r
    said = r.toks[start]
    verb = (Tok("never", said.start, said.start), Tok("enter", said.start, said.start))
    return replace(r, toks=verb + r.toks[start:place.end] + r.toks[end:])
