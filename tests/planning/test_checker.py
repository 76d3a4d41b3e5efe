"""The path checker and the oracle on tiny hand-made grids with known answers."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sgplan.logic.automaton import Automaton
from sgplan.planning.checker import check_path
from sgplan.scene.grid import OccupancyGrid, StairsLink

from .oracle import optimal_cost

RES = (0.1, 0.2)


def _grid() -> OccupancyGrid:
    """Two floors of 3x4 cells, all free but (1, 1) on floor 0; stairs (0,3)@0 <-> (0,0)@1 cost 2 m."""
    free = np.ones((2, 3, 4), dtype=bool)
    free[0, 1, 1] = False
    return OccupancyGrid(
        traversable=free,
        room_map=np.ones((2, 3, 4), dtype=np.int16),
        resolution_m=RES,
        origin_m=(0.0, 0.0),
        floor_z_m=np.array([0.0, 3.0]),
        stairs=(StairsLink(lower_floor=0, lower_cell=(0, 3), upper_cell=(0, 0), cost_m=2.0),),
        robot_radius_m=0.0,
    )


def _eventually_a() -> Automaton:
    """DFA of F a over one proposition: state 0 waits, state 1 accepts forever."""
    return Automaton(aps=("a",), table=np.array([[0, 1], [1, 1]], dtype=np.int32), initial=0,
                     accepting=np.array([False, True]))


def _labels(goal: tuple[int, int, int]) -> np.ndarray:
    labels = np.zeros((2, 3, 4), dtype=np.uint32)
    labels[goal] = 1
    return labels


def test_valid_path_cost_is_recomputed() -> None:
    labels = _labels((1, 2, 1))  # floor 1, row 2, col 1
    path = np.array([[0, 2, 0, 0], [0, 3, 0, 0], [0, 0, 1, 0], [1, 1, 1, 0], [2, 1, 1, 1]])
    check = check_path(path, _grid(), labels, _eventually_a())
    assert check.valid, check.problems
    assert check.cost_m == pytest.approx(0.2 + 2.0 + math.hypot(0.1, 0.2) + 0.1)


@pytest.mark.parametrize(
    ("path", "fragment"),
    [
        ([[0, 0, 0, 0], [0, 2, 0, 0]], "no legal move"),
        ([[0, 0, 0, 0], [1, 1, 0, 0]], "not traversable"),
        ([[0, 0, 0, 0], [0, 1, 0, 1]], "the automaton gives 0"),
        ([[0, 0, 0, 0], [0, 1, 0, 0]], "not accepting"),
        ([[0, 0, 0, 0], [5, 0, 0, 0]], "outside the grid"),
    ],
)
def test_bad_paths_are_reported(path: list[list[int]], fragment: str) -> None:
    check = check_path(np.array(path), _grid(), _labels((1, 2, 1)), _eventually_a())
    assert not check.valid
    assert any(fragment in p for p in check.problems), check.problems


def test_profiles_differ_on_the_start_label() -> None:
    labels = _labels((0, 0, 0))  # the start cell itself satisfies a
    start_only = np.array([[0, 0, 0, 1]])
    assert check_path(start_only, _grid(), labels, _eventually_a(), "ltlf").valid
    assert not check_path(start_only, _grid(), labels, _eventually_a(), "authors").valid
    assert optimal_cost(_grid(), labels, _eventually_a(), (0, 0, 0), "ltlf") == 0.0
    # authors: the start label is not read, so the robot must step off and back on (two diagonal-free moves)
    assert optimal_cost(_grid(), labels, _eventually_a(), (0, 0, 0), "authors") == pytest.approx(2 * 0.1)


def test_oracle_goes_around_the_obstacle_and_up_the_stairs() -> None:
    labels = _labels((1, 2, 1))
    cost = optimal_cost(_grid(), labels, _eventually_a(), (2, 0, 0))
    # (2,0) -> (1,0)?  cheapest route to the portal (0,3): (2,0)->(2,1)->(1,2)->(0,3) = 0.2 + 2 diagonals
    to_portal = 0.2 + 2 * math.hypot(0.1, 0.2)
    assert cost == pytest.approx(to_portal + 2.0 + math.hypot(0.1, 0.2) + 0.1)
    assert optimal_cost(_grid(), np.zeros((2, 3, 4), dtype=np.uint32), _eventually_a(), (2, 0, 0)) == math.inf
