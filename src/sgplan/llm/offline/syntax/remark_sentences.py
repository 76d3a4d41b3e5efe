"""A choice remark said as a sentence of its own: *Look at the TV in the lounge. Either of the two is fine.*

Spoken and typed missions often say that any one will do in a second sentence that is nothing but the
remark. Read alone it has no verb and no place; it says of the phrase before it exactly what *the TV in the
lounge, either of the two is fine* says (a remark, :func:`.qualifiers.remark_ahead`). So such a sentence is
joined to the one before it after a comma, and is then decided or refused as in one sentence (counted,
refused after a phrase that means each of several). A sentence that is only *the one ...* is joined the
same way by :func:`.corrections.joined_appositions`.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline.syntax.links import link
from sgplan.llm.offline.syntax.qualifiers import remark_ahead
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.text import Tok


def join_remarks(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each sentence that is only a choice remark joined to the sentence before it, after a
    comma (which stands where the sentence ended)."""
    out: list[Reader] = []
    for r in readers:
        before = out[-1] if out else None
        if before is not None and not before.aside and not r.aside and only_a_remark(r):
            # "Sit at the table, would you? Any of them will do.": the remark before the tag
            tag = 3 if before.word(len(before) - 3) == "," and before.words[-2:] in _TAGS else 0
            cut = len(before) - tag
            end = before.toks[cut - 1].end
            toks = (*before.toks[:cut], Tok(",", end, end), *r.toks, *before.toks[cut:])
            out[-1] = replace(before, toks=toks)
            continue
        out.append(r)
    return out


_TAGS = frozenset((modal, "you") for modal in ("would", "could", "will", "can"))
"""A question tag closing an order (*..., would you?*)."""


def only_a_remark(r: Reader) -> bool:
    """Whether the sentence is one choice remark (*Either of the two is fine.*, *Any one will do.*)."""
    said = remark_ahead(r, 0)
    if said is None or r.marker is not None:
        return False
    rest = link(r, len(said), sequence_too=False)  # "... is fine", "please": fillers
    return isinstance(rest, Match) and rest.end == len(r)
