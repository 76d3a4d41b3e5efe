"""English for messages: a count with its noun in the right number, an indefinite article, and a series.

>>> count(1, "room"), count(3, "room"), count(2, "entry", "entries"), count(1234, "cell")
('1 room', '3 rooms', '2 entries', '1,234 cells')
>>> a_or_an("apple"), a_or_an("oven"), a_or_an("bowl"), a_or_an("utility room"), a_or_an("empty room")
('an apple', 'an oven', 'a bowl', 'a utility room', 'an empty room')
>>> series(["the kitchen"]), series(["a", "b"]), series(["a", "b", "c"])
('the kitchen', 'a and b', 'a, b and c')
"""

from __future__ import annotations

from collections.abc import Sequence


def count(n: int, noun: str, plural: str | None = None) -> str:
    """``n`` and ``noun``, plural unless ``n`` is 1 (``plural`` for nouns that do not just take an s)."""
    return f"{n:,} {noun if n == 1 else plural or noun + 's'}"


# Words whose first letter misleads: vowel letters said with a consonant sound ("a utility room", "a
# urinal", "a one-way door") and a silent h ("an hour").
_CONSONANT_SOUND = ("uni", "use", "usu", "uti", "ute", "uri", "ura", "usb", "eu", "one", "once")
_VOWEL_SOUND = ("hour", "honest", "honour", "honor", "heir")


def a_or_an(noun: str) -> str:
    """``noun`` with its indefinite article, by the sound of its first letters (``an apple``, ``a utility
    room``, ``an hour``); good for the category names of scenes, not for every English word."""
    word = noun.lower()
    vowel = (word[:1] in "aeiou" and not word.startswith(_CONSONANT_SOUND)) or word.startswith(_VOWEL_SOUND)
    return f"{'an' if vowel else 'a'} {noun}"


def series(items: Sequence[str]) -> str:
    """``a``, ``a and b``, ``a, b and c`` (empty for no items)."""
    if len(items) <= 1:
        return "".join(items)
    return f"{', '.join(items[:-1])} and {items[-1]}"
