"""planning.setups: queue names and levels stated once (the planner's result, the bench's columns)."""

from __future__ import annotations

import pytest

from sgplan.planning.setups import LEVEL_NAMES, LLM, LTL, SETUPS, get_setup, queue_level_name, queue_name


@pytest.mark.parametrize("name", sorted(SETUPS))
def test_every_queue_name_reads_back_its_level(name: str) -> None:
    setup = SETUPS[name]
    levels = [LEVEL_NAMES[level] for level, _ in setup.queues]
    assert [queue_level_name(q) for q in setup.queue_names] == levels


def test_queue_names_say_the_heuristic_and_the_level() -> None:
    assert queue_name(0, LTL) == "LTL/anchor" and queue_name(3, LLM) == "LLM/room"
    assert get_setup("ALL").queue_names == (
        "LTL/anchor", "LLM/occupancy", "LLM/object", "LLM/room", "LLM/floor")


def test_expansions_by_level_sums_each_levels_queues_and_names_every_level() -> None:
    assert get_setup("ROOM").expansions_by_level([7, 5]) == {
        "anchor": 7, "occupancy": 0, "object": 0, "room": 5, "floor": 0}
    assert get_setup("ALL").expansions_by_level([1, 2, 3, 4, 5]) == dict(zip(LEVEL_NAMES, [1, 2, 3, 4, 5]))
