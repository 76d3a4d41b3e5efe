"""Tiny random buildings for the property tests (test-only: built with the package's public
:func:`sgplan.scene.synthetic.building_from_specs`)."""

from __future__ import annotations

import numpy as np

from sgplan.scene.model import Building
from sgplan.scene.synthetic import OBJECT_SIZES_M, ROOM_OBJECTS, Dimensions, RoomSpec, building_from_specs

SMALL_DIMS = Dimensions(
    band_depth_m=1.6,
    corridor_m=0.5,
    outer_wall_m=0.25,
    inner_wall_m=0.25,
    door_m=0.5,
    margin_m=0.25,
    stairs_width_m=1.0,
    landing_m=0.5,
    floor_gap_m=(2.5, 3.0),
    internal_door_probability=0.3,
    corridor_door_probability=0.85,
)


def random_small_building(seed: int | np.random.Generator) -> Building:
    """A tiny random building for property tests: fast (about a millisecond) and fully valid.

    1-2 floors; 1-3 ordinary rooms per floor plus one corridor per floor and, with two floors, one
    staircase (so 2-9 rooms in all, usually 3-6); 0-6 objects; cells of 0.25 m; grids of roughly
    16 x 20-40 cells. Walls are one cell thick, doors two cells wide; about one room in seven has no
    corridor door, so some rooms (and the objects in them) can be unreachable -- planners must cope.
    ``robot_radius_m`` is 0 (no inflation) and ``reach_radius_m`` 0.5 m (two cells).

    Example
    -------
    >>> @given(st.integers(0, 2**32 - 1))                               # doctest: +SKIP
    ... def test_something(seed):
    ...     building = random_small_building(seed)
    """
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    num_floors = int(rng.integers(1, 3))
    categories = list(ROOM_OBJECTS)
    specs = []
    for _ in range(num_floors):
        names = [str(categories[int(i)]) for i in rng.integers(len(categories), size=int(rng.integers(1, 4)))]
        specs.append([RoomSpec(n, (), width_m=float(rng.uniform(1.0, 2.25))) for n in names])
    num_objects = int(rng.integers(0, 7))
    slots = [(f, i) for f in range(num_floors) for i in range(len(specs[f]))]
    for _ in range(num_objects):
        f, i = slots[int(rng.integers(len(slots)))]
        spec = specs[f][i]
        small = [o for o in ROOM_OBJECTS[spec.category] if max(OBJECT_SIZES_M[o][:2]) <= 1.0] or ["bottle"]
        extra = small[int(rng.integers(len(small)))]
        specs[f][i] = RoomSpec(spec.category, (*spec.objects, extra), spec.width_m)
    return building_from_specs(specs, cell_m=0.25, seed=rng, name=f"small-{num_floors}f", dims=SMALL_DIMS,
                               robot_radius_m=0.0, reach_radius_m=0.5)
