"""Trajectory files: the waypoint CSVs sgplan writes and plain x_m,y_m,floor rows, their one-line errors, and
the recorded columns (q, cost_m, row, col) checked against what the monitor recomputes."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sgplan.errors import TrajectoryError
from sgplan.execution.monitor import Monitor
from sgplan.execution.trajectory import Trajectory, read_trajectory, recorded_mismatches
from sgplan.outputs.robot_files import write_waypoints_csv
from sgplan.outputs.waypoints import path_waypoints, simplify_path
from tests.plans import REACH_M, demo_plan


def waypoints_file(folder: Path, simplified: bool) -> Path:
    demo = demo_plan()
    path = demo.result.path
    assert path is not None
    labels = demo.mission.labels(demo.building, REACH_M)
    keep = simplify_path(path, demo.grid, labels, demo.mission.automaton) if simplified else None
    return write_waypoints_csv(path_waypoints(path, demo.grid, demo.building, keep),
                               folder / f"{'simplified' if simplified else 'dense'}.csv")


def mismatches(trajectory: Trajectory) -> list[str]:
    demo = demo_plan()
    mon = Monitor(demo.building, demo.mission, demo.grid, demo.mission.labels(demo.building, REACH_M))
    status = mon.observe_xy(trajectory.poses, name=trajectory.pose_name)
    return recorded_mismatches(trajectory, demo.grid, status.states, status.lengths_m)


@pytest.mark.parametrize("simplified", [False, True])
def test_the_waypoint_files_of_a_plan_read_back_and_agree_with_the_monitor(tmp_path: Path, simplified: bool):
    trajectory = read_trajectory(waypoints_file(tmp_path, simplified))
    path = demo_plan().result.path
    assert path is not None
    assert set(trajectory.recorded) == {"q", "cost_m", "row", "col"}
    assert trajectory.lines[0] == 2 and trajectory.pose_name(1) == "pose 1 (line 3)"
    assert trajectory.poses[0, 2] == path[0, 2] and trajectory.poses[-1, 2] == path[-1, 2]
    if not simplified:
        assert len(trajectory.poses) == len(path) and trajectory.recorded["q"].tolist() == path[:, 3].tolist()
    assert mismatches(trajectory) == []


def test_plain_rows_without_a_header_with_comments_and_blank_lines(tmp_path: Path):
    file = tmp_path / "t.csv"
    file.write_text("# driven on 2026-11-27\n0.5,1.25,0\n\n  # a comment\n-0.5, 2, 1\n")
    trajectory = read_trajectory(file)
    assert trajectory.poses.tolist() == [[0.5, 1.25, 0.0], [-0.5, 2.0, 1.0]]
    assert trajectory.lines.tolist() == [2, 5] and trajectory.recorded == {}


def test_extra_columns_are_ignored_and_the_order_is_free(tmp_path: Path):
    file = tmp_path / "t.csv"
    file.write_text("stamp,floor,y_m,x_m\n10.0,0,2.0,1.0\n10.1,0,2.1,1.1\n")
    assert read_trajectory(file).poses.tolist() == [[1.0, 2.0, 0.0], [1.1, 2.1, 0.0]]


@pytest.mark.parametrize(("text", "fragment"), [
    ("", "t.csv: no poses: expected a header naming x_m, y_m, floor"),
    ("x_m,y_m,floor\n", "t.csv: line 1: no poses after the header"),
    ("x,y,floor\n1,2,0\n", "t.csv: line 1: the header has no x_m, y_m column (found: 'x, y, floor')"),
    ("x_m,y_m,floor,q,q\n1,2,0,0,0\n", "t.csv: line 1: the header names q more than once"),
    ("x_m,y_m,floor\n1,2,0\n1,2\n", "t.csv: line 3: 2 fields, the header has 3 (x_m, y_m, floor)"),
    ("x_m,y_m,floor\n1,2,0\n1,abc,0\n", "t.csv: line 3: field y_m: 'abc' is not a finite number of metres"),
    ("x_m,y_m,floor\n1,inf,0\n", "t.csv: line 2: field y_m: 'inf' is not a finite number of metres"),
    ("x_m,y_m,floor\n1,2,0.5\n", "t.csv: line 2: field floor: '0.5' is not a whole number"),
    ("x_m,y_m,floor,q\n1,2,0,\n", "t.csv: line 2: field q: '' is not a whole number"),
    ("1,2\n", "t.csv: line 1: 2 fields; a trajectory without a header has rows x_m,y_m,floor"),
])
def test_bad_files_get_one_line_naming_the_line_and_field(tmp_path: Path, text: str, fragment: str):
    file = tmp_path / "t.csv"
    file.write_text(text)
    with pytest.raises(TrajectoryError) as error:
        read_trajectory(file)
    assert str(error.value).startswith(f"{tmp_path}/{fragment}") and "\n" not in str(error.value)


def test_a_missing_file_is_named(tmp_path: Path):
    with pytest.raises(TrajectoryError, match=r"nothing\.csv"):
        read_trajectory(tmp_path / "nothing.csv")


def _edit(file: Path, line: int, column: str, value: str) -> None:
    lines = file.read_text().splitlines()
    header = lines[0].split(",")
    fields = lines[line - 1].split(",")
    fields[header.index(column)] = value
    lines[line - 1] = ",".join(fields)
    file.write_text("\n".join(lines) + "\n")


def test_recorded_columns_that_differ_are_reported_by_line(tmp_path: Path):
    file = waypoints_file(tmp_path, simplified=False)
    _edit(file, 5, "q", "9")
    _edit(file, 7, "q", "9")
    _edit(file, 6, "cost_m", "99.0")
    _edit(file, 8, "row", "0")
    found = mismatches(read_trajectory(file))
    assert found[0] == ("line 5: q is 9, but the monitor computes 0 (the file was made for another mission "
                        "or semantics profile?); 1 more lines differ")
    assert found[1].startswith("line 6: cost_m is 99.0000, but the route through the poses is 0.")
    assert found[2].startswith("line 8: row is 0, but the cell of its x_m is in row ")
    assert len(found) == 3


def test_the_monitor_names_a_bad_pose_by_its_line(tmp_path: Path):
    file = tmp_path / "t.csv"
    file.write_text("x_m,y_m,floor\n# start\n0,0,0\n1000,0,0\n")
    trajectory = read_trajectory(file)
    demo = demo_plan()
    mon = Monitor(demo.building, demo.mission, demo.grid, demo.mission.labels(demo.building, REACH_M))
    with pytest.raises(TrajectoryError, match=r"^pose 1 \(line 4\): \(x 1000 m, y 0 m, floor 0\) lies off"):
        mon.observe_xy(trajectory.poses, name=trajectory.pose_name)
    assert np.isfinite(trajectory.poses).all()
