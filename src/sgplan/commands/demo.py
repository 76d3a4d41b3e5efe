"""``sgplan demo``: the embedded demo building, summarised and drawn (no data, no network needed)."""

from __future__ import annotations

import argparse

from sgplan.commands.common import say


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("demo", help="run the demo on the embedded demo building (offline)")
    parser.add_argument("--out", metavar="DIR", default="out/demo", help="where drawings go (default: out/demo)")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from sgplan.scene.demo import demo_building
    from sgplan.scene.draw import draw_building
    from sgplan.scene.grid import build_occupancy_grid
    from sgplan.scene.summary import summarize, summary_lines

    building = demo_building()
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    print("\n".join(summary_lines(summarize(building, grid))))
    for path in draw_building(building, args.out, grid=grid):
        say(f"wrote {path}")
    return 0
