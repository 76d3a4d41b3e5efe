"""Lists after a colon: *three things: A, B and C*, *visit two rooms: the kitchen and the office*, *could you
do a few things for me: ...*, *never enter these: ...*.

A sentence that ends with a colon announces the list of the next one when it ends with a noun group that
only counts or names the items (*three things*, *the following*, *these rooms*): the noun group is dropped
and the words before it (the verb, a negation: *never enter these rooms:*) are read with the list, so nothing
that carries meaning is lost. How many items the announcement said, and of what, is kept
(:class:`.tree.Announced`) and checked against the list (the phrases of its actions, and the grounding
for the category); the items are independent tasks. Words before a colon that ask nothing (*Here's the plan:*,
*Remember:*) are dropped. Any other colon ends a sentence, as ``.`` does.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.preamble import is_chitchat
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.syntax.tree import Announced


def at_colons(readers: list[Reader]) -> list[Reader]:
    """``readers`` (sentences, some ending with a colon) with each announcement read with the sentence after
    it, and the other colons dropped."""
    out: list[Reader] = []
    for r in readers:
        if out and out[-1].announced is not None and not out[-1].toks:
            out[-1] = replace(r, toks=out[-1].announced.prefix + r.toks, announced=out[-1].announced)
            continue
        if r.word(len(r) - 1) != ":":
            out.append(r)
            continue
        said = replace(r, toks=r.toks[:-1])
        if is_chitchat(said, 0, len(said)) or all(w in lx.HEADS_UP or w in lx.FILLERS for w in said.words):
            continue  # "Here's the plan:", "Remember:": they ask nothing
        announced = announcement(said)
        if announced is not None:
            out.append(replace(said, toks=(), announced=announced))
        elif said.toks:
            out.append(said)
    return [r for r in out if r.toks]


def announcement(r: Reader) -> Announced | None:
    """What the words of ``r`` announce of the list after its colon, or ``None`` when they do not end with a
    noun group that counts or names the items."""
    end = len(r)
    while end > 0 and any(r.words[end - len(t):end] == t for t in lx.ANNOUNCE_TAIL):
        end -= next(len(t) for t in lx.ANNOUNCE_TAIL if r.words[end - len(t):end] == t)
    head = r.nouns.match(r.words, end - 1)
    if end == 0 or not (r.word(end - 1) in lx.ANNOUNCED or (head is not None and head.plural)):
        return None
    start = end - 1
    while start > 0 and (r.word(start - 1) in lx.ANNOUNCING or r.word(start - 1).isdigit()
                         or r.word(start - 1) in lx.NUMBER_WORDS):
        start -= 1
    if any(r.np_starts(k) for k in range(start)):
        return None  # a phrase before the noun group: not only an announcement
    count = next((lx.NUMBER_WORDS.get(w) or int(w) for w in r.words[start:end]
                  if w.isdigit() or w in lx.NUMBER_WORDS), None)
    return Announced(r.quote(start, end), r.toks[:start], count, head if head is not None and head.plural
                     and r.word(end - 1) not in lx.ANNOUNCED else None)

