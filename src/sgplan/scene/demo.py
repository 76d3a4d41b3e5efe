"""The embedded demo building: a two-storey house generated in code (no data files needed).

Ground floor: living room (couch, TV, ...), kitchen (refrigerator, oven, sink, ...), dining room (table
and chairs), bathroom (toilet, sink). Upper floor: two bedrooms with beds, a bathroom and a home office.
Each floor has a corridor; a staircase joins them. Cells are 0.05 m, so the grid is about 200 x 320
cells per floor and exact planning on it takes well under a second. Object classes are Gibson / COCO
names (``refrigerator``, ``tv``, ``dining table``, ...), as in the real scenes.
"""

from __future__ import annotations

import numpy as np

from sgplan.scene.model import Building
from sgplan.scene.synthetic import RoomSpec, building_from_specs

DEMO_SEED = 7
DEMO_CELL_M = 0.05
DEMO_ROBOT_RADIUS_M = 0.15
DEMO_REACH_RADIUS_M = 0.6

DEMO_FLOORS: tuple[tuple[RoomSpec, ...], ...] = (
    (
        RoomSpec("living_room", ("couch", "tv", "potted plant", "vase", "clock"), width_m=5.0),
        RoomSpec("kitchen", ("refrigerator", "oven", "sink", "microwave", "bowl"), width_m=3.6),
        RoomSpec("dining_room", ("dining table", "chair", "chair", "vase"), width_m=3.8),
        RoomSpec("bathroom", ("toilet", "sink"), width_m=2.4),
    ),
    (
        RoomSpec("bedroom", ("bed", "chair", "book"), width_m=4.0),
        RoomSpec("bedroom", ("bed", "teddy bear", "clock"), width_m=3.6),
        RoomSpec("bathroom", ("toilet", "sink", "bottle"), width_m=2.6),
        RoomSpec("home_office", ("chair", "laptop", "potted plant"), width_m=3.2),
    ),
)
"""The rooms of each floor and their objects (corridors and the staircase are added by the generator)."""

_START_ROOMS = ("corridor", "living_room", "kitchen", "bedroom", "home_office")

DEMO_STARTS: tuple[tuple[int, int, int], ...] = (
    (103, 46, 0), (170, 39, 0), (53, 102, 0), (65, 93, 1), (42, 164, 1),
)
"""The demo's initial cells ``(row, col, floor)``: :func:`deepest_start_cells` of the demo building, stored
so that loading the demo (e.g. to translate a mission) builds no occupancy grid; a test recomputes them."""


def demo_building() -> Building:
    """A fresh copy of the demo building (same content on every call).

    It carries default ``robot_radius_m`` (0.15 m), ``reach_radius_m`` (0.6 m) and five
    ``initial_cells`` ``(row, col, floor)``: :data:`DEMO_STARTS`.
    """
    building = building_from_specs(
        DEMO_FLOORS,
        cell_m=DEMO_CELL_M,
        seed=DEMO_SEED,
        name="demo-house",
        robot_radius_m=DEMO_ROBOT_RADIUS_M,
        reach_radius_m=DEMO_REACH_RADIUS_M,
    )
    building.initial_cells = list(DEMO_STARTS)
    return building


def deepest_start_cells(building: Building) -> list[tuple[int, int, int]]:
    """The open-floor cell deepest inside the first room of each category in ``corridor, living_room,
    kitchen, bedroom, home_office`` (floor order), traversable for the demo robot radius: how
    :data:`DEMO_STARTS` were chosen."""
    from scipy import ndimage

    from sgplan.scene.grid import build_occupancy_grid

    grid = build_occupancy_grid(building, DEMO_ROBOT_RADIUS_M)
    starts = []
    for category in _START_ROOMS:
        room = building.rooms_named(category)[0]
        inside = grid.traversable[room.floor] & (grid.room_map[room.floor] == room.id)
        depth = ndimage.distance_transform_edt(inside)
        row, col = np.unravel_index(int(np.argmax(depth)), depth.shape)
        starts.append((int(row), int(col), room.floor))
    return starts
