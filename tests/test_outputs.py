"""Robot-ready outputs: waypoints (dense and simplified), events, CSV and ROS path files, `plan --json`."""

from __future__ import annotations

import csv
import dataclasses
import itertools
import json
import math
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

import sgplan
from sgplan.cli import main
from sgplan.errors import OutputError
from sgplan.logic.automaton import Automaton
from sgplan.outputs.waypoints import crossed_cells, densify, leg_costs, simplify_path
from sgplan.planning.checker import check_path
from sgplan.result import PlanResult
from sgplan.scene.grid import OccupancyGrid
from tests import shared_data
from tests.polyline_oracle import cells_meeting_segment, check_polyline

# Out and back on floor 0, then upstairs, never through the living room (room_6) or the kitchen (room_4).
FORMULA = ('F("enter(room_5)" & F("reach(object_28)" & F "enter(room_11)")) '
           '& G(!"enter(room_6)" & !"enter(room_4)")')


@lru_cache(maxsize=1)
def demo_result() -> PlanResult:
    building = sgplan.load_scene("demo")
    return sgplan.plan(building, sgplan.mission_from_formula(FORMULA, building), 0, setup="NO-LLM")


CELLS = st.tuples(st.integers(-40, 40), st.integers(-40, 40))


@given(CELLS, CELLS)
def test_crossed_cells_are_the_cells_whose_interior_the_segment_meets(a: tuple[int, int],
                                                                       b: tuple[int, int]) -> None:
    cells = crossed_cells(a, b)
    assert tuple(cells[0]) == a and tuple(cells[-1]) == b
    assert (np.abs(np.diff(cells, axis=0)).max(axis=1, initial=1) == 1).all()  # 4- or 8-adjacent steps
    assert cells.tolist() == cells_meeting_segment(a, b).tolist()  # brute force, same cells, same order


def _crossed_cells_by_sampling_the_crossings(a: tuple[int, int], b: tuple[int, int]) -> np.ndarray:
    """Reference for :func:`crossed_cells` in floating point: the cells at the midpoints between
    consecutive grid-line crossings (a corner is one crossing of both lines)."""
    p0 = np.array([a[0] + 0.5, a[1] + 0.5])
    d = np.array([b[0] - a[0], b[1] - a[1]], dtype=np.float64)
    crossings = []
    for axis in (0, 1):
        if d[axis] != 0:
            lo, hi = sorted((p0[axis], p0[axis] + d[axis]))
            crossings.append((np.arange(np.floor(lo) + 1, np.ceil(hi)) - p0[axis]) / d[axis])
    ts = np.unique(np.round(np.concatenate([[0.0, 1.0], *crossings]), 12))
    return np.floor(p0 + ((ts[:-1] + ts[1:]) / 2.0)[:, None] * d).astype(np.int64).reshape(-1, 2)


@given(CELLS, CELLS)
def test_crossed_cells_match_the_floating_point_reference(a: tuple[int, int], b: tuple[int, int]) -> None:
    reference = _crossed_cells_by_sampling_the_crossings(a, b).tolist() if a != b else [list(a)]
    assert crossed_cells(a, b).tolist() == reference


def test_a_segment_through_corners_enters_only_the_diagonal_cells() -> None:
    for a, b in [((0, 0), (3, 3)), ((0, 0), (2, 6)), ((5, 5), (5, -2)), ((0, 0), (-4, 2))]:
        assert crossed_cells(a, b).tolist() == _crossed_cells_by_sampling_the_crossings(a, b).tolist()
    assert crossed_cells((0, 0), (3, 3)).tolist() == [[0, 0], [1, 1], [2, 2], [3, 3]]
    assert crossed_cells((0, 0), (2, -2)).tolist() == [[0, 0], [1, -1], [2, -2]]
    assert crossed_cells((1, 1), (1, 1)).tolist() == [[1, 1]]
    # (0, 0) -> (2, 6) passes through the corner of cells (0, 1) and (1, 2), then of (1, 4) and (2, 5).
    assert crossed_cells((0, 0), (2, 6)).tolist() == [[0, 0], [0, 1], [1, 2], [1, 3], [1, 4], [2, 5], [2, 6]]


def _diagonal_along_an_edge() -> tuple[np.ndarray, OccupancyGrid, np.ndarray, Automaton]:
    """A path down the diagonal of a room whose cells above the diagonal are blocked (an inflated wall
    at 45 degrees): every corner it passes touches a blocked cell."""
    size = 30
    rows, cols = np.indices((size, size))
    traversable = (rows >= cols)[None]
    grid = OccupancyGrid(traversable=traversable, room_map=np.ones_like(traversable, dtype=np.int16),
                         resolution_m=(0.01, 0.01), origin_m=(0.0, 0.0), floor_z_m=np.zeros(1), stairs=(),
                         robot_radius_m=0.1)
    automaton = Automaton(aps=("p",), table=np.array([[0, 1], [1, 1]]), initial=0,
                          accepting=np.array([False, True]))
    labels = np.zeros((1, size, size), dtype=np.uint32)
    labels[0, size - 1, size - 1] = 1  # the goal: the far corner
    path = np.array([[k, k, 0, 0] for k in range(size)])
    path[-1, 3] = 1
    return path, grid, labels, automaton


def test_a_diagonal_along_an_inflated_edge_is_one_segment() -> None:
    path, grid, labels, automaton = _diagonal_along_an_edge()
    keep = simplify_path(path, grid, labels, automaton)
    assert keep.tolist() == [0, len(path) - 1]  # was every cell: the corners' side cells are blocked
    assert check_polyline(path, keep, grid, labels, automaton) == []


def test_simplified_waypoints_keep_the_mission_the_clearance_and_the_stairs() -> None:
    r = demo_result()
    automaton = r.mission.automaton
    keep = simplify_path(r.path, r.grid, r.labels, automaton)
    assert [w.index for w in r.waypoints_simplified] == keep.tolist()
    assert 2 < len(keep) < len(r.path) / 5
    crossed = densify(r.path, keep, automaton, r.labels)  # the cells a robot crosses on the polyline
    check = check_path(crossed, r.grid, r.labels, automaton, "ltlf")
    assert check.valid, check.problems  # free cells only, avoided rooms avoided, mission accepted
    assert r.waypoints_simplified[-1].cost_m <= r.cost_m + 1e-9
    floors = [w.floor for w in r.waypoints_simplified]
    changes = [i for i in range(1, len(floors)) if floors[i] != floors[i - 1]]
    assert len(changes) == 1 and floors[0] == 0 and floors[-1] == 1
    stairs = r.grid.stairs[0]
    below, above = r.waypoints_simplified[changes[0] - 1], r.waypoints_simplified[changes[0]]
    assert (below.row, below.col) == stairs.lower_cell and (above.row, above.col) == stairs.upper_cell


def test_a_segment_never_cuts_through_a_cell_that_changes_the_mission() -> None:
    r = demo_result()
    automaton = r.mission.automaton
    keep = simplify_path(r.path, r.grid, r.labels, automaton)
    (ra, ca, floor), (rb, cb, _) = r.path[keep[0], :3], r.path[keep[1], :3]
    on_path = {tuple(c) for c in r.path[:, :3].tolist()}
    cut = next(tuple(c) for c in crossed_cells((int(ra), int(ca)), (int(rb), int(cb))).tolist()
               if (*c, floor) not in on_path)  # a cell the first segment crosses but the path does not visit
    labels = r.labels.copy()
    labels[floor, cut[0], cut[1]] |= np.uint32(1 << automaton.aps.index("enter(room_4)"))  # now "kitchen"
    again = simplify_path(r.path, r.grid, labels, automaton)
    for a, b in itertools.pairwise(again):
        if b == a + 1:
            continue  # the planner's own step
        crossed = crossed_cells(tuple(r.path[a, :2].tolist()), tuple(r.path[b, :2].tolist()))[1:-1]
        assert r.path[a, 2] != floor or cut not in {tuple(c) for c in crossed.tolist()}
    assert len(again) > len(keep) and check_path(densify(r.path, again, automaton, labels), r.grid, labels,
                                                 automaton).valid


def _simplify_reference(path: np.ndarray, grid, labels: np.ndarray, automaton) -> list[int]:
    """The rule of :func:`simplify_path` stated plainly in Python, over the brute-force segment cells: from
    each kept row, the farthest row of its floor and state that a valid segment reaches."""

    def segment_ok(i: int, j: int) -> bool:
        floor, q = path[i, 2], path[i, 3]
        if (path[i:j + 1, 2] != floor).any() or (path[i + 1:j, 3] != q).any():
            return False
        for r, c in cells_meeting_segment(tuple(path[i, :2].tolist()), tuple(path[j, :2].tolist()))[1:-1]:
            if not (0 <= r < grid.shape[1] and 0 <= c < grid.shape[2]) or not grid.traversable[floor, r, c]:
                return False
            if automaton.table[q, labels[floor, r, c]] != q:
                return False
        return True

    keep, i = [0], 0
    while i < len(path) - 1:
        keep.append(max(j for j in range(i + 1, len(path)) if j == i + 1 or segment_ok(i, j)))
        i = keep[-1]
    return keep


@pytest.mark.parametrize(("formula", "start", "setup"), [
    (FORMULA, 0, "NO-LLM"), ('F("enter(room_4)" & F "enter(room_11)")', 2, "A*"),
    ('F "reach(object_28)" & G !"enter(room_5)"', 1, "NO-LLM"),
])
def test_the_compiled_simplification_follows_the_farthest_segment_rule(formula: str, start: int,
                                                                       setup: str) -> None:
    building = sgplan.load_scene("demo")
    r = sgplan.plan(building, sgplan.mission_from_formula(formula, building), start, setup=setup)
    automaton = r.mission.automaton
    keep = simplify_path(r.path, r.grid, r.labels, automaton)
    assert keep.tolist() == _simplify_reference(r.path, r.grid, r.labels, automaton)
    assert keep.dtype == np.int64 and 2 <= len(keep) < len(r.path)
    assert simplify_path(r.path[:2], r.grid, r.labels, automaton).tolist() == [0, 1]
    # A path given by hand that leaves the grid: its cells outside are refused (never read), like the rule's.
    outside = r.path[:3].copy()
    outside[:, 3] = r.path[0, 3]
    far = 3 * (r.grid.shape[1] + r.grid.shape[2])  # segments longer than any inside the grid
    outside[1, :2] = (outside[0, 0] - far, outside[0, 1])
    outside[2, :2] = (outside[0, 0] - 2 * far, outside[0, 1] + 1)
    assert simplify_path(outside, r.grid, r.labels, automaton).tolist() == [0, 1, 2] == \
        _simplify_reference(outside, r.grid, r.labels, automaton)


def test_waypoints_are_metric_and_in_rooms() -> None:
    r = demo_result()
    w = r.waypoints[0]
    assert (w.row, w.col, w.floor) == r.start and w.cost_m == 0.0
    assert (w.x_m, w.y_m) == pytest.approx(r.building.floors[0].cell_to_xy((w.row, w.col)))
    assert w.z_m == r.building.floors[0].ground_z_m and w.room == "room_2" and w.room_name == "corridor"
    assert r.waypoints[-1].cost_m == pytest.approx(r.cost_m) == pytest.approx(leg_costs(r.path, r.grid).sum())
    assert r.waypoints[-1].z_m == r.building.floors[1].ground_z_m > 0
    record = w.to_dict()
    assert list(record) == ["index", "x_m", "y_m", "z_m", "floor", "row", "col", "room", "room_name", "q",
                            "cost_m"]
    assert record == dataclasses.asdict(w) and all(type(v) in (int, float, str) for v in record.values())


def test_every_waypoint_is_its_cell_centre_room_and_cost_exactly() -> None:
    """The columns computed at once equal, bit for bit, the per-cell definitions: the grid's cell centre,
    the floor's ground height, the room holding the cell, the cost of the legs so far."""
    r = demo_result()
    assert r.path is not None and r.grid is not None and r.building is not None
    rooms = {room.id: room for room in r.building.rooms()}
    costs = np.concatenate([[0.0], np.cumsum(leg_costs(r.path, r.grid))]).tolist()
    for k, (w, (row, col, floor, q)) in enumerate(zip(r.waypoints, r.path.tolist(), strict=True)):
        x_m, y_m, _ = r.grid.cell_xyz(floor, (row, col))
        room = rooms.get(int(r.grid.room_map[floor, row, col]))
        expected = (k, x_m, y_m, r.building.floors[floor].ground_z_m, floor, row, col,
                    room.key if room else None, room.name if room else None, q, costs[k])
        assert dataclasses.astuple(w) == expected
        assert [type(v) for v in dataclasses.astuple(w)] == [type(v) for v in expected]


def test_events_say_where_each_proposition_became_true_and_the_automaton_moved() -> None:
    r = demo_result()
    props = [e for e in r.events if e.kind == "proposition"]
    assert [e.meaning for e in props if e.meaning != "enter(room_2)"][:3] == \
        ["enter(room_5)", "reach(object_28)", "enter(room_11)"]
    states = [e for e in r.events if e.kind == "state"]
    assert (
        states[-1].accepting and states[-1].to_state == r.path[-1, 3] and states[-1].index == len(r.path) - 1
    )
    costs = np.concatenate([[0.0], np.cumsum(leg_costs(r.path, r.grid))])
    for e in r.events:
        assert e.cost_m == pytest.approx(costs[e.index]) and (e.row, e.col, e.floor) == tuple(
            r.path[e.index, :3]
        )
    kitchen = next(e for e in props if e.meaning == "enter(room_5)")
    assert kitchen.entity == "bathroom" and "bathroom" in kitchen.describe()


def test_csv_and_ros_path_files(tmp_path: Path) -> None:
    r = demo_result()
    with r.write_waypoints_csv(tmp_path / "w.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == len(r.waypoints_simplified) and float(rows[-1]["cost_m"]) == pytest.approx(
        r.waypoints_simplified[-1].cost_m, abs=1e-4)
    assert (
        len(list(csv.reader(r.write_waypoints_csv(tmp_path / "d.csv", simplified=False).open())))
        == len(r.path) + 1
    )
    document = yaml.safe_load(r.write_ros_path_yaml(tmp_path / "p.yaml", frame_id="house").read_text())
    assert [p["floor"] for p in document["paths"]] == [0, 1]
    poses = [pose for p in document["paths"] for pose in p["path"]["poses"]]
    assert len(poses) == len(r.waypoints_simplified) and poses[0]["header"]["frame_id"] == "house"
    first, second = poses[0]["pose"], poses[1]["pose"]
    q = first["orientation"]
    assert q["z"] ** 2 + q["w"] ** 2 == pytest.approx(1.0, abs=1e-5)
    heading = math.atan2(
        second["position"]["y"] - first["position"]["y"], second["position"]["x"] - first["position"]["x"]
    )
    assert 2 * math.atan2(q["z"], q["w"]) == pytest.approx(heading, abs=1e-4)


def test_plan_json_to_stdout_and_robot_files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)
    code = main(
        [
            "plan", "--scene", "demo", "--text", "Go to the kitchen.", "--start-room", "bathroom on floor 0",
            "--json", "-", "--waypoints", "w.csv", "--ros-path", "p.yaml", "--setup", "no-llm",
        ]
    )
    out = capsys.readouterr().out
    record = json.loads(out)  # stdout holds the JSON only
    assert code == 0 and not (tmp_path / "-").exists() and (tmp_path / "w.csv").is_file()
    assert record["scene"] == "demo-house" and record["mission"]["text"] == "Go to the kitchen."
    assert record["mission"]["formula"] and record["mission"]["propositions"] == {
        "enter(room_4)": "enter(room_4)"
    }
    assert (
        record["status"] == "optimal"
        and record["cost_m"] > 0
        and record["start_from"] == "room bathroom room_5"
    )
    assert record["events"][-1]["accepting"] and record["waypoints_simplified"][0]["room"] == "room_5"
    assert "cost" not in record and all("cost_m" in it for it in record["iterations"])


def test_a_timeout_exits_3_and_prints_its_bound(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = [
        "plan", "--scene", "demo", "--formula", FORMULA, "--setup", "NO-LLM", "--json",
        str(tmp_path / "t.json"),
    ]
    assert main([*argv, "--max-expansions", "300"]) == 3
    err = capsys.readouterr().err
    record = json.loads((tmp_path / "t.json").read_text())
    assert record["status"] == "timeout" and f"within x{record['bound']:g} of the optimum" in err
    assert "--max-expansions 300" in err and record["bound"] > 1
    assert main([*argv, "--max-expansions", "1"]) == 3
    assert "no path found within the budget (--max-expansions 1)" in capsys.readouterr().err


def test_plan_draws_png_svg_and_the_automaton_and_writes_the_html_report(tmp_path: Path) -> None:
    code = main(
        [
            "plan", "--scene", "demo", "--formula", FORMULA, "--setup", "NO-LLM", "--draw",
            str(tmp_path / "d"), "--html", str(tmp_path / "r.html"),
        ]
    )
    names = {p.name for p in (tmp_path / "d").iterdir()}
    assert code == 0 and {"plan_floor_0.png", "plan_floor_1.svg", "automaton.dot", "automaton.svg"} <= names
    page = (tmp_path / "r.html").read_text()
    assert page.startswith("<!DOCTYPE html>") and "enter(room_11)" in page and 'id="events"' in page


def test_plan_records_are_json_with_one_line_per_row() -> None:
    from sgplan.outputs.jsontext import record_json

    record = demo_result().to_dict()
    text = record_json(record)
    assert json.loads(text) == json.loads(json.dumps(record)) and text.endswith("}\n")
    lines = text.splitlines()
    assert f"  {json.dumps(record['path'][0], separators=(', ', ': '))}," in lines
    rows = sum(len(record[key]) for key in ("path", "waypoints", "waypoints_simplified", "events"))
    assert len(lines) < rows + 200  # a row per line, not a number per line
    odd = {"e": [], "rows": [[1, 2], {"a": "x\ny"}], "mixed": [1, [2]], "nested": {"k": [{"z": None}]},
           "s": "é"}
    assert json.loads(record_json(odd)) == odd and record_json({}) == "{}\n"
    for bad in (float("nan"), float("inf")):
        with pytest.raises(ValueError):
            record_json({"cost_m": bad})
        with pytest.raises(ValueError):
            record_json({"rows": [[bad]]})


def test_simplified_waypoints_on_allensville_are_its_corners() -> None:
    """The first-day report: "Check both bathrooms, then go to the kitchen" from the lobby gave 766 cells and
    157 waypoints, 125 of its segments one cell long, along diagonals beside the inflated obstacles."""
    building = shared_data.scene_building("Allensville")
    mission = sgplan.mission_from_text("Check both bathrooms, then go to the kitchen", building)
    r = sgplan.plan(building, mission, start="lobby")
    keep = np.array([w.index for w in r.waypoints_simplified])
    assert len(keep) <= 25 < len(r.path) / 25
    assert check_polyline(r.path, keep, r.grid, r.labels, mission.automaton) == []
    legs = leg_costs(r.path[keep], r.grid)
    changes = set(np.flatnonzero(np.diff(r.path[:, 3])) + 1)  # rows where the mission moves on: kept
    one_cell = [k for k, leg in enumerate(legs) if leg < 0.015 and keep[k + 1] not in changes]
    assert len(one_cell) <= 1, [(keep[k], keep[k + 1]) for k in one_cell]


def test_a_waypoint_tolerance_cuts_the_inflated_corners_and_nothing_else() -> None:
    building = shared_data.scene_building("Allensville")
    mission = sgplan.mission_from_text("Check both bathrooms, then go to the kitchen", building)
    r = sgplan.plan(building, mission, start="lobby")
    exact = [w.index for w in r.waypoints_simplified]
    cut = np.array([w.index for w in r.simplify_waypoints(0.01)])
    assert len(cut) < len(exact) and r.waypoint_tolerance_m == r.to_dict()["waypoint_tolerance_m"] == 0.01
    changes = np.flatnonzero(np.diff(r.path[:, 3])) + 1
    assert set(changes) <= set(cut.tolist())  # the mission still moves on at kept waypoints
    assert check_polyline(r.path, cut, r.grid, r.labels, mission.automaton, tolerance_m=0.01,
                          building=building) == []
    without = check_polyline(r.path, cut, r.grid, r.labels, mission.automaton)
    assert any("enters blocked cell" in problem for problem in without)  # it did use the tolerance
    with pytest.raises(OutputError, match=r"below the robot radius 0\.15 m"):
        r.simplify_waypoints(0.15)
    with pytest.raises(OutputError, match="non-negative"):
        r.simplify_waypoints(-0.01)
