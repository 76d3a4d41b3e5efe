"""``sgplan plan``: plan an optimal path for a mission over a scene with AMRA*.

The mission is a mission folder, a formula, or natural language (``--text``, translated by the backend
of ``--llm``). When the setup needs guidance that the mission does not carry, the ``--llm`` backend's
guide provides it (the offline symbolic guide by default, which is not a language model).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sgplan.commands.common import (add_scene_arguments, load_scene_arg, non_negative_int, positive_int,
                                    positive_seconds, reach_radius, robot_radius, say)
from sgplan.commands.translate import add_llm_arguments, open_backends_from_args
from sgplan.errors import MissionError, PlanningError, SgplanError

if TYPE_CHECKING:
    from sgplan.llm.backends import Backends
    from sgplan.mission import Mission
    from sgplan.scene.model import Building


def _start_cell(text: str) -> tuple[int, int, int]:
    try:
        row, col, floor = (int(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected ROW,COL,FLOOR (grid cells), got {text!r}") from None
    return (row, col, floor)


def register(sub: argparse._SubParsersAction) -> None:
    from sgplan.planning.amra import SETUPS

    parser = sub.add_parser("plan", help="plan an optimal path for a mission (AMRA*)")
    add_scene_arguments(parser)
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--mission-dir", metavar="DIR", help="mission folder (automaton.aut, ap_desc.yaml, llm_heuristic.yaml)")
    what.add_argument("--formula", metavar="F", help="LTL formula: token list, Spot infix or LBT prefix")
    what.add_argument("--text", metavar="MISSION", help="the mission in natural language (translated with --llm)")
    parser.add_argument("--aps", metavar="FILE", help="ap_desc.yaml giving the formula's proposition names a meaning")
    parser.add_argument("--guidance", metavar="FILE", help="llm_heuristic.yaml to use instead of the mission's")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--start", type=_start_cell, metavar="ROW,COL,FLOOR", help="start cell")
    where.add_argument("--start-index", type=non_negative_int, metavar="K", help="start at the scene's initial position K")
    parser.add_argument("--setup", default="ALL", help=f"planner setup: {', '.join(SETUPS)} (default ALL)")
    parser.add_argument("--profile", choices=("ltlf", "authors"), default="ltlf",
                        help="semantics: ltlf (default; start label read, missing automaton edges reject) or "
                             "authors (the authors' C++: start label not read, missing edges keep the state)")
    parser.add_argument("--robot-radius", type=robot_radius, metavar="M", help="robot radius (default: the scene's)")
    parser.add_argument("--reach-radius", type=reach_radius, metavar="M", help="object reach radius (default: the scene's)")
    parser.add_argument("--time-limit", type=positive_seconds, metavar="S", help="search time budget in seconds")
    parser.add_argument("--max-expansions", type=positive_int, metavar="N", help="search expansion budget")
    parser.add_argument("--json", metavar="OUT", help="write the result as JSON")
    parser.add_argument("--draw", metavar="DIR", help="write one PNG per floor with the path")
    parser.add_argument("--verify", action="store_true", help="check the path with the independent checker")
    parser.add_argument("--save-mission", metavar="DIR",
                        help="with --text: save the translated mission, its guidance and the LLM run record here")
    add_llm_arguments(parser)
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    t_start = time.perf_counter()
    record: dict[str, Any] = {"status": "error", "profile": args.profile, "setup": args.setup}
    try:
        status = _plan(args, record, t_start)
    except SgplanError as error:
        record.update(status=getattr(error, "status", "error"), message=str(error))
        _write_json(args.json, record)
        raise
    _write_json(args.json, record)
    return status


def _plan(args: argparse.Namespace, record: dict[str, Any], t_start: float) -> int:
    from sgplan.mission import load_mission_folder, mission_from_formula, read_ap_desc, read_guidance, write_guidance
    from sgplan.pipeline import make_problem, resolve_start, result_record
    from sgplan.planning.amra import get_setup, plan

    building = load_scene_arg(args.scene, args.data)
    if args.save_mission and not args.text:
        raise MissionError("--save-mission saves a translated mission: use it with --text")
    backends = None
    if args.mission_dir:
        mission = load_mission_folder(args.mission_dir, profile=args.profile)
    elif args.formula:
        mission = mission_from_formula(args.formula, read_ap_desc(args.aps) if args.aps else None)
    else:
        backends = open_backends_from_args(args)
        say(f"translating with {backends.translator.name} ({backends.description})")
        mission = _translate(args, building, backends)
    if args.guidance:
        mission.guidance = read_guidance(args.guidance)
    for note in mission.notes:
        say(f"note: {note}")
    if get_setup(args.setup).uses_llm and mission.guidance is None:
        mission_text = mission.grounded_text or mission.text
        from sgplan.llm.guidance import LLMGuide  # LLM modules only when a guide is needed (~0.2 s)

        if backends is None:
            backends = open_backends_from_args(args, mission_text=mission_text)
        elif isinstance(backends.guide, LLMGuide):
            backends.guide.mission_text = mission_text  # the grounded text, known only after translation
        say(f"setup {args.setup} needs guidance: asking {backends.guide.name} ({backends.description})")
        mission.guidance = backends.guide.guide(building, mission.automaton, mission.descriptions)
        if args.save_mission:
            say(f"wrote {write_guidance(mission.guidance, Path(args.save_mission) / 'llm_heuristic.yaml')}")
    if backends is not None and backends.chat is not None:
        summary = backends.record.to_json()["summary"]
        record["llm"] = {"backend": backends.description, "calls": summary["calls"], "from_cache": summary["from_cache"]}
        if args.save_mission:
            from sgplan.llm.translation import RECORD_NAME  # the LLM stack costs ~0.5 s: only when used

            backends.record.save(Path(args.save_mission) / RECORD_NAME)
    start = resolve_start(building, args.start, args.start_index)
    prepared = make_problem(building, mission, start, profile=args.profile,
                            robot_radius_m=args.robot_radius, reach_radius_m=args.reach_radius)
    load_s = time.perf_counter() - t_start
    say(f"scene {building.name}: start {start}, robot radius {prepared.radii.robot_m} m ({prepared.radii.robot_from}), "
        f"reach {prepared.radii.reach_m} m ({prepared.radii.reach_from}), profile {args.profile}, "
        f"{mission.automaton.num_states} automaton states")

    def progress(it: Any) -> None:
        say(f"  (w1, w2) = ({it.w1:g}, {it.w2:g})  cost {it.cost_m:.4f} m  bound x{it.bound:g}  "
            f"{it.time_s:.3f} s  {sum(it.expansions):,} expansions")

    result = plan(prepared.problem, args.setup, time_limit_s=args.time_limit,
                  max_expansions=args.max_expansions, callback=progress)
    record.update(result_record(result))
    record.update(start=list(start), radii={"robot_m": prepared.radii.robot_m, "reach_m": prepared.radii.reach_m})
    record["timings"].update(load_s=load_s, wall_s=time.perf_counter() - t_start)
    if result.path is None:
        raise PlanningError(f"no path found within the budget ({result.status})", status=result.status)
    print(f"{result.status}: cost {result.cost_m:.4f} m over {len(result.path)} cells "
          f"(setup {result.setup}, {len(result.iterations)} iterations, search {result.search_s:.3f} s, "
          f"precompute {result.precompute_s:.3f} s)")
    if args.verify:
        from sgplan.planning.checker import check_path

        check = check_path(result.path, prepared.problem.grid, prepared.problem.labels, mission.automaton, args.profile)
        record["verified"] = check.valid
        if not check.valid:
            raise PlanningError("the path failed the independent check: " + "; ".join(check.problems))
        if abs(check.cost_m - result.cost_m) > 1e-6:
            raise PlanningError(f"the checker recomputes cost {check.cost_m:.6f} m, the planner said {result.cost_m:.6f} m")
        print(f"verified: the path is legal, collision-free and accepted; cost {check.cost_m:.4f} m")
    if args.draw:
        from sgplan.scene.draw import draw_building

        cells = [tuple(int(v) for v in row[:3]) for row in result.path]
        for png in draw_building(building, args.draw, grid=prepared.problem.grid, path=cells, stem="plan_floor"):
            say(f"wrote {png}")
    return 0


def _translate(args: argparse.Namespace, building: Building, backends: Backends) -> Mission:
    """The mission of ``--text``, saved under ``--save-mission`` when given."""
    from sgplan.llm.translation import mission_of, translate_to_folder
    from sgplan.logic import to_infix

    if args.save_mission:
        translation, mission = translate_to_folder(args.text, building, backends.translator, args.save_mission,
                                                   backends.record)
        say(f"wrote the mission folder {args.save_mission}")
    else:
        translation = backends.translator.translate(args.text, building)
        mission = mission_of(translation)
    say(f"formula: {to_infix(translation.formula)} ({mission.automaton.num_states} automaton states)")
    return mission


def _write_json(target: str | None, record: dict[str, Any]) -> None:
    if not target:
        return
    path = Path(target)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
    except OSError as error:
        raise MissionError(f"cannot write the JSON result: {error.strerror}", path) from None
