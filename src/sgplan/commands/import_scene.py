"""``sgplan import KIND SOURCE --out DIR``: convert another tool's scene graph to sgplan's format."""

from __future__ import annotations

import argparse

from sgplan.commands.common import positive_number, reach_radius, robot_radius, say
from sgplan.english import count


def register(sub: argparse._SubParsersAction) -> None:
    from sgplan.importers import DEFAULT_OPEN_GAP_M, KINDS

    parser = sub.add_parser(
        "import", help="import a Hydra / Matterport3D / ROS map scene into sgplan's format",
        description="Import a scene made by another tool into a folder sgplan plans on (scene.json and "
        "rasters.npz: floors, rooms, objects, occupancy), saying what was left out and why. Exit codes: 0 "
        "imported, 2 an error, 70 a bug.",
    )
    parser.add_argument(
        "kind",
        choices=KINDS,
        metavar="KIND",
        help="hydra (spark-dsg .json), mp3d (Matterport3D .house) or ros (map_server map.yaml)",
    )
    parser.add_argument("source", metavar="SOURCE", help="the file to import")
    parser.add_argument(
        "--out", required=True, metavar="SCENE_DIR", help="folder to write scene.json + rasters.npz into"
    )
    parser.add_argument(
        "--resolution",
        type=positive_number,
        default=0.05,
        metavar="M",
        help="cell size in metres (default 0.05; a ROS map keeps its own)",
    )
    parser.add_argument(
        "--labels",
        metavar="FILE",
        help="hydra: names of the objects' integer labels (Hydra label-space yaml, YAML or CSV id -> name)",
    )
    parser.add_argument(
        "--rooms", metavar="FILE", help="ros: the rooms file (room polygons with names, objects)"
    )
    parser.add_argument(
        "--robot-radius",
        type=robot_radius,
        default=0.1,
        metavar="M",
        help="the scene's robot radius, used for start cells and as the planning default (0.1)",
    )
    parser.add_argument(
        "--reach-radius",
        type=reach_radius,
        default=0.5,
        metavar="M",
        help="the scene's default object reach radius (0.5)",
    )
    parser.add_argument(
        "--open-gap",
        type=positive_number,
        default=DEFAULT_OPEN_GAP_M,
        metavar="M",
        help="mp3d: floor polygons closer than this share an open boundary, not a wall "
        f"({DEFAULT_OPEN_GAP_M})",
    )
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from sgplan.importers.assemble import Settings
    from sgplan.importers.detect import import_scene
    from sgplan.scene.native import write_native_scene

    settings = Settings(
        resolution_m=args.resolution, robot_radius_m=args.robot_radius, reach_radius_m=args.reach_radius
    )
    result = import_scene(
        args.kind, args.source, settings, labels=args.labels, rooms=args.rooms, open_gap_m=args.open_gap
    )
    for note in result.notes:
        say(f"note: {note}")
    building = result.building
    folder = write_native_scene(building, args.out)
    rooms = sum(1 for _ in building.rooms())
    objects = sum(1 for _ in building.objects())
    rows, cols = building.grid_shape
    print(
        f"imported {building.name}: {count(building.num_floors, 'floor')}, {count(rooms, 'room')}, "
        f"{count(objects, 'object')}, {rows} x {cols} cells of {building.resolution_m[0]:g} m, "
        f"{count(len(building.initial_cells), 'start cell')} -> {folder}"
    )
    return 0
