"""English counts and series for messages (sgplan.english)."""

from __future__ import annotations

from sgplan.english import a_or_an, count, series


def test_count_puts_the_noun_in_the_right_number() -> None:
    assert [count(n, "room") for n in (0, 1, 2)] == ["0 rooms", "1 room", "2 rooms"]
    assert count(1, "entry", "entries") == "1 entry" and count(3, "entry", "entries") == "3 entries"
    assert count(12345, "cell") == "12,345 cells"


def test_series_joins_with_commas_and_a_final_and() -> None:
    joined = [series(items) for items in ([], ["a"], ["a", "b"], ["a", "b", "c"])]
    assert joined == ["", "a", "a and b", "a, b and c"]


def test_the_indefinite_article_follows_the_sound_of_the_noun() -> None:
    nouns = ["apple", "oven", "empty room", "umbrella", "bowl", "utility room", "unicorn", "one-way door",
             "utensil", "urinal", "hour glass", "house"]
    assert [a_or_an(n) for n in nouns] == [
        "an apple", "an oven", "an empty room", "an umbrella", "a bowl", "a utility room", "a unicorn",
        "a one-way door", "a utensil", "a urinal", "an hour glass", "a house",
    ]


def test_a_choice_of_objects_is_said_with_the_right_article() -> None:
    """Found by a blind-set writer: the plain-English reading said 'reach a apple'."""
    from sgplan.explain.referents import Referent, group_phrase

    apples = [Referent(f"reach(object_{k})", "object", f"object_{k}", "apple", 0, "room_11", "kitchen")
              for k in (31, 32)]
    assert group_phrase(apples) == "an apple (object_31 or object_32, in the kitchen room_11, floor 0)"
    assert group_phrase(apples, "every").startswith("every apple (")
