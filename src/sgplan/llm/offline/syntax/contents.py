"""What a container holds, said right after it: *a bottle of water*, *a bowl of leftover soup*.

The scene holds the bottle, not the water: the words *of <contents>* after an object of the scene name no
place, so they are set aside and said back (*Not part of the mission: 'of water'*), and the object is read
alone. Only food and drink are contents (:data:`_CONTENTS`, perhaps after one word of
:data:`_CONTENT_WORDS`: *of leftover soup*): *the vase of the dining room* (a learner's possessive of place)
and *the chair of my mother* (whose chair?) are left to the parser. The words are kept out of the lexicon,
so that they stay unknown to the rest of the grammar (*we're out of milk* is still a statement).
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline.syntax.reader import Reader

_CONTENTS = frozenset({"water", "juice", "milk", "tea", "coffee", "wine", "beer", "soda", "lemonade",
                       "squash", "fruit", "cereal", "soup", "stew", "pasta", "rice", "salad", "sugar",
                       "flour", "pills", "sweets", "candy", "biscuits", "cookies", "crisps", "chips", "nuts",
                       "ice", "flowers"})
"""Food, drink and what else people keep in a bottle, bowl, cup or vase."""
_CONTENT_WORDS = frozenset({"leftover", "cold", "hot", "warm", "fresh", "sparkling", "orange", "apple",
                            "cut", "some", "my", "the"})
"""Words that may come before the contents (*of leftover soup*, *of orange juice*, *of my pills*)."""


def contents_aside(r: Reader) -> list[Reader]:
    """``r`` without the contents said after its objects, then each as a reader set aside (see the module
    docstring); ``[r]`` when it says none."""
    out: list[Reader] = []
    k = 0
    while k < len(r):
        head = r.head(k)
        end = contents_end(r, k + head.words) if head is not None and head.kind == "object" else None
        if head is None or end is None:
            k += 1
            continue
        at = k + head.words
        out.append(replace(r, toks=r.toks[at:end], aside=True))
        r = replace(r, toks=r.toks[:at] + r.toks[end:])
        k = at
    return [r, *out] if out else [r]


def contents_end(r: Reader, i: int) -> int | None:
    """Where *of <contents>* at ``i`` ends, or ``None`` when the words there are not that."""
    if r.word(i) != "of":
        return None
    k = i + 1 + (r.word(i + 1) in _CONTENT_WORDS)
    return k + 1 if r.word(k) in _CONTENTS and r.head(k) is None else None
