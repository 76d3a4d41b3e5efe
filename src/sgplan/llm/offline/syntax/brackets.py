"""Brackets: a room in brackets right after an object, as operators' notes place it (*apple (kit) or bowl
(LR)*, *teddy (LR) -> teddy (bdrm)*), and a remark of the speaker in brackets (*check the bottle (it's the
cough syrup)*).

A room: the brackets are read as *in*: *bowl (LR)* is *bowl in LR*, the bowl of the living room, and *bowl
(kitchen or living room, either is fine)* is a bowl in either room. Only a bracket holding phrases that name
rooms (joined by *or*, a choice remark after them), right after a word naming an object; other brackets
(*(any)*, *(either one)*, *(fl1)*) are left as they are.

A remark: a bracket that opens with a subject (*I*, *we*, *it*, *the cat*, after a hedge such as *I think*
or a doubt such as *no idea why*)
and says nothing a mission could read (no floor, no word of order, choice, count, negation or correction,
and no room or object of the scene but as a pronoun or inside another noun: *toilet paper*) is set aside
whole and said back (*I think we're low on toilet paper*). Anything else in brackets is read as a clause
between commas, as before.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.phrases import Phrases
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
    head = r.head_before(k)
    return head is not None and head.kind == "object"


def bracketed_remarks(r: Reader) -> list[Reader]:
    """``r`` without its remarks in brackets, then each remark as a reader set aside (see the module
    docstring); ``[r]`` when it has none."""
    out: list[Reader] = []
    k = 0
    while k < len(r):
        close = next((j for j in range(k + 1, len(r) + 1) if bracket(r, j, ")")), None) \
            if bracket(r, k, "(") else None
        if close is not None and remark(r, k + 1, close):
            out.append(replace(r, toks=r.toks[k + 1:close], aside=True))
            r = replace(r, toks=r.toks[:k] + r.toks[close + 1:])  # the bracket's commas with it
            continue
        k += 1
    return [r, *out] if out else [r]


_HEDGES = Phrases((("i", "think"), ("i", "guess"), ("i", "suppose"), ("i", "reckon"), ("i", "believe"),
                   ("probably",), ("maybe",), ("apparently",), ("pretty", "sure")))
_WHY = frozenset({"why", "how", "what", "where", "whether", "if"})
_READ_WORDS = (lx.FIRST | frozenset(lx.LAST) | lx.ORDER_HEADS | frozenset(lx.UNIVERSAL) | lx.CHOICE_WORDS
               | frozenset(lx.FLOOR_WORDS) | frozenset(lx.RELATIVE_FLOORS) | frozenset(lx.ANAPHORIC_ONE)
               | lx.CORRECTING_WORDS
               | frozenset({"before", "after", "until", "till", "if", "when", "whenever", "only", "again",
                            "once", "order", "never", "not", "no", "you", "avoid", "stay", "keep", "except"}))
"""Words a bracket may say for the mission (*(first)*, *(either one)*, *(not the one upstairs)*, *(you can
skip it)*): such a bracket is no remark."""


def remark(r: Reader, start: int, end: int) -> bool:
    """Whether the words ``[start, end)`` in brackets are a remark of the speaker (see the module
    docstring)."""
    k = start + len(r.phrase(start, _HEDGES) or ())
    doubt = r.phrase(start, lx.UNSURE)  # "(no idea why it has two)"
    if doubt is not None and r.word(start + len(doubt)) in _WHY:
        start = k = start + len(doubt) + 1
    if k >= end or (r.word(k) not in lx.SUBJECT_PRONOUNS and not (
            r.word(k) in lx.DETERMINERS and r.head(k + 1) is None and r.word(k + 1).isalpha())):
        return False
    after_heads = [j + head.words for j in range(start, end) if (head := r.head(j)) is not None]
    return not any(r.word(j) in _READ_WORDS or r.phrase(j, lx.NEG_STARTS) for j in range(start, end)) and all(
        r.head(j) is None and r.word(j).isalpha() and r.word(j) not in lx.STRUCTURAL  # "toilet paper"
        for j in after_heads) and not (
        r.spelling is not None and any(r.spelling.may_be_a_misspelt_name(w) for w in r.words[start:end]))
