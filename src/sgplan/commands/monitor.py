"""``sgplan monitor``: judge the trajectory a robot drove against a mission (:mod:`sgplan.execution.monitor`).

The mission is said back first, as by ``plan``; then the verdict, what is left, and what the monitor had to
assume about the poses (warnings). See docs/execution.md.

Exit codes: 0 done (the mission is satisfied); 5 in progress (not yet satisfied, still possible);
6 violated (no continuation can satisfy it any more); 2 an error (a bad file, pose or mission);
70 a bug in sgplan.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from typing import TYPE_CHECKING, Any, TextIO

from sgplan.commands.common import (
    add_profile_argument,
    add_reach_model_argument,
    add_scene_arguments,
    load_scene_arg,
    log,
    positive_number,
    reach_radius,
    robot_radius,
    write_json_record,
)
from sgplan.commands.missions import add_mission_arguments, mission_from_args
from sgplan.commands.sayback import check_folder_fits, say_back
from sgplan.commands.translate import add_llm_arguments
from sgplan.english import count
from sgplan.errors import TrajectoryError
from sgplan.planning.setups import reach_model_for

if TYPE_CHECKING:
    from sgplan.execution.monitor import MonitorStatus
    from sgplan.execution.trajectory import Trajectory

IN_PROGRESS_EXIT = 5
"""Exit code of a trajectory after which the mission is not yet satisfied but still can be."""
VIOLATED_EXIT = 6
"""Exit code of a trajectory after which no continuation can satisfy the mission."""
EXIT_CODES = {"done": 0, "in-progress": IN_PROGRESS_EXIT, "violated": VIOLATED_EXIT}


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "monitor",
        help="judge a driven trajectory against a mission: done, in progress (what is left) or violated",
        description="Read the poses a robot drove (a CSV of x_m, y_m, floor, e.g. plan --waypoints) and say "
        "whether the mission is done, in progress (and what is left) or violated (and by which step). "
        "Exit codes: 0 done, 5 in progress, 6 violated, 2 error, 70 a bug.",
    )
    add_scene_arguments(parser)
    add_mission_arguments(parser)
    parser.add_argument("--trajectory", required=True, metavar="FILE.csv",
                        help="the poses driven: a CSV with x_m, y_m, floor columns (plan --waypoints writes "
                        "one) or plain x_m,y_m,floor rows")
    add_profile_argument(parser)
    parser.add_argument("--robot-radius", type=robot_radius, metavar="M",
                        help="robot radius (default: the scene's): which cells count as obstacles")
    parser.add_argument("--reach-radius", type=reach_radius, metavar="M",
                        help="object reach radius (default: the scene's)")
    add_reach_model_argument(parser)
    parser.add_argument("--max-gap", type=positive_number, metavar="M", default=None,
                        help="report consecutive poses farther apart than this (metres; default 1, none "
                             "for a plan --waypoints file, whose straight segments are the path's)")
    parser.add_argument("--json", metavar="OUT", help="write the verdict as JSON ('-': to stdout)")
    parser.add_argument("--force", action="store_true",
                        help="monitor with a --mission-dir even if it was made for another scene")
    add_llm_arguments(parser)
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    import sgplan
    from sgplan.execution.monitor import Monitor
    from sgplan.execution.trajectory import read_trajectory, recorded_mismatches
    from sgplan.starts import Point

    t0 = time.perf_counter()
    out: TextIO = sys.stderr if args.json == "-" else sys.stdout
    building = load_scene_arg(args.scene, args.data)
    trajectory = read_trajectory(args.trajectory)
    x_m, y_m, floor = trajectory.poses[0]
    mission, _ = mission_from_args(args, building, Point(x_m, y_m, int(floor)))
    reach_model = reach_model_for(args.profile, args.reach_model)
    record: dict[str, Any] = {"scene": building.name, "trajectory": str(trajectory.path),
                              "profile": args.profile, "reach_model": reach_model,
                              "mission_text": mission.text}
    if args.mission_dir:
        check_folder_fits(args.mission_dir, mission, building, force=args.force, record=record)
    session = sgplan.Session(building, max_shared_bytes=0)
    say_back(mission, building, record, stream=out, session=session, reach_radius_m=args.reach_radius,
             reach_model=reach_model)
    monitor = Monitor.in_session(session, mission, profile=args.profile, robot_radius_m=args.robot_radius,
                                 reach_radius_m=args.reach_radius, reach_model=reach_model,
                                 max_gap_m=_max_gap_m(args, trajectory))
    try:
        status = monitor.observe_xy(trajectory.poses, name=trajectory.pose_name)
    except TrajectoryError as error:
        raise TrajectoryError(str(error), trajectory.path) from None
    mismatches = recorded_mismatches(trajectory, monitor.grid, status.states, status.lengths_m)
    _report(status, trajectory, mismatches, monitor.mission.automaton.num_states, out)
    if args.json:
        record |= {"formula": str(mission.formula) if mission.formula is not None else None,
                   **status.to_dict(), "recorded_mismatches": mismatches,
                   "wall_s": time.perf_counter() - t0}
        write_json_record(args.json, record)
    return EXIT_CODES[status.verdict]


def _max_gap_m(args: argparse.Namespace, trajectory: Trajectory) -> float:
    """``--max-gap``; else none for sgplan's own waypoints (their segments are the path's), else the
    default tolerance."""
    from sgplan.execution.monitor import DEFAULT_MAX_GAP_M

    if args.max_gap is not None:
        return float(args.max_gap)
    return math.inf if trajectory.from_sgplan else DEFAULT_MAX_GAP_M


def _report(status: MonitorStatus, trajectory: Trajectory, mismatches: list[str], num_states: int,
            out: TextIO) -> None:
    """The verdict on ``out``; per kind of issue its first one (and how many more), and the mismatches, as
    warnings (stderr)."""
    by_kind: dict[str, list[str]] = {}
    for issue in status.issues:
        by_kind.setdefault(issue.kind, []).append(issue.message)
    for messages in by_kind.values():
        more = f" (and {len(messages) - 1} more like it; --json lists them all)" if len(messages) > 1 else ""
        log.warning(f"warning: {messages[0]}{more}")
    for message in mismatches:
        log.warning(f"warning: {trajectory.path}: {message}")
    print(f"trajectory {trajectory.path}: {count(status.poses, 'pose')}, {count(status.cells, 'cell')} read, "
          f"{status.length_m:.2f} m; automaton state {status.state} (states 0..{num_states - 1})", file=out)
    print(f"verdict: {status.summary(trajectory.pose_name)}", file=out)
