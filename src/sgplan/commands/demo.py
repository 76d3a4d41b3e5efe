"""``sgplan demo``: the whole pipeline on the embedded demo building, offline, in a few seconds.

Demo building -> offline translation of a natural-language mission -> minimal DFA -> offline symbolic
guidance -> AMRA* (setup ALL) -> independent check -> PNGs per floor, the mission folder and a JSON run
record. Both language steps use the offline backends, which are not LLMs; the output says so.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from sgplan.commands.common import non_negative_int, say
from sgplan.commands.sayback import say_back

DEMO_MISSION = (
    "Visit the bathroom on floor 0 without touching the sink, then sit on a chair in the dining room, "
    "then go to the bedroom with the teddy bear. Always avoid the living room and the kitchen."
)
FIRST_RUN_HINT_S = 3.0
"""Above this set-up time (seconds) the demo explains that numba was compiling (first run only)."""


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("demo", help="run the whole pipeline on the embedded demo building (offline)")
    parser.add_argument("--out", metavar="DIR", default="out/demo", help="output folder (default: out/demo)")
    parser.add_argument("--text", default=DEMO_MISSION, help="the mission (controlled English, see docs/offline.md)")
    parser.add_argument("--start-index", type=non_negative_int, default=0, metavar="K", help="initial position K (0-4)")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from sgplan.llm.offline import PatternTranslator
    from sgplan.mission import mission_from_formula, save_mission_folder
    from sgplan.pipeline import add_offline_guidance, make_problem, resolve_start, result_record
    from sgplan.planning.amra import plan
    from sgplan.planning.checker import check_path
    from sgplan.scene.demo import demo_building
    from sgplan.scene.draw import draw_building
    from sgplan.scene.hierarchy import attribute_hierarchy

    t0 = time.perf_counter()
    out = Path(args.out)
    building = demo_building()
    say(f"scene: {building.name}, {building.num_floors} floors, {sum(1 for _ in building.rooms())} rooms, "
        f"{sum(1 for _ in building.objects())} objects (embedded demo building)")
    print(f"mission: {args.text}")

    translator = PatternTranslator()
    translation = translator.translate(args.text, building)
    mission = mission_from_formula(translation.formula, text=args.text, grounded_text=translation.grounded_text)
    print(f"grounded: {translation.grounded_text}")
    print(f"formula:  {translation.formula}")
    print(f"automaton: {mission.automaton.num_states} states over {len(mission.automaton.aps)} propositions")
    explanation = say_back(mission, building)
    guide_name = add_offline_guidance(mission, building)

    start = resolve_start(building, index=args.start_index)
    prepared = make_problem(building, mission, start)
    say(f"planning from {start} with AMRA* (setup ALL):")
    result = plan(
        prepared.problem, "ALL",
        callback=lambda it: say(f"  (w1, w2) = ({it.w1:g}, {it.w2:g})  cost {it.cost_m:.3f} m  {it.time_s * 1e3:.1f} ms"),
    )
    setup_s = prepared.build_s + result.precompute_s
    if setup_s > FIRST_RUN_HINT_S:
        say(f"  (set-up took {setup_s:.1f} s, mostly the one-time compile of the planner's numba kernels; "
            "they are cached, so later runs start in about a second)")
    check = check_path(result.path, prepared.problem.grid, prepared.problem.labels, mission.automaton)
    if not check.valid:  # pragma: no cover - a bug, not a user error
        raise RuntimeError(f"demo path failed the independent check: {check.problems}")
    print(f"optimal path: {result.cost_m:.3f} m, {len(result.path)} cells, first path after "
          f"{result.iterations[0].time_s * 1e3:.1f} ms, optimum after {result.search_s * 1e3:.1f} ms of search; "
          "verified by the independent checker")

    mission_dir = save_mission_folder(mission, out / "mission", hierarchy_text=attribute_hierarchy(building),
                                      building=building)
    cells = [tuple(int(v) for v in row[:3]) for row in result.path]
    pngs = draw_building(building, out, grid=prepared.problem.grid, path=cells, stem="plan_floor")
    record = {
        "backends": {"translation": f"{translator.name} (not an LLM)", "guidance": f"{guide_name} (not an LLM)"},
        "scene": building.name,
        "mission": {"text": args.text, "grounded_text": translation.grounded_text,
                    "tokens": list(translation.tokens), "formula": str(translation.formula),
                    "explanation": explanation.to_dict()},
        "start": list(start),
        "plan": result_record(result),
        "verified": check.valid,
        "wall_s": time.perf_counter() - t0,
    }
    (out / "run.json").write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
    print(f"backends: translation {translator.name}, guidance {guide_name} (offline, not LLMs)")
    print(f"wrote {', '.join(str(p) for p in pngs)}, {out / 'run.json'} and the mission folder {mission_dir}")
    return 0
