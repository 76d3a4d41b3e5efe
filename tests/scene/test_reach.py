"""The reach models (sgplan.scene.reach): the ``visible`` model against an independent brute force
(tests/scene/reach_oracle.py) on floors drawn in code and random ones, and the cases that motivated it."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sgplan.errors import PlanningError
from sgplan.planning.setups import PROFILE_REACH_MODELS, REACH_MODELS, reach_model_for
from sgplan.scene._sight import visible_cells
from sgplan.scene.demo import demo_building
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import Proposition, label_raster, proposition_cells
from sgplan.scene.model import NO_ROOM, CatCode, Floor, SceneObject
from sgplan.scene.reach import DEFAULT_REACH_MODEL, object_reach_cells
from tests.scene.reach_oracle import crossed_cells, visible_reach
from tests.shared_data import scene_building

OBJECT, OTHER = 7, 8
"""Category-map ids of the object to reach and of another object."""
_CAT = {".": CatCode.GROUND, "#": CatCode.WALL, " ": CatCode.OUTSIDE, "s": CatCode.STAIRS_UP,
        "o": OBJECT, "x": OTHER}
_ROOM = {"A": 1, "B": 2, "-": NO_ROOM}


def drawn_floor(cats: str, rooms: str, resolution_m: tuple[float, float] = (0.1, 0.1)) -> Floor:
    """A floor from two drawings of equal shape: the category map (``.`` floor, ``#`` wall, space outside,
    ``s`` stairs, ``o`` the object, ``x`` another object) and the room map (``A``, ``B``, ``-`` none)."""
    cat = np.array([[_CAT[ch] for ch in line] for line in cats.strip("\n").split("\n")], dtype=np.int16)
    room = np.array([[_ROOM[ch] for ch in line] for line in rooms.strip("\n").split("\n")], dtype=np.int16)
    assert cat.shape == room.shape
    return Floor(index=0, name="A", uuid=2, origin_m=(0.0, 0.0), resolution_m=resolution_m, ground_z_m=0.0,
                 cat_map=cat, room_map=room)


def the_object(floor: Floor, room_id: int = 1, object_id: int = OBJECT) -> SceneObject:
    cells = np.argwhere(floor.cat_map == object_id)
    lo, hi = cells.min(axis=0), cells.max(axis=0)
    return SceneObject(id=object_id, uuid=70, name="sink", room_id=room_id, room_uuid=10,
                       location_m=np.zeros(3), size_m=np.zeros(3), grid_min=(int(lo[0]), int(lo[1])),
                       grid_max=(int(hi[0]), int(hi[1])))


def reached(floor: Floor, radius_m: float, model: str = "visible",
            obj: SceneObject | None = None) -> np.ndarray:
    """The model's cells as a bool raster, checked against the brute force for ``visible``."""
    obj = obj or the_object(floor)
    out = np.zeros(floor.shape, dtype=bool)
    out.flat[object_reach_cells(floor, obj, radius_m, model)] = True
    if model == "visible":
        np.testing.assert_array_equal(out, visible_reach(floor, obj, radius_m))
    return out


def test_oracle_crossing_rule() -> None:
    """The brute force's own rule: a segment through a corner crosses only the diagonal cell."""
    assert crossed_cells((0, 0), (2, 2)) == [(0, 0), (1, 1), (2, 2)]
    assert crossed_cells((0, 0), (0, 3)) == [(0, 0), (0, 1), (0, 2), (0, 3)]
    assert crossed_cells((0, 0), (1, 2)) == [(0, 0), (0, 1), (1, 1), (1, 2)]


WALL_ROOMS = """
AAAAA-BBBBB
AAAAA-BBBBB
AAAAA-BBBBB
AAAAA-BBBBB
AAAAA-BBBBB
"""


def test_a_wall_blocks_what_the_box_reaches_through() -> None:
    floor = drawn_floor("""
.....#.....
.....#.....
...o.#.....
.....#.....
.....#.....
""", WALL_ROOMS)
    box, visible = reached(floor, 0.45, "box"), reached(floor, 0.45)
    assert box[2, 6] and box[2, 7] and box[4, 7]  # 0.3-0.4 m away, behind the wall
    assert not visible[:, 5:].any()
    assert visible[2, :3].all() and visible[0, 3] and visible[4, 1]


def test_sight_through_a_doorway() -> None:
    floor = drawn_floor("""
.....#.....
.....#.....
...o.......
.....#.....
.....#.....
""", WALL_ROOMS)
    visible = reached(floor, 0.45)
    assert visible[2, 5] and visible[2, 6] and visible[2, 7]  # straight through the door
    assert not visible[0, 6] and not visible[4, 6]  # beside the door: the wall is in the way


def test_a_segment_through_a_corner_passes_between_diagonal_cells() -> None:
    """As the planner's diagonal step does (and the waypoints' line of sight)."""
    cats = """
o#...
#.#..
.#.#.
..#..
"""
    rooms = """
AAAAA
AAAAA
AAAAA
AAAAA
"""
    floor = drawn_floor(cats, rooms)
    floor.room_map[floor.cat_map == CatCode.WALL] = NO_ROOM  # walls of no room: opaque
    visible = reached(floor, 0.45)
    assert visible[1, 1] and visible[2, 2] and visible[3, 3]
    blocked = drawn_floor(cats.replace("#.#..", "###.."), rooms)
    blocked.room_map[blocked.cat_map == CatCode.WALL] = NO_ROOM
    assert not reached(blocked, 0.45)[3, 3]


def test_the_objects_own_room_is_see_through_others_are_not() -> None:
    """A sink inside a counter: the counter (wall cells of the sink's room) does not hide it; the same
    counter drawn in another room, or another room's object, does."""
    cats = """
.......
.#####.
.#ox##.
.#####.
.......
"""
    inside = drawn_floor(cats, "AAAAAAA\n" * 5)
    visible = reached(inside, 0.35)
    assert visible[0, 2] and visible[4, 2] and visible[2, 0]
    assert not visible[1, 1] and not visible[2, 3]  # furniture cells reach nothing
    assert visible[2, 2]  # the object's own cells do
    other = drawn_floor(cats, "AAAAAAA\nABBBBBA\nABABBBA\nABBBBBA\nAAAAAAA\n")
    assert reached(other, 0.35).sum() == 1  # only the object's cell: every line crosses room B


def test_only_floor_cells_and_the_object_reach_it() -> None:
    floor = drawn_floor("""
.. ss
.o.##
.....
""", """
AAAAA
AAAAA
AAAAA
""")
    visible = reached(floor, 0.25)
    assert visible[1, 1] and visible[0, 0] and visible[2, 2]
    assert not visible[0, 2] and not visible[0, 3] and not visible[1, 3]


def test_an_object_in_many_pieces() -> None:
    """As many runs of object cells as a row can hold (every other cell), on odd and even widths."""
    for width in (5, 6):
        row = ("o." * width)[:width]
        floor = drawn_floor("\n".join([row] * 3), "\n".join(["A" * width] * 3))
        assert reached(floor, 0.15).all()
    empty = np.zeros((3, 4), dtype=bool)
    assert not visible_cells(empty, empty, ~empty, np.array([1, 0])).any()  # no object cell: nothing


def test_anisotropic_cells_and_the_radius_edge() -> None:
    """Distances are metres between centres, per axis resolution; at 0.05 m, 12 cells are 0.6000000000000001
    m in float64, outside a 0.6 m radius (the EDT's test, which the brute force repeats)."""
    floor = drawn_floor("." * 30 + "\n" + "." * 14 + "o" + "." * 15, "A" * 30 + "\n" + "A" * 30,
                        resolution_m=(0.2, 0.05))
    visible = reached(floor, 0.6)
    row = np.flatnonzero(visible[1])
    assert row.min() == 14 - 11 and row.max() == 14 + 11
    assert visible[0, 14] and not visible[0, 26]


@st.composite
def _floors(draw: st.DrawFn, size: int = 14, extent: int = 4, cells_reach: int = 12) -> tuple[Floor, float]:
    """A random floor (walls, outside, stairs, another object, rooms 1/2/none everywhere) with the object
    (room 1) as a block of up to ``extent`` rows and columns plus scattered cells, and a radius of up to
    ``cells_reach`` cells."""
    rows, cols = draw(st.integers(3, size)), draw(st.integers(3, size))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    blocked = draw(st.sampled_from([0.0, 0.1, 0.3, 0.6]))
    codes = np.array([CatCode.GROUND, CatCode.WALL, CatCode.OUTSIDE, CatCode.STAIRS_DOWN, OTHER])
    cat = np.where(rng.random((rows, cols)) < blocked, codes[rng.integers(1, 5, (rows, cols))], 0)
    r0, c0 = int(rng.integers(rows)), int(rng.integers(cols))
    cat[r0:r0 + int(rng.integers(1, extent + 1)), c0:c0 + int(rng.integers(1, extent + 1))] = OBJECT
    cat[rng.random((rows, cols)) < 0.03] = OBJECT  # objects in pieces too
    room = rng.choice(np.array([1, 2, NO_ROOM]), size=(rows, cols), p=[0.6, 0.3, 0.1])
    res = draw(st.sampled_from([(0.1, 0.1), (0.05, 0.05), (0.1, 0.07), (0.009985776293823039, 0.0099910599)]))
    radius = draw(st.floats(0.5, cells_reach)) * res[0]
    floor = Floor(index=0, name="A", uuid=2, origin_m=(0.0, 0.0), resolution_m=res, ground_z_m=0.0,
                  cat_map=cat.astype(np.int16), room_map=room.astype(np.int16))
    return floor, radius


@settings(max_examples=200, deadline=None)
@given(_floors())
def test_visible_model_is_the_brute_force(case: tuple[Floor, float]) -> None:
    floor, radius = case
    reached(floor, radius)


@settings(max_examples=25, deadline=None)
@given(_floors(size=36, extent=20, cells_reach=20))
def test_visible_model_is_the_brute_force_on_larger_floors(case: tuple[Floor, float]) -> None:
    """Objects spanning several bands of rows and radii of many cells: the shortcuts of the kernel
    (rectangles of opaque cells, bands in their shadow, the last target seen) all come into play."""
    floor, radius = case
    reached(floor, radius)


@settings(max_examples=40, deadline=None)
@given(_floors(size=24, extent=8, cells_reach=10), st.integers(0, 2**32 - 1),
       st.sampled_from(["box", "visible"]))
def test_deciding_some_cells_gives_those_of_the_whole_region(case: tuple[Floor, float], seed: int,
                                                              model: str) -> None:
    """``among`` (the planning domain's free cells of one room) only saves work."""
    floor, radius = case
    obj = the_object(floor)
    among = np.random.default_rng(seed).random(floor.shape) < 0.5
    whole = object_reach_cells(floor, obj, radius, model)
    np.testing.assert_array_equal(object_reach_cells(floor, obj, radius, model, among=among),
                                  whole[among.reshape(-1)[whole]])


def test_labels_choose_the_model() -> None:
    building = demo_building()
    sink = building.objects_named("sink")[0]
    prop = Proposition("reach", sink.uuid)
    floor = building.floors[0]
    for model in ("box", "visible"):
        cells = proposition_cells(building, prop, 0.6, model)
        np.testing.assert_array_equal(cells, object_reach_cells(floor, sink, 0.6, model))
        assert np.array_equal(np.flatnonzero(label_raster(building, [prop], 0.6, model)), cells)
    assert reach_model_for("authors") == "box" and reach_model_for("ltlf") == "visible"
    assert reach_model_for("authors", " Visible ") == "visible" and REACH_MODELS == ("box", "visible")
    assert PROFILE_REACH_MODELS["ltlf"] == DEFAULT_REACH_MODEL
    with pytest.raises(PlanningError, match="unknown reach model 'sphere'; use one of box, visible"):
        reach_model_for("ltlf", "sphere")
    with pytest.raises(ValueError, match="unknown reach model 'Box'"):
        object_reach_cells(floor, sink, 0.6, "Box")


def _rows_cols(floor: Floor, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return np.unravel_index(cells, floor.shape)  # type: ignore[return-value]


def test_demo_bathroom_sink_is_not_reached_from_the_kitchen_through_the_wall() -> None:
    building = demo_building()
    floor = building.floors[0]
    bathroom = next(r for r in building.rooms_named("bathroom") if r.floor == 0)
    sink = next(o for o in building.objects_named("sink") if o.room_id == bathroom.id)
    kitchen = building.rooms_named("kitchen")[0].id
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    in_kitchen = {}
    for model in ("box", "visible"):
        rows, cols = _rows_cols(floor, object_reach_cells(floor, sink, 0.6, model))
        keep = (floor.room_map[rows, cols] == kitchen) & grid.traversable[0, rows, cols]
        in_kitchen[model] = (rows[keep], cols[keep])
    # The wall between kitchen and bathroom runs beside the sink; the box reaches along it.
    wall_col, wall_top = sink.grid_min[1] - 1, sink.grid_min[0]
    while floor.cat_map[wall_top - 1, wall_col] == CatCode.WALL:
        wall_top -= 1
    assert floor.room_map[sink.grid_min[0], wall_col - 2] == kitchen  # the kitchen beyond the wall
    assert (in_kitchen["box"][0] >= wall_top).sum() > 50
    # The visible region enters the kitchen only through the door above the wall, in sight of the sink.
    assert len(in_kitchen["visible"][0]) > 0 and (in_kitchen["visible"][0] < wall_top).all()


def test_demo_reach_is_within_the_radius() -> None:
    """The box's corners are 0.6 * sqrt(2) m away (the demo's chair was "reached" 0.78 m away in a
    doorway); the visible model keeps every cell within 0.6 m of an object cell."""
    building = demo_building()
    for obj in building.objects():
        floor = building.floors[building.room(uuid=obj.room_uuid).floor]
        footprint = np.argwhere(floor.cat_map == obj.id)
        for model, farthest in (("box", 0.77), ("visible", 0.6)):
            rows, cols = _rows_cols(floor, object_reach_cells(floor, obj, 0.6, model))
            d = np.sqrt(((rows[:, None] - footprint[None, :, 0]) * 0.05) ** 2
                         + ((cols[:, None] - footprint[None, :, 1]) * 0.05) ** 2).min(axis=1)
            assert (d.max() > farthest) if model == "box" else (d.max() <= farthest)


def test_allensville_objects_are_not_reached_from_the_bedroom() -> None:
    """The blind evaluator's case: from bedroom room_6 the box reaches the dining room's vase object_21
    and the kitchen's microwave object_14 through walls; the visible model does not."""
    building = scene_building("Allensville")
    bedroom = building.room(uuid=6)
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    floor = building.floors[bedroom.floor]
    for uuid in (21, 14):
        obj = building.object(uuid=uuid)
        assert obj.room_id != bedroom.id
        counts = {}
        for model in ("box", "visible"):
            rows, cols = _rows_cols(floor, object_reach_cells(floor, obj, 0.7, model))
            counts[model] = int(((floor.room_map[rows, cols] == bedroom.id)
                                 & grid.traversable[bedroom.floor, rows, cols]).sum())
        assert counts["box"] > 0 and counts["visible"] == 0, (uuid, counts)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_sight_may_change_is_the_reach_window_test(seed: int) -> None:
    """The bounding-box pre-filter of ``sight_may_change`` never skips an object whose reach window holds a
    changed cell (the footprint lies in the box the scene records), and the answer is the window's."""
    from sgplan.scene.reach import reach_window, sight_may_change

    building = demo_building()
    rng = np.random.default_rng(seed)
    rows, cols = building.grid_shape
    near = list(building.objects())[int(rng.integers(len(list(building.objects()))))]
    floor = building.room(uuid=near.room_uuid).floor
    # cells around one object, so that some windows hold them and some do not
    r = rng.integers(near.grid_min[0] - 20, near.grid_max[0] + 21, size=int(rng.integers(1, 6)))
    c = rng.integers(near.grid_min[1] - 20, near.grid_max[1] + 21, size=r.size)
    cells = np.clip(r, 0, rows - 1) * cols + np.clip(c, 0, cols - 1)
    for obj in building.objects():
        if building.room(uuid=obj.room_uuid).floor != floor:
            assert not sight_may_change(building, obj, {floor: cells}, 0.6, "visible")
            continue
        window = reach_window(building.floors[floor], obj, 0.6, "visible")
        r, c = np.divmod(cells, cols)
        inside = window is not None and bool(((r >= window[0][0]) & (r < window[0][1])
                                              & (c >= window[1][0]) & (c < window[1][1])).any())
        assert sight_may_change(building, obj, {floor: cells}, 0.6, "visible") == inside
        assert not sight_may_change(building, obj, {floor: cells}, 0.6, "box")
