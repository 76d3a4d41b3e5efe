"""A step said as a choice that is fine: *go to the couch and then either bedroom on the top floor is fine*.

After *then*, a phrase of *either* / *any* / *whichever* closing its clause with *is fine* / *will do* (the
words of :data:`.lexicon.REMARK_FINE`) is the next step, that choice: the remark is dropped and the phrase
read as the step it stands for. Only after *then*: after a comma the same words may confirm a choice named
before (*grab a bottle, either bottle is fine*) or turn a group into one of it (*check the TVs, either TV
is fine*), which :mod:`.qualifiers` reads or refuses. Words before the remark that are not one noun phrase
(a verb, a prohibition) are left as they are.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Reader

_ENDS = ("", ",", "and", "then", "but")


def fine_choice(r: Reader) -> Reader:
    """``r`` with the remark of each chosen step after *then* dropped (see the module docstring)."""
    for k in range(1, len(r)):
        if r.word(k) not in lx.CHOOSERS_OF_KIND or r.word(k - 1) != "then":
            continue
        end = next(j for j in range(k + 1, len(r) + 1) if r.word(j) in _ENDS)
        fine = next(((j, said) for j in range(k + 2, end) if (said := r.phrase(j, lx.REMARK_FINE))
                     and j + len(said) == end), None)
        if fine is None:
            continue
        at, said = fine
        phrase = noun_phrase(r, k, "goal")
        if not isinstance(phrase, Match) or phrase.end != at:
            continue  # the words before the remark are not one phrase of a choice
        return fine_choice(replace(r, toks=r.toks[:at] + r.toks[at + len(said):]))
    return r
