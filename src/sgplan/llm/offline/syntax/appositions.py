"""What says which, said as a sentence of its own: *Water the plant. The one in the living room.*, *Look
at the TV in the lounge. Either of the two is fine.*

Spoken and typed missions often say which one in a second sentence that is nothing but *the one ...* or
a choice remark. Read alone it has no verb and no place; it says which of the phrase before it is meant,
exactly as *the plant, the one in the living room* (an apposition, :func:`.qualifiers.apposition`) or *the
TV in the lounge, either of the two is fine* (a remark, :func:`.qualifiers.remark_ahead`) does. So such a
sentence is joined to the one before it after a comma, and is then decided or refused as usual. Only a
sentence that is one whole *the one(s) ...* phrase or remark is joined; anything more is left alone.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.links import link
from sgplan.llm.offline.syntax.phrases import noun_phrase
from sgplan.llm.offline.syntax.qualifiers import remark_ahead
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.syntax.tree import Described, OneHead
from sgplan.llm.offline.text import Tok


def join_appositions(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each sentence that is only *the one(s) ...* or a choice remark joined to the sentence
    before it, after a comma (which stands where the sentence ended)."""
    out: list[Reader] = []
    for r in readers:
        before = out[-1] if out else None
        if before is not None and not before.aside and not r.aside and (only_the_one(r) or only_a_remark(r)):
            end = before.toks[-1].end
            comma = Tok(",", end, end)
            out[-1] = replace(before, toks=(*before.toks, comma, *r.toks))
            continue
        out.append(r)
    return out


def only_a_remark(r: Reader) -> bool:
    """Whether the sentence is one choice remark (*Either of the two is fine.*, *Any one will do.*)."""
    said = remark_ahead(r, 0)
    if said is None or r.marker is not None:
        return False
    rest = link(r, len(said), sequence_too=False)  # "... is fine", "please": fillers
    return isinstance(rest, Match) and rest.end == len(r)


def only_the_one(r: Reader) -> bool:
    """Whether the sentence is one phrase *the one(s) ...* (*The one in the living room.*)."""
    if not (r.word(0) == "the" and r.word(1) in lx.ANAPHORIC_ONE) or r.marker is not None:
        return False
    said = noun_phrase(r, 0, "goal")
    return (isinstance(said, Match) and said.end == len(r) and isinstance(said.node, Described)
            and isinstance(said.node.head, OneHead))
