"""A floor said with *only* as a sentence or a heading of its own, in operators' shorthand: *this flr only.*,
*fl 1 only: kit -> DR*, *upstairs only*, *only the ground floor.*

Such words confine the whole mission to that floor, as *stay on this floor* does; they are read as that
sentence (the floor's words kept where they were said, so that refusals quote them). Only a floor is read
so: *kitchen only* (only the kitchen as a goal, or keep to the kitchen?) is left to the parser, which
refuses it; and only the whole sentence, or the words before its colon (*this flr only: ...*).
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.floors import floor_words
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.text import Tok


def floor_only(r: Reader) -> Reader:
    """``r`` read as *stay on <floor>* when it is only a floor and *only* (see the module docstring), else
    ``r``."""
    end = r.words.index(":") if ":" in r.words else len(r)
    while end > 0 and r.word(end - 1) == "please":  # "top floor only pls:"
        end -= 1
    first = 1 if r.word(0) == "only" else 0  # "only the ground floor" / "this flr only"
    at = first + (r.word(first) == "the")
    floor_end = at + 1 if r.word(at) in lx.RELATIVE_FLOORS else getattr(floor_words(r, at), "end", None)
    if floor_end is None or (first == 1 and floor_end != end) or (
            first == 0 and (r.word(floor_end) != "only" or floor_end + 1 != end)):
        return r
    said = r.toks[first]
    verb: tuple[Tok, ...] = (Tok("stay", said.start, said.start),)
    verb += () if r.word(at) in lx.RELATIVE_FLOORS else (Tok("on", said.start, said.start),)
    rest = r.words.index(":") if ":" in r.words else len(r)
    return replace(r, toks=verb + r.toks[first:floor_end] + r.toks[rest:])
