"""A room in brackets right after an object, as operators' notes place it: *apple (kit) or bowl (LR)*,
*teddy (LR) -> teddy (bdrm)*.

The brackets are read as *in*: *bowl (LR)* is *bowl in LR*, the bowl of the living room, and *bowl (kitchen
or living room, either is fine)* is a bowl in either room. Only a bracket holding phrases that name rooms
(joined by *or*, a choice remark after them), right after a word naming an object; other brackets (*(any)*,
*(either one)*, *(fl1)*) are left as they are.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.text import Tok


def bracketed_rooms(r: Reader) -> Reader:
    """``r`` with each room in brackets after an object read as *in* that room (see the module docstring)."""
    toks = list(r.toks)
    for k in range(len(r) - 1, 0, -1):
        if not bracket(r, k, "(") or not object_before(r, k):
            continue
        end = rooms_end(r, k + 1)
        if end is None:
            continue
        remark = r.phrase(end + 1, lx.CHOICE_AFFIRMATIONS) if r.word(end) == "," else None
        close = end + 1 + len(remark) if remark and bracket(r, end + 1 + len(remark), ")") else end
        if bracket(r, close, ")"):
            said = r.toks[k]  # "bowl (kitchen or LR, either is fine)": "bowl in kitchen or LR, either ..."
            toks[k:close + 1] = [Tok("in", said.start, said.end), *r.toks[k + 1:close]]
    return replace(r, toks=tuple(toks)) if toks != list(r.toks) else r


def rooms_end(r: Reader, i: int) -> int | None:
    """The end of the phrase naming a room at ``i``, or of several joined by *or* (*kitchen or living room*);
    ``None`` when no room is named there."""
    end = None
    while r.np_starts(i):
        room = noun_phrase(r, i, "qualifier")
        head = r.head(i) or r.head(i + 1)
        if not isinstance(room, Match) or head is None or head.kind != "room":
            break  # "apple (kit) or bowl (LR)": the bracket closed after the kitchen
        end = room.end
        if r.word(end) != "or":
            break
        i = end + 1
    return end


def bracket(r: Reader, k: int, said: str) -> bool:
    """Whether the bracket ``said`` was typed at the token ``k`` (the text reads brackets as commas, one comma
    for a bracket and a comma after it) or, for a closing one, right before it."""
    if not 0 <= k <= len(r) or (k == len(r) and said == "("):
        return False
    start = r.toks[k - 1].end if said == ")" and k > 0 else r.toks[k].start
    end = r.toks[k].start + 1 if k < len(r) else len(r.text)
    return said in r.text[start:end]


def object_before(r: Reader, k: int) -> bool:
    """Whether a word naming an object ends right before the token ``k``."""
    return any((h := r.head(j)) is not None and h.kind == "object" and j + h.words == k
               for j in range(max(0, k - 3), k))
