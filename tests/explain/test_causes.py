"""A mission that cannot be planned names its cause in words: no door, no room for the robot, a way in too
narrow for this robot (with the largest radius that gets through, checked here by planning with it), or
rooms the mission forbids."""

from __future__ import annotations

import dataclasses
import re
from functools import cache

import numpy as np
import pytest

import sgplan
from sgplan.errors import MissionError, PlanningError, UnsatisfiableMissionError
from sgplan.explain.causes import component_of, components_without, start_component
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building
from tests import shared_data


@cache
def _building() -> Building:
    """A corridor with an office behind a 0.5 m door, a kitchen and a pantry behind it, and a closet
    without a door."""
    b = sgplan.BuildingBuilder("narrow", size_m=(8.0, 4.0), resolution_m=0.05, robot_radius_m=0.1)
    b.add_floor()
    hall = b.add_room(0, "corridor", box=(0, 0, 8, 1.5))
    office = b.add_room(0, "office", box=(0, 1.5, 2.5, 4))
    b.add_door(hall, office, at=(1.2, 1.5), width_m=0.5)
    kitchen = b.add_room(0, "kitchen", box=(2.5, 1.5, 5, 4))
    b.add_door(hall, kitchen, at=(3.7, 1.5), width_m=0.9)
    pantry = b.add_room(0, "pantry", box=(5, 1.5, 6.5, 4))
    b.add_door(kitchen, pantry, at=(5, 2.7), width_m=0.9)
    b.add_room(0, "closet", box=(6.5, 1.5, 8, 4))
    b.add_start(0.5, 0.7, 0)
    return b.build()


def _failure(text: str, radius_m: float, building: Building | None = None) -> PlanningError:
    building = building or _building()
    with pytest.raises(PlanningError) as caught:
        sgplan.plan(building, sgplan.mission_from_text(text, building), 0, robot_radius_m=radius_m)
    return caught.value


def _largest_said(message: str) -> float:
    return float(re.search(r"a robot of radius up to ([\d.]+) m", message).group(1))  # type: ignore[union-attr]


def test_a_way_in_too_narrow_for_the_robot_says_which_radius_gets_through() -> None:
    error = _failure("Go to the office.", 0.25)
    message = str(error)
    assert error.status == "infeasible" and "no door" not in message
    assert "office (room_4, floor 0) cannot be reached from the start by a robot of radius 0.25 m" in message
    largest = _largest_said(str(error))
    building = _building()
    mission = sgplan.mission_from_text("Go to the office.", building)
    assert sgplan.plan(building, mission, 0, robot_radius_m=largest).status == "optimal"  # the claim holds
    with pytest.raises(PlanningError):
        sgplan.plan(building, mission, 0, robot_radius_m=largest + 0.01)


def test_a_room_without_a_door_says_so() -> None:
    message = str(_failure("Go to the closet.", 0.1))
    assert ("the closet (room_7, floor 0) cannot be reached from the start by a robot of radius 0.1 m; it "
            "has no door to any other room; no free passage leads there at any robot radius") in message
    assert "never holds" not in message  # the planner's internal words are gone


def test_forbidden_rooms_are_named_only_when_they_are_the_cause() -> None:
    building = _building()
    text = "Go to the pantry. Never enter the kitchen."
    with pytest.raises(MissionError, match="no way through this scene's rooms and doors"):
        sgplan.mission_from_text(text, building)  # the translator says so too
    mission = sgplan.mission_from_formula('F "enter(room_6)" & G !"enter(room_5)"', building, text=text)
    with pytest.raises(PlanningError) as caught:
        sgplan.plan(building, mission, 0, robot_radius_m=0.1)
    message = str(caught.value)
    assert ("the pantry (room_6, floor 0) can be reached only through rooms the mission forbids: the "
            "kitchen (room_5, floor 0)") in message
    message = str(_failure("Go to the office. Never enter the kitchen.", 0.25))
    assert "kitchen" not in message and "a robot of radius up to" in message  # the door, not the kitchen


@pytest.mark.gibson
def test_the_benevolence_utility_room_names_its_causes() -> None:
    building = shared_data.scene_building("Benevolence")
    mission = sgplan.mission_from_text("Go to the utility room.", building)
    with pytest.raises(UnsatisfiableMissionError) as caught:
        sgplan.plan(building, mission)
    message = str(caught.value)
    assert ("Why: no cell in the utility room (room_20, floor 2) is free for a robot of radius 0.2 m; a "
            "robot of radius up to") in message and message.endswith("it has no door to any other room.")
    error = _failure("Go to the utility room.", 0.1, building)
    assert ("the utility room (room_20, floor 2) cannot be reached from the start by a robot of radius "
            "0.1 m; it has no door to any other room; the way in lets a robot of radius up to") in str(error)
    largest = _largest_said(str(error))
    assert sgplan.plan(building, mission, robot_radius_m=largest).status == "optimal"


def _flood(grid: OccupancyGrid, start: tuple[int, int, int], allowed: np.ndarray) -> np.ndarray:
    """The oracle: a breadth-first flood over 8-neighbours and stairs links."""
    area = np.zeros_like(allowed)
    row, col, floor = start
    area[floor, row, col] = True
    if not allowed[floor, row, col]:
        return area
    stairs = {}
    for link in grid.stairs:
        lower, upper = (link.lower_floor, *link.lower_cell), (link.upper_floor, *link.upper_cell)
        stairs[lower], stairs[upper] = upper, lower
    todo = [(floor, row, col)]
    while todo:
        f, r, c = todo.pop()
        steps = [(f, r + dr, c + dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1)]
        for g, s, t in [*steps, *([stairs[(f, r, c)]] if (f, r, c) in stairs else [])]:
            if (0 <= s < allowed.shape[1] and 0 <= t < allowed.shape[2] and allowed[g, s, t]
                    and not area[g, s, t]):
                area[g, s, t] = True
                todo.append((g, s, t))
    return area


def test_the_start_component_without_rooms_is_the_flood_and_kept_per_grid_and_rooms() -> None:
    building = sgplan.load_scene("demo")
    grid = sgplan.Session(building).grid()
    kitchen, stairs_room = (building.rooms_named(name)[0].id for name in ("kitchen", "staircase"))
    starts = [tuple(int(v) for v in np.argwhere(grid.traversable[f])[k]) + (f,)
              for f in range(grid.shape[0]) for k in (0, 500, 2000)]
    for rooms in ([], [kitchen], [stairs_room, kitchen]):
        allowed = grid.traversable & ~np.isin(grid.room_map, rooms)
        components = components_without(grid, rooms)
        for start in starts:
            expected = _flood(grid, start, allowed)  # type: ignore[arg-type]
            assert np.array_equal(component_of(components, start), expected)  # type: ignore[arg-type]
            assert np.array_equal(start_component(grid, start, allowed), expected)  # type: ignore[arg-type]
    assert components_without(grid, [kitchen]) is components_without(grid, [kitchen, kitchen])
    assert components_without(grid, [kitchen]) is not components_without(grid, [stairs_room])
    other = dataclasses.replace(grid, traversable=grid.traversable.copy())
    assert components_without(other, [kitchen]) is not components_without(grid, [kitchen])
