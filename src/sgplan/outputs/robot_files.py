"""Waypoint files for a robot stack: CSV, and YAML shaped like ROS ``nav_msgs/Path`` messages per floor.

The YAML holds one ``nav_msgs/Path`` per stretch of the route on one floor, in route order (a route that
goes up and comes back down has two stretches on the lower floor)::

    frame_id: map
    paths:
      - floor: 0
        path:                      # a nav_msgs/Path message
          header: {frame_id: map, stamp: {sec: 0, nanosec: 0}}
          poses:                   # geometry_msgs/PoseStamped
            - header: {frame_id: map, stamp: {sec: 0, nanosec: 0}}
              pose:
                position: {x: 1.25, y: -3.5, z: 0.0}
                orientation: {x: 0.0, y: 0.0, z: 0.38, w: 0.92}   # heading to the next pose

Positions are metres in the scene's frame (rounded to 0.1 mm); orientations are yaw-only quaternions facing
the next pose
(the last pose of a stretch keeps the heading of the one before).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Sequence
from pathlib import Path

import yaml

from sgplan.errors import OutputError
from sgplan.outputs.waypoints import Waypoint

CSV_COLUMNS = ("index", "x_m", "y_m", "z_m", "floor", "room", "room_name", "row", "col", "q", "cost_m")


def _open_for_writing(path: str | Path) -> Path:
    target = Path(path).expanduser()
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise OutputError(f"{target}: cannot create the folder: {error.strerror}") from None
    return target


def write_waypoints_csv(waypoints: Sequence[Waypoint], path: str | Path) -> Path:
    """Write one CSV row per waypoint (header :data:`CSV_COLUMNS`; empty room fields outside rooms)."""
    target = _open_for_writing(path)
    try:
        with target.open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(CSV_COLUMNS)
            for w in waypoints:
                writer.writerow(
                    [
                        w.index, f"{w.x_m:.4f}", f"{w.y_m:.4f}", f"{w.z_m:.4f}", w.floor, w.room or "",
                        w.room_name or "", w.row, w.col, w.q, f"{w.cost_m:.4f}",
                    ]
                )
    except OSError as error:
        raise OutputError(f"{target}: cannot write the waypoints: {error.strerror}") from None
    return target


def _stamp(frame_id: str) -> dict[str, object]:
    return {"frame_id": frame_id, "stamp": {"sec": 0, "nanosec": 0}}


def ros_paths(waypoints: Sequence[Waypoint], frame_id: str = "map") -> dict[str, object]:
    """The document of :func:`write_ros_path_yaml` (see the module) as plain dicts and lists."""
    stretches: list[list[Waypoint]] = []
    for w in waypoints:
        if not stretches or stretches[-1][-1].floor != w.floor:
            stretches.append([])
        stretches[-1].append(w)
    paths = []
    for stretch in stretches:
        poses = []
        yaw = 0.0
        for k, w in enumerate(stretch):
            if k + 1 < len(stretch):
                nxt = stretch[k + 1]
                yaw = math.atan2(nxt.y_m - w.y_m, nxt.x_m - w.x_m)
            poses.append({
                "header": _stamp(frame_id),
                "pose": {
                    "position": {"x": round(w.x_m, 4), "y": round(w.y_m, 4), "z": round(w.z_m, 4)},
                    "orientation": {"x": 0.0, "y": 0.0, "z": round(math.sin(yaw / 2), 6),
                                    "w": round(math.cos(yaw / 2), 6)},
                },
            })
        paths.append({"floor": stretch[0].floor, "path": {"header": _stamp(frame_id), "poses": poses}})
    return {"frame_id": frame_id, "paths": paths}


def write_ros_path_yaml(waypoints: Sequence[Waypoint], path: str | Path, frame_id: str = "map") -> Path:
    """Write the waypoints as ROS ``nav_msgs/Path`` messages per floor stretch (see the module)."""
    target = _open_for_writing(path)
    try:
        target.write_text(yaml.safe_dump(ros_paths(waypoints, frame_id), sort_keys=False), encoding="utf-8")
    except OSError as error:
        raise OutputError(f"{target}: cannot write the ROS path: {error.strerror}") from None
    return target
