"""A rule on each visit of a place said as operators' notes say it: *rule: each kit visit -> DR after*,
*every LR visit => kitchen after*, *after every garage visit -> kit*.

Such words are read as *whenever you visit <place> then ...* (the place's words kept where they were said,
so that refusals quote them): each visit of the place, then the rest. Only with an arrow or *then* after
*visit* (the arrows are read *then* by the tokenizer), and only at the start of a sentence or after a
colon (*rule:*): *each kitchen visit* elsewhere is left to the parser, which refuses it.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.noun_slot import place_phrase
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.text import Tok

_EACH = frozenset({"every", "each"})


def each_visit_rule(r: Reader) -> Reader:
    """``r`` with *(after) each <place> visit then* read as *whenever you visit <place> then* (see the
    module docstring), else ``r``."""
    start = r.words.index(":") + 1 if ":" in r.words else 0
    k = start + (r.word(start) == "after")
    if r.word(k) not in _EACH:
        return r
    place = place_phrase(r, k + 1, "condition")
    if place is None or r.word(place.end) not in lx.VISIT_NOUNS or r.word(place.end + 1) != "then":
        return r
    said = r.toks[start]
    whenever = (Tok("whenever", said.start, said.start), Tok("you", said.start, said.start),
                Tok("visit", said.start, said.start))
    return replace(r, toks=r.toks[:start] + whenever + r.toks[k + 1:place.end] + r.toks[place.end + 1:])
