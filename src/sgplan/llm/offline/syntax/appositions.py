"""An apposition said as a sentence of its own: *Water the plant. The one in the living room.*

Spoken and typed missions often say which one in a second sentence that is nothing but *the one ...*.
Read alone it has no verb and no kind; it says which of the phrase before it is meant, exactly as *the
plant, the one in the living room* does. So such a sentence is joined to the one before it as that
apposition (:func:`.qualifiers.apposition`), which then decides it or refuses it as usual. Only a
sentence that is one whole *the one(s) ...* phrase is joined; anything more is left to be read or refused.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.phrases import noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.syntax.tree import Described, OneHead
from sgplan.llm.offline.text import Tok


def join_appositions(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each sentence that is only *the one(s) ...* joined to the sentence before it, after
    a comma (which stands where the sentence ended)."""
    out: list[Reader] = []
    for r in readers:
        before = out[-1] if out else None
        if before is not None and not before.aside and not r.aside and only_the_one(r):
            end = before.toks[-1].end
            comma = Tok(",", end, end)
            out[-1] = replace(before, toks=(*before.toks, comma, *r.toks))
            continue
        out.append(r)
    return out


def only_the_one(r: Reader) -> bool:
    """Whether the sentence is one phrase *the one(s) ...* (*The one in the living room.*)."""
    if not (r.word(0) == "the" and r.word(1) in lx.ANAPHORIC_ONE) or r.marker is not None:
        return False
    said = noun_phrase(r, 0, "goal")
    return (isinstance(said, Match) and said.end == len(r) and isinstance(said.node, Described)
            and isinstance(said.node.head, OneHead))
