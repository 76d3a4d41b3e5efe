"""*I need the living room sorted*, *I want the fridge checked*: the place is the goal, and the state wanted
(*sorted*, *checked*) is how, set aside and said back.

The wrapper *I need* / *I want* / *I'd like* carries no meaning (:data:`.lexicon.POLITE`); what it leaves, a
noun phrase and a past participle closing the clause, is read as the phrase alone, a goal, as *check that the
couch is tidy* is the couch. Only a participle: a word ending in *-ed* (no room or object), or *done*, right
after the phrase and before the clause ends.

A wish about how things in general should be (*so I want things looking nice*, *I want everything tidy*,
*I want the place to look nice*: the home as a whole), naming no room or object and asking nothing of
*you*, is context: set aside and said back, the sentence read without it.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Reader

_WANTS = (("i", "need"), ("i", "want"), ("i", "would", "like"), ("we", "need"), ("we", "want"))
_ENDS = ("", ",", "and", "then", "so", "before", "by", "please")
_IN_GENERAL = frozenset({"things", "everything", "stuff"})
"""What a wish about things in general is about (*I want things looking nice*, *I want everything tidy*)."""


def wanted_done(r: Reader) -> list[Reader]:
    """``r`` without the participle of each *I need X <participle>*, and that word set aside, and without a
    wish about things in general, set aside (see the module docstring)."""
    for k in range(len(r)):
        wants = next((w for w in _WANTS if r.words[k:k + len(w)] == w), None)
        if wants is None:
            continue
        start = k + len(wants)
        wish = general_wish(r, k, start)
        if wish is not None:
            return [*wanted_done(wish[0]), wish[1]] if wish[0].toks else [wish[1]]
        phrase = noun_phrase(r, start, "goal")
        if not isinstance(phrase, Match):
            continue
        at = phrase.end
        word = r.word(at)
        participle = word == "done" or (word.endswith("ed") and len(word) > 4)
        if participle and r.word(at + 1) in _ENDS and r.head(at) is None:
            kept = replace(r, toks=r.toks[:at] + r.toks[at + 1:])
            return [*wanted_done(kept), replace(r, toks=r.toks[at:at + 1], aside=True, marker=None)]
    return [r]


def general_wish(r: Reader, k: int, start: int) -> tuple[Reader, Reader] | None:
    """The sentence without the wish about things in general said from ``k`` (its object at ``start``: *so I
    want things looking nice*), and the wish set aside; ``None`` when the words there are no such wish."""
    home = r.at(start, "the", "place")  # "I want the place to look nice": the home as a whole
    if r.word(start) not in _IN_GENERAL and not home:
        return None
    end = next((j for j in range(start, len(r)) if r.word(j) in (",", "and", "then")), len(r))
    said = r.words[start:end]
    if "you" in said or ("to" in said and not home) or any(r.head(j) for j in range(start + 2 * home, end)):
        return None
    said_from = k - (1 if r.word(k - 1) in ("so", "and") else 0)  # ", so I want ..."
    cut = said_from - (1 if r.word(said_from - 1) == "," else 0)
    return (replace(r, toks=r.toks[:cut] + r.toks[end:]),
            replace(r, toks=r.toks[said_from:end], aside=True, marker=None))
