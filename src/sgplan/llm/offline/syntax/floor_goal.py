"""A move between floors that ends the mission: *Check the fridge, then go upstairs.*, *Hey robot, I want you
to go downstairs.*

*Go upstairs* before goals only says on which floor they are (*Go upstairs. Check the laptop.*: the laptop
upstairs). With no goal after it, the floor itself is the goal: the move is read as *go to the floor above*
(*below* for *downstairs*), which the grounding counts from the start floor (refused when the floor of the
goal before it may differ), or takes as the other floor of a building with two. Only a move verb
(:data:`.lexicon.FLOOR_MOVE_VERBS`), *back* between them or not, right before the last word of the last
sentence with content, is read so (sentences after it may only be remarks: *Thanks!*), and only when the
mission says no other move between floors (*go upstairs, then come back downstairs* is left to the parser,
which refuses it). A move to the floor the goal before it is on already (*check the laptop, then go
upstairs*, in a building of two floors) holds at once.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.context import closing_only
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.text import Tok

_AFTER_MOVE = frozenset({"please", "now", "pls"})
"""Words a sentence may end with after the move (*go upstairs please*)."""
_DIRECTION = {1: "above", -1: "below"}
_CLAUSE_STARTS = frozenset({",", ";", "and", "then", "but"})
"""Words after which the clause of the move starts (*check the fridge, and then go upstairs*)."""
_LIGHT = frozenset({"please", "just", "also", "now", "finally", "lastly", "robot", "okay", "ok"})
"""Words that may come before the move in its clause (*and finally go upstairs*), besides a polite wrapper
(*I want you to go upstairs*); any other word may make someone else move (*once I go upstairs*) or the
move a time (*before you go upstairs*), which is no goal."""


def floor_goal_last(readers: list[Reader]) -> list[Reader]:
    """``readers`` with a move between floors that ends the mission read as going to that floor (see the
    module docstring)."""
    last = next((k for k in range(len(readers) - 1, -1, -1)
                 if not (readers[k].aside or closing_only(readers[k], 0, len(readers[k])))), None)
    if last is None:
        return readers
    moves = sum(w in lx.RELATIVE_FLOORS for r in readers[:last + 1] for w in r.words)
    if moves > 1:  # "go upstairs, then come back downstairs": the first move is no goal of its own here
        return readers
    return [*readers[:last], _to_floor(readers[last]), *readers[last + 1:]]


def _to_floor(r: Reader) -> Reader:
    """``r`` with its last word *upstairs* / *downstairs* read as *to the floor above / below* when a move
    verb (*back* between them or not) comes right before it, and only light words or a polite wrapper
    before the verb in its clause; else ``r``."""
    end = len(r)
    while end > 0 and (r.word(end - 1) in _AFTER_MOVE or r.word(end - 1) == ","):
        end -= 1
    k = end - 1
    verb = k - 1 - (r.word(k - 1) == "back")  # "then come back downstairs"
    if k < 1 or r.word(k) not in lx.RELATIVE_FLOORS or r.word(verb) not in lx.FLOOR_MOVE_VERBS:
        return r
    j = max((j + 1 for j in range(verb) if r.word(j) in _CLAUSE_STARTS), default=0)
    while j < verb:  # "and never go upstairs", "once I go upstairs", "to go upstairs": no floor goal
        polite = r.phrase(j, lx.POLITE)
        if polite is None and r.word(j) not in _LIGHT:
            return r
        j += len(polite) if polite is not None else 1
    said = r.toks[k]
    words = ("to", "the", "floor", _DIRECTION[lx.RELATIVE_FLOORS[r.word(k)]])
    return replace(r, toks=(*r.toks[:k], *(Tok(w, said.start, said.end) for w in words), *r.toks[k + 1:]))
