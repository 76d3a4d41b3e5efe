"""A step said as a choice that is fine: *go to the couch and then either bedroom on the top floor is fine*.

A choice remark run on after a noun without a mark, as dictation types it (*grab an apple any apple is fine
then ...*), is read as between commas (:func:`remark_commas`); one said after a word that closes the step
(*chk tv after (either)*, *look at the TV in the living room as well, either one*) is read right after the
noun phrase (:func:`remark_after_closing`).

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
from sgplan.llm.offline.phrases import Phrases
from sgplan.llm.offline.syntax.brackets import bracket
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.qualifiers import remark_ahead
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.text import Tok

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


_REMARK_WORDS = frozenset({"of", "them", "the", "one", "ones", "these", "those"}) | frozenset(lx.NUMBER_WORDS)
"""Words between the chooser and the *is fine* of a run-on remark besides the noun (*any of them*)."""
_PHRASE_WORDS = 8
"""How many words back the noun a run-on remark names again may be (*grab an apple from the kitchen any
apple ...*)."""


def remark_commas(r: Reader) -> Reader:
    """``r`` with commas around each choice remark run on after a noun of the scene without a mark (*grab an
    apple any apple is fine then ...*, *sit at the dining table any of them doesnt matter then ...*): a word
    of :data:`.lexicon.CHOOSERS_OF_KIND`, a noun of the phrase before it again or *of them* / *one*, and a
    remark of :data:`.lexicon.REMARK_FINE` closing the clause. Read between commas, the remark is then
    decided or refused as one typed so. A remark naming another noun (*go to the kitchen any bathroom is fine
    then ...*) may be the next step: left as it is."""
    cuts: list[int] = []
    for k in range(2, len(r)):
        if r.word(k) not in lx.CHOOSERS_OF_KIND or r.head_before(k) is None:
            continue
        # the kinds of the phrase before it (*an apple from the kitchen*)
        named = {h.categories for j in range(max(0, k - _PHRASE_WORDS), k) if (h := r.head(j)) is not None}
        end = next((j for j in range(k + 1, len(r) + 1) if r.word(j) in _ENDS), len(r))
        j = k + 1
        while j < end and ((head := r.head(j)) is None or head.categories in named) and (
                head is not None or r.word(j) in _REMARK_WORDS):
            j += head.words if head is not None else 1
        fine = r.phrase(j, lx.REMARK_FINE)
        if fine is not None and j + len(fine) == end:
            cuts += [k] if r.word(end) in ("", ",") else [k, end]
    return r.with_commas(cuts)


_CLOSING_STEP = Phrases((("after",), ("afterwards",), ("done",), ("first",), ("too",), ("as", "well"),
                         ("also",)))
"""Words that close a step after its noun phrase, before a choice remark about that phrase (*chk tv after
(either)*, *until dining chair done (either one)*, *the TV in the living room as well, either one*)."""


def remark_after_closing(r: Reader) -> Reader:
    """``r`` with each choice remark said after a word of :data:`_CLOSING_STEP` that follows a noun of the
    scene moved right after that noun (*chk tv, either, after*), where it is decided or refused as one typed
    so; the remark is in brackets or says *one* (not *..., then the couch after, either is fine*: either
    order?), and runs to the end of its clause."""
    for k in range(1, len(r)):
        closing = r.phrase(k, _CLOSING_STEP)
        said = remark_ahead(r, k + len(closing)) if closing and r.head_before(k) is not None else None
        if closing is None or said is None or r.word(end := k + len(closing) + len(said)) not in _ENDS:
            continue
        if "one" not in said and not bracket(r, k + len(closing), "("):
            continue  # "the couch after, either is fine": either order? Only "(either)", "either one" move
        toks, n = r.toks, len(closing)
        comma = Tok(",", toks[end - 1].end, toks[end - 1].end)  # "chk tv, either, after"
        return remark_after_closing(replace(r, toks=(*toks[:k], *toks[k + n:end], comma, *toks[k:k + n],
                                                      *toks[end:])))
    return r
