"""Planning instances for the tests: hand-made ones with known optimal costs, and random small ones."""

from __future__ import annotations

import numpy as np

from sgplan.logic import parse_infix
from sgplan.logic.automaton import Automaton
from sgplan.logic.ltlf import ltlf_to_dfa
from sgplan.planning import PlanningProblem
from sgplan.planning.setups import reach_model_for
from sgplan.scene.grid import OccupancyGrid, StairsLink, build_occupancy_grid
from sgplan.scene.labels import Proposition, label_raster
from sgplan.scene.model import Building, CatCode, Floor, Room
from tests.scene.small_buildings import random_small_building

RES = 0.1


def open_building(floors: int = 1, rows: int = 5, cols: int = 12) -> Building:
    """``floors`` floors of one obstacle-free room each (room id = floor + 1, uuid = 10 + floor)."""
    made = []
    for f in range(floors):
        room = Room(
            id=f + 1, uuid=10 + f, name="hall", floor=f, location_m=np.array([0.25, 0.6, 1.0]),
            size_m=np.array([0.5, 1.2, 2.0]), grid_min=(0, 0), grid_max=(rows - 1, cols - 1),
        )
        made.append(
            Floor(
                index=f, name="ABC"[f], uuid=100 + f, origin_m=(0.0, 0.0), resolution_m=(RES, RES),
                ground_z_m=3.0 * f, cat_map=np.full((rows, cols), CatCode.GROUND, dtype=np.int16),
                room_map=np.full((rows, cols), f + 1, dtype=np.int16), rooms={room.id: room},
            )
        )
    return Building(id=1, uuid=1, name="open", floors=made)


def open_grid(building: Building, stairs: tuple[StairsLink, ...] = ()) -> OccupancyGrid:
    floors = building.num_floors
    rows, cols = building.grid_shape
    return OccupancyGrid(
        traversable=np.ones((floors, rows, cols), dtype=bool),
        room_map=np.stack([f.room_map for f in building.floors]),
        resolution_m=(RES, RES), origin_m=(0.0, 0.0), floor_z_m=3.0 * np.arange(floors, dtype=float),
        stairs=stairs, robot_radius_m=0.0,
    )


def automaton(formula: str, aps: tuple[str, ...]) -> Automaton:
    return ltlf_to_dfa(parse_infix(formula), aps=aps)


def marks(shape: tuple[int, int, int], cells: dict[int, list[tuple[int, int, int]]]) -> np.ndarray:
    """A label raster with bit ``b`` set on each ``(row, col, floor)`` of ``cells[b]``."""
    labels = np.zeros(shape, dtype=np.uint32)
    for bit, where in cells.items():
        for row, col, floor in where:
            labels[floor, row, col] |= np.uint32(1 << bit)
    return labels


FORMULAS = (
    "F p0",
    "F(p0 & F p1)",
    "!p0 U p1",
    "F p1 & G !p0",
    "F(p0 & X p1)",
    "F p0 & F p1",
    "F(p2 & F p0) & G !p1",
    "F p2 & (!p2 U p0)",
    "F(p0 & F(p1 & F p2))",
    "G(p0 -> F p2) & F p0",
)


def random_problem(seed: int, profile: str = "ltlf", guidance: str = "random") -> PlanningProblem:
    """A random small building, 3 propositions (2 rooms, 1 object or room), a formula, a free start.

    ``guidance``: ``"random"`` (adversarial: random rooms and objects), ``"none"``.
    """
    rng = np.random.default_rng(seed)
    building = random_small_building(int(rng.integers(1 << 31)))
    grid = build_occupancy_grid(building, 0.0)
    rooms = list(building.rooms())
    objects = list(building.objects())
    picks = rng.choice(len(rooms), size=min(3, len(rooms)), replace=False)
    props = [Proposition("enter", rooms[int(i)].uuid) for i in picks[:2]]
    props.append(
        Proposition("reach", objects[0].uuid) if objects else Proposition("enter", rooms[int(picks[-1])].uuid)
    )
    aps = ("p0", "p1", "p2")
    formula = FORMULAS[int(rng.integers(len(FORMULAS)))]
    labels = label_raster(building, props, 0.5, reach_model_for(profile))  # the profile's, as the problem's
    free = np.argwhere(grid.traversable)
    floor, row, col = free[int(rng.integers(len(free)))]
    guide = None
    if guidance == "random":
        targets = [f"move({r.uuid}, {rooms[int(rng.integers(len(rooms)))].uuid})" for r in rooms]
        targets += [f"reach({o.room_uuid}, {o.uuid})" for o in objects]
        guide = {
            room.uuid: {q: [targets[int(i)] for i in rng.integers(len(targets), size=int(rng.integers(0, 4)))]
                        for q in range(8)}
            for room in rooms
        }
    return PlanningProblem(
        building=building, grid=grid, labels=labels, automaton=automaton(formula, aps),
        start=(int(row), int(col), int(floor)), profile=profile, guidance=guide, reach_radius_m=0.5,
    )
