"""Small buildings for the execution tests, built in code (:class:`sgplan.scene.builder.BuildingBuilder`).

``flat()``: one floor of 4 x 6 m in 0.1 m cells -- a corridor along x 0..1.5 m, a kitchen (x 1.5..4, y
0..3) and a bedroom (x 1.5..4, y 3..6), doors corridor-kitchen at y 1.5, corridor-bedroom at y 4.5 and
kitchen-bedroom at x 2.75; a sink in the kitchen, a bed in the bedroom, a plant in the corridor.
``house()``: the same flat with a second floor (a corridor and an office with a desk) joined by a
staircase at the corridor's end.
"""

from __future__ import annotations

from sgplan.scene.builder import BuildingBuilder
from sgplan.scene.model import Building


def _flat_floor(b: BuildingBuilder, floor: int, with_stairs_room: bool) -> int:
    hall = b.add_room(floor, "corridor", box=(0.0, 0.0, 1.5, 5.0 if with_stairs_room else 6.0))
    kitchen = b.add_room(floor, "kitchen", box=(1.5, 0.0, 4.0, 3.0))
    bedroom = b.add_room(floor, "bedroom", box=(1.5, 3.0, 4.0, 6.0))
    b.add_door(hall, kitchen, at=(1.5, 1.5))
    b.add_door(hall, bedroom, at=(1.5, 4.5))
    b.add_door(kitchen, bedroom, at=(2.75, 3.0))
    b.add_object(kitchen, "sink", box=(3.3, 0.3, 3.8, 0.8))
    b.add_object(bedroom, "bed", box=(2.5, 4.5, 3.8, 5.7))
    b.add_object(hall, "plant", box=(0.3, 3.0, 0.6, 3.3))
    return hall


def flat(robot_radius_m: float = 0.0, reach_radius_m: float = 0.3) -> Building:
    """The one-floor flat of the module docstring, starting in the corridor at (0.7, 0.7) m."""
    b = BuildingBuilder("flat", size_m=(4.0, 6.0), resolution_m=0.1, wall_m=0.1,
                        robot_radius_m=robot_radius_m, reach_radius_m=reach_radius_m)
    _flat_floor(b, b.add_floor(), with_stairs_room=False)
    b.add_start(0.7, 0.7, 0)
    b.add_start(2.0, 5.0, 0)
    return b.build()


def house(robot_radius_m: float = 0.0, reach_radius_m: float = 0.3) -> Building:
    """The flat with an upper floor (corridor, office with a desk) over a staircase at y 5..6 m."""
    b = BuildingBuilder("house", size_m=(4.0, 6.0), resolution_m=0.1, wall_m=0.1,
                        robot_radius_m=robot_radius_m, reach_radius_m=reach_radius_m)
    ground, upper = b.add_floor(), b.add_floor()
    ground_hall = _flat_floor(b, ground, with_stairs_room=True)
    stairs = b.add_staircase(ground, portal=(0.75, 5.5), box=(0.0, 5.0, 1.5, 6.0))
    b.add_door(ground_hall, stairs, at=(0.75, 5.0))
    hall = b.add_room(upper, "corridor", box=(0.0, 0.0, 1.5, 5.0))
    office = b.add_room(upper, "office", box=(1.5, 0.0, 4.0, 6.0))
    b.add_door(hall, office, at=(1.5, 2.5))
    b.add_door(hall, stairs, at=(0.75, 5.0))
    b.add_object(office, "desk", box=(3.0, 4.0, 3.8, 5.5))
    b.add_start(0.7, 0.7, 0)
    return b.build()
