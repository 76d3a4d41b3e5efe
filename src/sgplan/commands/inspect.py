"""``sgplan inspect SCENE``: print a scene's summary and optionally draw its floors."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys

from sgplan.commands.common import add_axes_argument, add_scene_arguments, load_scene_arg, robot_radius, say


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("inspect", help="summarise a scene (floors, rooms, objects, grid, portals)")
    add_scene_arguments(parser, positional=True)
    parser.add_argument("--robot-radius", type=robot_radius, default=None, metavar="M",
                        help="robot radius in metres for the free-cell counts (default: the scene's, else 0)")
    parser.add_argument("--draw", metavar="DIR", default=None,
                        help="write one PNG and one SVG per floor into DIR")
    add_axes_argument(parser)
    parser.add_argument("--no-objects", action="store_true", help="leave the object lists out")
    parser.add_argument(
        "--json", metavar="OUT", help="write the summary as JSON ('-': to stdout, instead of the text)"
    )
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from sgplan.result import write_text
    from sgplan.scene.cache import occupancy_grid_cached
    from sgplan.scene.grid import build_occupancy_grid
    from sgplan.scene.summary import summarize, summary_lines

    building = load_scene_arg(args.scene, args.data)
    has_maps = all(floor.has_maps for floor in building.floors)
    radius = args.robot_radius if args.robot_radius is not None else (building.robot_radius_m or 0.0)
    grid = occupancy_grid_cached(building, radius, build_occupancy_grid) if has_maps else None
    summary = summarize(building, grid)
    if args.json:
        text = json.dumps(dataclasses.asdict(summary), indent=1, allow_nan=False) + "\n"
        if args.json == "-":
            sys.stdout.write(text)
        else:
            say(f"wrote {write_text(args.json, text)}")
    if args.json != "-":
        print("\n".join(summary_lines(summary, objects=not args.no_objects)))
    if args.draw:
        from sgplan.scene.draw import draw_building  # matplotlib: only when drawing

        if not has_maps:
            say("no maps in this scene (raw .npz): nothing to draw")
            return 0
        for path in draw_building(building, args.draw, grid=grid, axes=args.axes):
            say(f"wrote {path}")
    return 0
