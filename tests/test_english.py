"""English counts and series for messages (sgplan.english)."""

from __future__ import annotations

from sgplan.english import count, series


def test_count_puts_the_noun_in_the_right_number() -> None:
    assert [count(n, "room") for n in (0, 1, 2)] == ["0 rooms", "1 room", "2 rooms"]
    assert count(1, "entry", "entries") == "1 entry" and count(3, "entry", "entries") == "3 entries"
    assert count(12345, "cell") == "12,345 cells"


def test_series_joins_with_commas_and_a_final_and() -> None:
    joined = [series(items) for items in ([], ["a"], ["a", "b"], ["a", "b", "c"])]
    assert joined == ["", "a", "a and b", "a, b and c"]
