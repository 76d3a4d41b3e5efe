"""``sgplan plan``: plan an optimal path for a mission over a scene with AMRA* (through :mod:`sgplan.api`).

The mission is a mission folder, a formula, or natural language (``--text``, translated by the backend
of ``--llm``). When the setup needs guidance that the mission does not carry, the ``--llm`` backend's
guide provides it (the offline symbolic guide by default, which is not a language model).

Exit codes: 0 optimal; 2 an error (bad input, invalid start, infeasible mission); 3 a budget ran out
(``--time-limit`` / ``--max-expansions``): the best path so far is still written, with its bound; 4 no
path in the scene satisfies the mission, from any start; 70 a bug in sgplan.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from sgplan.commands.common import (
    add_axes_argument,
    add_profile_argument,
    add_reach_model_argument,
    add_scene_arguments,
    load_scene_arg,
    log,
    non_negative_int,
    non_negative_metres,
    plan_options,
    positive_int,
    positive_seconds,
    reach_radius,
    robot_radius,
    say,
    write_json_record,
)
from sgplan.commands.missions import add_mission_arguments, mission_from_args
from sgplan.commands.sayback import check_folder_fits, say_back
from sgplan.commands.translate import add_llm_arguments, backend_note, open_backends_from_args
from sgplan.errors import MissionError, SgplanError
from sgplan.planning.setups import SETUPS, get_setup

if TYPE_CHECKING:
    from sgplan.api import Session
    from sgplan.mission import Mission
    from sgplan.options import PlanOptions
    from sgplan.result import PlanResult
    from sgplan.starts import StartSpec

TIMEOUT_EXIT = 3
"""Exit code of a plan whose search budget ran out (distinct from errors, 2)."""


def _triple(kind: type, what: str) -> Callable[[str], tuple]:
    """An argparse type reading ``A,B,FLOOR`` with ``A`` and ``B`` of ``kind``."""

    def parse(text: str) -> tuple:
        try:
            a, b, floor = text.split(",")
            return (kind(a), kind(b), int(floor))
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None
    return parse


def add_start_arguments(parser: argparse.ArgumentParser) -> argparse._MutuallyExclusiveGroup:
    """``--start`` | ``--start-xy`` | ``--start-room`` | ``--start-index`` (:func:`start_spec` reads them);
    returns the group, for a command's own kinds of start."""
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--start", type=_triple(int, "ROW,COL,FLOOR (grid cells)"), metavar="ROW,COL,FLOOR",
                       help="start cell")
    where.add_argument(
        "--start-xy", type=_triple(float, "X,Y,FLOOR (metres, floor index)"), metavar="X,Y,FLOOR",
        help="start at a metric point (snapped to the nearest free cell within 0.5 m)",
    )
    where.add_argument("--start-room", metavar="ROOM", help="start in a room: room_<uuid>, a category "
                       "('kitchen') or 'bathroom on floor 1'; the room's free cell farthest from obstacles")
    where.add_argument("--start-index", type=non_negative_int, metavar="K",
                       help="start at the scene's initial position K (default 0)")
    return where


def add_planning_arguments(parser: argparse.ArgumentParser) -> None:
    """The planning options' arguments (setup, profile, radii, reach model, budgets), stored under the
    options' names (:func:`sgplan.commands.common.plan_options` reads them)."""
    parser.add_argument(
        "--setup", default="ALL", help=f"planner setup, any case: {', '.join(SETUPS)} (default ALL)"
    )
    add_profile_argument(parser)
    parser.add_argument("--robot-radius", dest="robot_radius_m", type=robot_radius, metavar="M",
                        help="robot radius (default: the scene's)")
    parser.add_argument("--reach-radius", dest="reach_radius_m", type=reach_radius, metavar="M",
                        help="object reach radius (default: the scene's)")
    add_reach_model_argument(parser)
    parser.add_argument("--time-limit", dest="time_limit_s", type=positive_seconds, metavar="S",
                        help="search time budget in seconds")
    parser.add_argument("--max-expansions", type=positive_int, metavar="N", help="search expansion budget")


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "plan",
        help="plan an optimal path for a mission (AMRA*)",
        description="Plan an optimal path. Exit codes: 0 optimal, 2 error, 3 budget ran out "
        "(the best path so far is still written), 4 no path in the scene "
        "satisfies the mission, 70 a bug.",
    )
    add_scene_arguments(parser)
    add_mission_arguments(parser)
    parser.add_argument(
        "--guidance", metavar="FILE", help="llm_heuristic.yaml to use instead of the mission's"
    )
    where = add_start_arguments(parser)
    where.add_argument("--after", metavar="FILE.csv",
                       help="plan the rest of the mission from the end of this trajectory (the poses a robot "
                       "drove: a CSV as --waypoints writes, or x_m,y_m,floor rows), in the mission state "
                       "the trajectory left it in")
    add_planning_arguments(parser)
    _add_output_arguments(parser)
    parser.add_argument("--verify", action="store_true", default=None,
                        help="accepted for old scripts, changes nothing: every path is checked by the "
                        "independent checker")
    parser.add_argument("--confirm", action="store_true",
                        help="show what will be planned and ask before planning (needs a terminal)")
    parser.add_argument("--force", action="store_true",
                        help="plan a --mission-dir even if it was made for another scene")
    parser.add_argument(
        "--save-mission", metavar="DIR",
        help="with --text: save the translated mission, its guidance and the LLM run record here",
    )
    add_llm_arguments(parser)
    parser.set_defaults(run=run)


def _add_output_arguments(parser: argparse.ArgumentParser) -> None:
    """The ``outputs`` group: JSON, waypoint files, pictures and the HTML report."""
    out = parser.add_argument_group("outputs")
    out.add_argument("--json", metavar="OUT", help="write the result as JSON ('-': to stdout)")
    out.add_argument("--waypoints", metavar="FILE.csv", help="write the simplified metric waypoints as CSV")
    out.add_argument(
        "--ros-path",
        metavar="FILE.yaml",
        help="write the simplified waypoints as YAML shaped like "
        "ROS nav_msgs/Path messages, one per floor stretch",
    )
    out.add_argument("--dense", action="store_true", help="--waypoints / --ros-path hold every cell, not the "
                     "simplified polyline")
    out.add_argument("--waypoint-tolerance", type=non_negative_metres, default=0.0, metavar="M",
                     help="simplified segments may give up M metres of clearance at the inflated obstacles' "
                     "edge, for fewer waypoints where the path hugs a corner (below the robot radius; "
                     "default 0: the planner's own clearance)")
    out.add_argument(
        "--draw", metavar="DIR",
        help="write one PNG and one SVG per floor with the path, and the automaton (DOT, SVG)",
    )
    add_axes_argument(out)
    out.add_argument("--html", metavar="FILE", help="write a self-contained HTML report of the plan")


def run(args: argparse.Namespace) -> int:
    t_start = time.perf_counter()
    record: dict[str, Any] = {"status": "error", "profile": args.profile, "setup": args.setup}
    try:
        result, extras = _plan(args)
    except SgplanError as error:
        record.update(status=getattr(error, "status", "error"), message=str(error))
        write_json_record(args.json, record)
        raise
    record = result.to_dict() | extras
    record["timings"]["wall_s"] = time.perf_counter() - t_start
    write_json_record(args.json, record)
    return _report(args, result)


def _plan(args: argparse.Namespace) -> tuple[PlanResult, dict[str, Any]]:
    """The plan of ``args``, and what the JSON record holds beyond the result (scene fit, LLM calls)."""
    import sgplan
    from sgplan.mission import read_guidance, write_guidance

    options = plan_options(args)
    building = load_scene_arg(args.scene, args.data)
    if args.save_mission and not args.text:
        raise MissionError("--save-mission saves a translated mission: use it with --text")
    mission, backends = mission_from_args(args, building, start_spec(args), save_to=args.save_mission)
    if args.guidance:
        mission.guidance = read_guidance(args.guidance)
    for note in mission.notes:
        say(f"note: {note}")
    extras: dict[str, Any] = {}
    if args.mission_dir:
        check_folder_fits(args.mission_dir, mission, building, force=args.force, record=extras)
    # The session keeps where each proposition holds between the saying back and the plan (no planner
    # parts: this process plans once).
    session = sgplan.Session(building, max_shared_bytes=0)
    # Said back before any guidance call or search; on stderr when stdout carries the JSON.
    explanation = say_back(mission, building, confirm=args.confirm,
                           stream=sys.stderr if args.json == "-" else sys.stdout, session=session,
                           reach_radius_m=options.reach_radius_m, reach_model=options.effective_reach_model)
    guide = None
    if get_setup(options.setup).uses_llm and mission.guidance is None:
        if backends is None:
            backends = open_backends_from_args(args, mission_text=mission.grounded_text or mission.text)
        guide = backends.guide
        say(f"setup {options.setup} needs guidance: asking {guide.name} ({backend_note(backends)})")

    def progress(it: Any) -> None:
        say(f"  (w1, w2) = ({it.w1:g}, {it.w2:g})  cost {it.cost_m:.4f} m  bound x{it.bound:g}  "
            f"{it.time_s:.3f} s  {sum(it.expansions):,} expansions")

    start, start_state = start_spec(args), None
    if args.after:
        start, start_state = _trajectory_end(args, session, mission, options, extras)
    result = sgplan.plan(building, mission, start, options=options, guide=guide,
                         callback=progress, explanation=explanation,  # said back above: not made twice
                         session=session, start_state=start_state)
    if args.waypoint_tolerance and result.path is not None:
        result.simplify_waypoints(args.waypoint_tolerance)
    if args.save_mission and guide is not None and result.mission is not None and result.mission.guidance:
        say(
            f"wrote {write_guidance(result.mission.guidance, Path(args.save_mission) / 'llm_heuristic.yaml')}"
        )
    if backends is not None and backends.chat is not None:
        from sgplan.llm.translation import RECORD_NAME

        summary = backends.record.to_json()["summary"]
        extras["llm"] = {"backend": backends.description, "calls": summary["calls"],
                         "from_cache": summary["from_cache"]}
        if args.save_mission:
            backends.record.save(Path(args.save_mission) / RECORD_NAME)
    return result, extras


def _trajectory_end(args: argparse.Namespace, session: Session, mission: Mission, options: PlanOptions,
                    extras: dict[str, Any]) -> tuple[tuple[int, int, int], int]:
    """The cell and mission state at the end of the ``--after`` trajectory (read by the monitor, its
    recorded columns checked); the monitor's verdict goes into ``extras``.

    Raises
    ------
    MissionViolatedError
        the trajectory broke the mission (naming the step).
    """
    from sgplan.errors import MissionViolatedError, TrajectoryError
    from sgplan.execution.monitor import Monitor
    from sgplan.execution.trajectory import read_trajectory, recorded_mismatches

    trajectory = read_trajectory(args.after)
    monitor = Monitor.in_session(session, mission, profile=options.profile,
                                 robot_radius_m=options.robot_radius_m, reach_radius_m=options.reach_radius_m,
                                 reach_model=options.effective_reach_model)
    try:
        status = monitor.observe_xy(trajectory.poses, name=trajectory.pose_name)
    except TrajectoryError as error:
        raise TrajectoryError(str(error), trajectory.path) from None
    for message in recorded_mismatches(trajectory, monitor.grid, status.states, status.lengths_m):
        log.warning(f"warning: {trajectory.path}: {message}")
    for issue in status.issues[:3]:
        log.warning(f"warning: {issue.message}")
    extras["after"] = {"trajectory": str(trajectory.path), **status.to_dict()}
    if status.verdict == "violated":
        raise MissionViolatedError(f"{trajectory.path}: the trajectory "
                                   f"{status.summary(trajectory.pose_name)}")
    say(f"after {trajectory.path}: {status.summary(trajectory.pose_name)}")
    assert status.cell is not None
    return status.cell, status.state


def start_spec(args: argparse.Namespace) -> StartSpec:
    """The start given by --start, --start-xy, --start-room or --start-index (see sgplan.starts); with
    ``plan --after``, the trajectory's last pose."""
    from sgplan.starts import Point

    if getattr(args, "after", None):
        from sgplan.execution.trajectory import read_trajectory

        x_m, y_m, floor = read_trajectory(args.after).poses[-1]
        return Point(float(x_m), float(y_m), int(floor))
    if args.start_xy:
        return Point(*args.start_xy)
    return args.start or args.start_room or args.start_index


def _report(args: argparse.Namespace, result: PlanResult) -> int:
    """Print the outcome (to stderr when the JSON goes to stdout), write the files; the exit code."""
    out: TextIO = sys.stderr if args.json == "-" else sys.stdout
    if result.path is not None:
        print(result.summary() + f", search {result.timings['search_s']:.3f} s, precompute "
              f"{result.timings['precompute_s']:.3f} s", file=out)
        print(
            f"verified: the path is legal, collision-free and accepted; cost {result.cost_m:.4f} m", file=out
        )
        for event in result.events:
            say(f"  {event.describe()}")
        simplified = not args.dense
        if args.waypoints:
            say(f"wrote {result.write_waypoints_csv(args.waypoints, simplified=simplified)}")
        if args.ros_path:
            say(f"wrote {result.write_ros_path_yaml(args.ros_path, simplified=simplified)}")
    if args.draw:
        for picture in result.draw(args.draw, axes=args.axes):
            say(f"wrote {picture}")
    if args.html:
        say(f"wrote {result.write_html(args.html)}")
    if result.status == "timeout":
        budget = ", ".join(part for part in (
            f"--time-limit {args.time_limit_s:g} s" if args.time_limit_s is not None else "",
            f"--max-expansions {args.max_expansions}" if args.max_expansions is not None else "") if part)
        if result.path is None:
            log.warning(f"sgplan: timeout: no path found within the budget ({budget})")
        else:
            log.warning(
                f"sgplan: timeout: the budget ({budget}) ran out; the path's cost {result.cost_m:.4f} m is "
                f"within x{result.bound:g} of the optimum"
            )
        return TIMEOUT_EXIT
    return 0
