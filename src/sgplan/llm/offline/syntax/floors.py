"""Syntax rules for floors: *floor 1*, *the second floor*, *the top floor*, *this floor*, *the floor
above*, *two floors down*. Which floor they are (and whether the building has it) is the grounding's
(:mod:`..grounding.floors`)."""

from __future__ import annotations

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.syntax.tree import (
    FloorNumber,
    FloorOffset,
    FloorSpec,
    MiddleFloor,
    StartFloor,
    TopFloor,
)


def floor_count(r: Reader, i: int) -> int | None:
    """``a`` / ``one`` / ``two`` / ``2`` at ``i`` as a number of floors, else ``None``."""
    w = r.word(i)
    return 1 if w == "a" else int(w) if w.isdigit() else lx.NUMBER_WORDS.get(w)


def floor_offset(r: Reader, i: int) -> Match[FloorOffset] | None:
    """Floors counted from the start floor: *floor above* / *floor below* (after *the*), *next floor up*,
    *one floor up*, *two floors down*, *a floor down*, and a trailing *us* / *this one*."""
    w, nxt, third = r.word(i), r.word(i + 1), r.word(i + 2)
    count = floor_count(r, i)
    if w in lx.FLOOR_WORDS and nxt in lx.FLOOR_DIRECTIONS:
        delta, n = lx.FLOOR_DIRECTIONS[nxt], 2
    elif w == "next" and nxt in lx.FLOOR_WORDS and third in lx.FLOOR_DIRECTIONS:
        delta, n = lx.FLOOR_DIRECTIONS[third], 3
    elif count is not None and nxt in lx.FLOOR_PLURALS and third in lx.FLOOR_DIRECTIONS:
        delta, n = lx.FLOOR_DIRECTIONS[third] * count, 3
    else:
        return None
    said = r.quote(i, i + n)  # the words typed ("upstairs" for a move read as "the floor above")
    if r.word(i + n) in ("us", "you", "me"):
        n += 1  # "the floor above us"
    elif r.at(i + n, "this", "one"):
        n += 2  # "the floor below this one"
    return Match(FloorOffset(delta, said), i + n)


def floor_words(r: Reader, i: int) -> Match[FloorSpec] | None:
    """A floor named by the words at ``i``: *floor 1*, *second floor*, *ground floor*, *top floor*, *middle
    floor*, *this floor* (the start floor), or one counted from the start (:func:`floor_offset`)."""
    moved = floor_offset(r, i)
    if moved is not None:
        return Match(moved.node, moved.end)
    w, nxt = r.word(i), r.word(i + 1)
    said = f"{w} {nxt}"
    spec: FloorSpec
    if w in lx.FLOOR_WORDS and (nxt.isdigit() or nxt in lx.NUMBER_WORDS or nxt == "zero"):
        spec = FloorNumber(0 if nxt == "zero" else int(nxt) if nxt.isdigit() else lx.NUMBER_WORDS[nxt], said)
    elif nxt not in lx.FLOOR_WORDS:
        return None
    elif w in lx.FLOOR_ORDINALS or w in lx.FLOOR_NAMED:
        spec = FloorNumber(lx.FLOOR_ORDINALS.get(w, lx.FLOOR_NAMED.get(w, 0)), said)
    elif w in lx.FLOOR_TOP:
        spec = TopFloor(said)
    elif w in lx.FLOOR_MIDDLE:
        spec = MiddleFloor(said)
    elif w in lx.START_FLOOR_WORDS:  # "on this floor": where the robot starts
        spec = StartFloor(said)
    else:
        return None
    return Match(spec, i + 2)
