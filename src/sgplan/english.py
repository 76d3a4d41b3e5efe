"""English for messages: a count with its noun in the right number, and a series of items.

>>> count(1, "room"), count(3, "room"), count(2, "entry", "entries"), count(1234, "cell")
('1 room', '3 rooms', '2 entries', '1,234 cells')
>>> series(["the kitchen"]), series(["a", "b"]), series(["a", "b", "c"])
('the kitchen', 'a and b', 'a, b and c')
"""

from __future__ import annotations

from collections.abc import Sequence


def count(n: int, noun: str, plural: str | None = None) -> str:
    """``n`` and ``noun``, plural unless ``n`` is 1 (``plural`` for nouns that do not just take an s)."""
    return f"{n:,} {noun if n == 1 else plural or noun + 's'}"


def series(items: Sequence[str]) -> str:
    """``a``, ``a and b``, ``a, b and c`` (empty for no items)."""
    if len(items) <= 1:
        return "".join(items)
    return f"{', '.join(items[:-1])} and {items[-1]}"
