"""``sgplan demo``: the whole pipeline on the embedded demo building, offline, in a few seconds.

Demo building -> offline translation of a natural-language mission -> minimal DFA -> offline symbolic
guidance -> AMRA* (setup ALL) -> independent check -> PNG and SVG per floor, the automaton, an HTML report,
the mission folder, the waypoints (CSV, ROS path YAML) and the run record ``run.json`` (the shape of ``plan
--json``), all through
:mod:`sgplan.api`. Both language steps use the offline backends, which are not LLMs; the output says so.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from sgplan.commands.common import add_axes_argument, non_negative_int, say
from sgplan.commands.sayback import say_back
from sgplan.english import count
from sgplan.errors import MissionError

DEMO_MISSION = (
    "Visit the bathroom on floor 0 without touching the sink, then sit on a chair in the dining room, "
    "then go to the bedroom with the teddy bear. Always avoid the living room and the kitchen."
)


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "demo", help="run the whole pipeline on the embedded demo building (offline)",
        description="Run the whole pipeline on the embedded demo building, offline, in a few seconds: a "
        "mission in controlled English is translated (offline, not an LLM), said back, turned into an "
        "automaton and planned with AMRA*; the optimal path is checked and written as pictures per floor "
        "(PNG, SVG), an HTML report, waypoints (CSV, ROS path YAML), the mission folder and run.json.",
    )
    parser.add_argument("--out", metavar="DIR", default="out/demo", help="output folder (default: out/demo)")
    parser.add_argument(
        "--text", default=DEMO_MISSION, help="the mission (controlled English, see docs/offline.md)"
    )
    parser.add_argument(
        "--start-index", type=non_negative_int, default=0, metavar="K", help="initial position K (0-4)"
    )
    add_axes_argument(parser)
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    import sgplan
    from sgplan.llm.backends import open_backends
    from sgplan.mission import save_mission_folder
    from sgplan.outputs.jsontext import record_json
    from sgplan.result import write_text
    from sgplan.scene.hierarchy import attribute_hierarchy

    t0 = time.perf_counter()
    out = Path(args.out)
    if not args.out.strip() or (out.exists() and not out.is_dir()):
        raise MissionError("--out must name a folder to write the demo's outputs to", out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise MissionError(f"cannot create the output folder ({error.strerror or error})", out) from None
    building = sgplan.load_scene("demo")
    rooms, objects = sum(1 for _ in building.rooms()), sum(1 for _ in building.objects())
    say(f"scene: {building.name}, {count(building.num_floors, 'floor')}, {count(rooms, 'room')}, "
        f"{count(objects, 'object')} (embedded demo building)")
    print(f"mission: {args.text}")
    backends = open_backends("offline")
    mission = sgplan.mission_from_text(args.text, building, llm=backends)
    print(f"grounded: {mission.grounded_text}")
    print(f"formula:  {mission.formula}")
    print(f"automaton: {count(mission.automaton.num_states, 'state')} over "
          f"{count(len(mission.automaton.aps), 'proposition')}")
    explanation = say_back(mission, building)
    say("planning with AMRA* (setup ALL):")
    result = sgplan.plan(
        building,
        mission,
        args.start_index,
        options=sgplan.PlanOptions(setup="ALL"),
        guide=backends.guide,
        explanation=explanation,
        callback=lambda it: say(
            f"  (w1, w2) = ({it.w1:g}, {it.w2:g})  cost {it.cost_m:.3f} m  {it.time_s * 1e3:.1f} ms"
        ),
    )
    print(
        f"optimal path: {result.cost_m:.3f} m, {count(len(result.cells), 'cell')} "
        f"({count(len(result.waypoints_simplified), 'simplified waypoint')}), first path after "
        f"{result.iterations[0].time_s * 1e3:.1f} ms, optimum after "
        f"{result.timings['search_s'] * 1e3:.1f} ms of search; verified by the independent checker"
    )
    for event in result.events:
        say(f"  {event.describe()}")
    mission_dir = save_mission_folder(result.mission or mission, out / "mission",
                                      hierarchy_text=attribute_hierarchy(building),
                                      building=building)
    written = [
        *result.draw(out, axes=args.axes), result.write_html(out / "report.html"),
        result.write_waypoints_csv(out / "waypoints.csv"), result.write_ros_path_yaml(out / "ros_path.yaml"),
    ]
    record = result.to_dict()
    record["backends"] = {"translation": f"{backends.translator.name} (not an LLM)",
                          "guidance": f"{result.guidance} (not an LLM)"}
    record["timings"]["wall_s"] = time.perf_counter() - t0
    written.append(write_text(out / "run.json", record_json(record)))
    print(f"backends: translation {backends.translator.name}, guidance {result.guidance} (offline, not LLMs)")
    print(f"wrote {', '.join(str(p) for p in written)} and the mission folder {mission_dir}")
    return 0
