"""Word lists and phrase tables of the lexicon: how they are written and how they are looked up.

A closed word list is written as running text (:func:`word_set`); a list of multi-word phrases as a
:class:`Phrases` table, which finds the longest of its phrases starting at a given word.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence


def word_set(text: str) -> frozenset[str]:
    """The words of ``text`` (split at white space): word lists are written as running text."""
    return frozenset(text.split())


class Phrases:
    """A table of phrases (tuples of lower-case words); :meth:`longest_at` finds the longest one that
    starts at a position of a word sequence.

    Parameters
    ----------
    phrases:
        the phrases, in any order; duplicates are dropped.
    """

    def __init__(self, phrases: Iterable[tuple[str, ...]]) -> None:
        self.phrases: tuple[tuple[str, ...], ...] = tuple(dict.fromkeys(phrases))
        by_first: dict[str, list[tuple[str, ...]]] = {}
        for phrase in sorted(self.phrases, key=len, reverse=True):
            by_first.setdefault(phrase[0] if phrase else "", []).append(phrase)
        self._by_first = {w: tuple(p) for w, p in by_first.items()}

    def __iter__(self) -> Iterator[tuple[str, ...]]:
        return iter(self.phrases)

    def __len__(self) -> int:
        return len(self.phrases)

    def __add__(self, other: Phrases) -> Phrases:
        return Phrases(self.phrases + other.phrases)

    def words(self) -> frozenset[str]:
        """Every word of every phrase."""
        return frozenset(w for phrase in self.phrases for w in phrase)

    def longest_at(self, words: Sequence[str], i: int) -> tuple[str, ...] | None:
        """The longest phrase equal to ``words[i : i + len(phrase)]``, or ``None``."""
        if not 0 <= i < len(words):
            return None
        for phrase in self._by_first.get(words[i], ()):
            if tuple(words[i : i + len(phrase)]) == phrase:
                return phrase
        return None
