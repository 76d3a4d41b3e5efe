"""``sgplan simulate``: drive a simulated robot along the plan of a mission while the building changes
(:mod:`sgplan.execution.simulate`), replanning at each change, and print the timeline.

Exit codes: 0 done; 6 violated; 7 impossible (no way left when the changes ran out); 2 an error (a bad
scene, mission or changes file); 70 a bug in sgplan.
"""

from __future__ import annotations

import argparse
import sys
from typing import TextIO

from sgplan.commands.common import add_scene_arguments, load_scene_arg, plan_options, say, write_json_record
from sgplan.commands.missions import add_mission_arguments, mission_from_args
from sgplan.commands.plan import add_start_arguments, start_spec
from sgplan.commands.sayback import check_folder_fits, say_back
from sgplan.commands.translate import add_llm_arguments


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "simulate",
        help="drive a simulated robot along the plan while the building changes, replanning at each change",
        description="Drive a simulated robot along the optimal plan, apply each change of --changes when its "
        "trigger is met (after a distance, on entering a room, at a waypoint), replan from the robot's "
        "cell and mission state, and print the timeline. Exit codes: 0 done, 6 violated, 7 impossible, "
        "2 error, 70 a bug.",
    )
    add_scene_arguments(parser)
    add_mission_arguments(parser)
    parser.add_argument("--changes", required=True, metavar="FILE.yaml",
                        help="the scene changes and their triggers (docs/execution.md; JSON works too)")
    add_start_arguments(parser)
    from sgplan.commands.plan import add_planning_arguments

    add_planning_arguments(parser)
    parser.add_argument("--draw", metavar="DIR", help="write a PNG per floor: the path driven, the abandoned "
                        "plans and the changed cells")
    parser.add_argument("--html", metavar="FILE", help="write an HTML page of the timeline and the drawings")
    parser.add_argument("--json", metavar="OUT", help="write the whole log as JSON ('-': to stdout)")
    parser.add_argument("--force", action="store_true",
                        help="use a --mission-dir even if it was made for another scene")
    add_llm_arguments(parser)
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    import sgplan
    from sgplan.commands.monitor import EXIT_CODES
    from sgplan.execution.changes import read_changes
    from sgplan.execution.run import IMPOSSIBLE_EXIT
    from sgplan.execution.simulate import simulate

    out: TextIO = sys.stderr if args.json == "-" else sys.stdout
    options = plan_options(args)
    building = load_scene_arg(args.scene, args.data)
    schedule = read_changes(args.changes)
    mission, _ = mission_from_args(args, building, start_spec(args))
    record: dict = {}
    if args.mission_dir:
        check_folder_fits(args.mission_dir, mission, building, force=args.force, record=record)
    session = sgplan.Session(building)
    say_back(mission, building, record, stream=out, session=session)
    the_run = sgplan.Run(session, mission, start_spec(args), options)
    sim = simulate(the_run, schedule)
    print("timeline (metres driven):", file=out)
    for moment in sim.timeline:
        print(moment.describe(), file=out)
    if args.draw or args.html:
        import tempfile
        from pathlib import Path

        from sgplan.execution.drawing import draw_simulation, simulation_html

        folder = Path(args.draw) if args.draw else Path(tempfile.mkdtemp(prefix="sgplan-simulate-"))
        pictures = draw_simulation(sim, folder)
        if args.draw:
            for picture in pictures:
                say(f"wrote {picture}")
        if args.html:
            say(f"wrote {simulation_html(sim, pictures, args.html)}")
    if args.json:
        write_json_record(args.json, record | sim.to_dict())
    return IMPOSSIBLE_EXIT if the_run.status == "impossible" else EXIT_CODES[the_run.status]
