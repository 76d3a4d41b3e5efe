"""Words the translator does not know, and the known words they look like (*did you mean*).

The known words are those of the lexicon (:data:`.lexicon.LEXICON_WORDS`) and of the scene's names, their
synonyms and abbreviations (:meth:`.nouns.NounLexicon.words`). A word of the mission that is neither, nor a
known word with an ending (*seen*, *pets*), is unknown; its suggestion is the closest word of the scene's
names, of the verbs and of the floors by :func:`difflib.get_close_matches` (the standard library's sequence
matcher), when one is close enough. A refusal lists every unknown word of the mission that has a
suggestion, at once, so that one rephrasing can fix them all.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.nouns import NounLexicon

CUTOFF = 0.8
"""How close (difflib's ratio, 0 to 1) a known word must be to be suggested for an unknown one."""
LOOSE_CUTOFF = 0.7
"""How close a word must be to a word of the scene's names to be taken for a misspelling of it where the
alternative is setting it aside (:meth:`Spelling.may_be_a_misspelt_name`)."""
MIN_LENGTH = 4
"""Shorter words are not corrected (*a*, *to*, *tv*: short words all look alike)."""
SUFFIXES = ("s", "es", "d", "ed", "n", "en", "ing", "er", "ly")
"""An unknown word that is a known one with one of these (*seen*, *pets*) is English, not a typo."""


class Spelling:
    """The words a scene's missions may use, and suggestions for the others.

    Parameters
    ----------
    nouns:
        the scene's head nouns (their words are known; the words of its categories are what a misspelt noun
        is compared with).
    """

    def __init__(self, nouns: NounLexicon) -> None:
        self.known = lx.LEXICON_WORDS | nouns.words()
        self.words = lx.LEXICON_WORDS - frozenset(lx.ABBREVIATIONS)  # of English, not abbreviations
        self.names = sorted({w for c in nouns.kinds for w in c.split() if len(w) >= MIN_LENGTH})
        words = self.names + [w for w in lx.AVOID_VERBS | frozenset(lx.FLOOR_WORDS) if len(w) >= MIN_LENGTH]
        self.suggestable = sorted(set(words))
        self.noun_words = sorted(w for w in nouns.words() if w.isalpha() and len(w) >= 3)

    def is_known(self, word: str) -> bool:
        """Whether ``word`` is a word of the lexicon or of the scene (numbers and IDs are)."""
        return (word in self.known or not word.isalpha() or word.startswith(("room_", "object_"))
                or word in lx.NUMBER_WORDS)

    def is_english(self, word: str) -> bool:
        """Whether an unknown ``word`` is a known word with an ending (*seen*, *pets*), not a typo."""
        return any(word.endswith(e) and word[: -len(e)] in self.words for e in SUFFIXES)

    def suggestion(self, word: str) -> str | None:
        """The known name or verb ``word`` looks like, or ``None``."""
        if len(word) < MIN_LENGTH or self.is_known(word) or self.is_english(word):
            return None
        found = difflib.get_close_matches(word, self.suggestable, n=1, cutoff=CUTOFF)
        return found[0] if found else None

    def scene_noun_like(self, word: str) -> str | None:
        """The word of the scene's names that the unknown ``word`` looks like (*bathrom*), or ``None``: such a
        word is a misspelt noun, never a verb."""
        if len(word) < MIN_LENGTH or self.is_known(word) or self.is_english(word):
            return None
        found = difflib.get_close_matches(word, self.names, n=1, cutoff=CUTOFF)
        return found[0] if found else None

    def may_be_a_misspelt_name(self, word: str) -> bool:
        """Whether ``word`` (of any length) looks like a word of the scene's names, synonyms or abbreviations
        (*vse*, *bwol*), by a looser measure than :meth:`scene_noun_like`: used where reading it as a thing
        the scene does not hold would silently drop it."""
        if self.is_known(word) or self.is_english(word):
            return False  # "watering" is "water" with an ending, not a misspelt name
        return any(_same_stem(word, name) for name in
                   difflib.get_close_matches(word, self.noun_words, n=3, cutoff=LOOSE_CUTOFF))

    def did_you_mean(self, words: Iterable[str]) -> str:
        """*did you mean 'kitchen' for 'kitchn', 'living' for 'livng'?* for every unknown word of ``words``
        that looks like a known one (each once, in order); ``""`` when none does."""
        pairs = [(w, s) for w in dict.fromkeys(words) if (s := self.suggestion(w)) is not None]
        if not pairs:
            return ""
        return "did you mean " + ", ".join(f"'{s}' for '{w}'" for w, s in pairs) + "?"


def _same_stem(word: str, name: str) -> bool:
    """Whether ``word`` is still close to ``name`` without the ending they share, when that is three letters
    or more (*dripping* is not *dining*: *dripp* and *din* are far apart; *dinning* is: *din* and *di*)."""
    shared = next((k for k, (a, b) in enumerate(zip(word[::-1], name[::-1], strict=False)) if a != b),
                  min(len(word), len(name)))
    if shared < 3:
        return True
    return difflib.SequenceMatcher(None, word[:-shared], name[:-shared]).ratio() >= LOOSE_CUTOFF
