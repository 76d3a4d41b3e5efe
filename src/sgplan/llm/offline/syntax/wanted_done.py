"""*I need the living room sorted*, *I want the fridge checked*: the place is the goal, and the state wanted
(*sorted*, *checked*) is how, set aside and said back.

The wrapper *I need* / *I want* / *I'd like* carries no meaning (:data:`.lexicon.POLITE`); what it leaves, a
noun phrase and a past participle closing the clause, is read as the phrase alone, a goal, as *check that the
couch is tidy* is the couch. Only a participle: a word ending in *-ed* (no room or object), or *done*, right
after the phrase and before the clause ends.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Reader

_WANTS = (("i", "need"), ("i", "want"), ("i", "would", "like"), ("we", "need"), ("we", "want"))
_ENDS = ("", ",", "and", "then", "so", "before", "by", "please")


def wanted_done(r: Reader) -> list[Reader]:
    """``r`` without the participle of each *I need X <participle>*, and that word set aside (see the module
    docstring)."""
    for k in range(len(r)):
        wants = next((w for w in _WANTS if r.words[k:k + len(w)] == w), None)
        if wants is None:
            continue
        start = k + len(wants)
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
