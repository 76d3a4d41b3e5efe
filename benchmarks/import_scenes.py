"""Time and peak memory of importing the two real scenes of ../shared/datasets/scene-examples.

Usage::

    .venv/bin/python benchmarks/import_scenes.py [--repeat N] [--resolution M] [--big N]

Imports the Matterport3D house and the Hydra apartment (the latter only when spark-dsg is installed;
its label file names the apartment's three labels, chair / lamp / table) and writes each to sgplan's
format in a temporary folder. Reported per scene: the best import time over the repetitions (parse,
rasterise, assemble, start cells; the libraries already imported), the write time, and the process's
peak RSS (which includes the interpreter and the libraries, measured separately after the imports).

``--big N`` also imports a generated house of N x N rooms (4 m square, 0.2 m walls, a door to each
neighbour, 10 pieces of furniture per room): how the importer scales with rooms, objects and grid size.
"""

from __future__ import annotations

import argparse
import resource
import sys
import tempfile
import time
from pathlib import Path

_T0 = time.perf_counter()
from sgplan.importers.assemble import Settings
from sgplan.importers.labelspace import read_label_map
from sgplan.importers.mp3d import import_house
from sgplan.scene.native import write_native_scene

_IMPORT_S = time.perf_counter() - _T0
EXAMPLES = Path(__file__).resolve().parents[1] / ".." / "shared" / "datasets" / "scene-examples"


def _peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB


def big_house(n: int, path: Path) -> Path:
    """A Matterport3D house of ``n`` x ``n`` bedrooms, doors between neighbours, 10 objects in each."""
    size, wall = 4.0, 0.2
    pitch = size + wall
    records, vertices, objects = [], [], []
    for k in range(n * n):
        x0, y0 = (k // n) * pitch, (k % n) * pitch
        records.append(
            f"R {k} 0 0 0 b {x0 + 2} {y0 + 2} 0  {x0} {y0} 0 {x0 + size} {y0 + size} 2.5  2.5 0 0 0 0"
        )
        records.append(
            f"S {k} {k} 0 F {x0 + 2} {y0 + 2} 0  0 0 1  {x0} {y0} 0 {x0 + size} {y0 + size} 0  0 0 0 0 0"
        )
        for x, y in ((x0, y0), (x0 + size, y0), (x0 + size, y0 + size), (x0, y0 + size)):
            vertices.append(f"V {len(vertices)} {k} F {x} {y} 0  0 0 1  0 0 0")
        for j in range(10):  # furniture along the walls
            cx, cy = x0 + 0.4 + 0.35 * j, y0 + 0.3
            objects.append(
                f"O {len(objects)} {k} 1 {cx} {cy} 0.4  1 0 0  0 1 0  0.15 0.2 0.4  0 0 0 0 0 0 0 0"
            )
        if k // n + 1 < n:  # door to the room below (along x)
            objects.append(
                f"O {len(objects)} {k} 0 {x0 + size + wall / 2} {y0 + 2} 1  0 0 1  0 1 0  1 0.45 0.05  0 0 0 "
                "0 0 0 0 0"
            )
        if k % n + 1 < n:  # door to the room on the right (along y)
            objects.append(
                f"O {len(objects)} {k} 0 {x0 + 2} {y0 + size + wall / 2} 1  0 0 1  1 0 0  1 0.45 0.05  0 0 0 "
                "0 0 0 0 0"
            )
    span = n * pitch
    lines = [
        "ASCII 1.1",
        f"H - - 0 0 {len(vertices)} {n * n} 0 {len(objects)} 2 {n * n} 0 1 0 0 0 0 0 0 0 0 {span} {span} 2.5 "
        "0 0 0 0 0",
        f"L 0 {n * n} - 0 0 0  0 0 0 {span} {span} 2.5 0 0 0 0 0",
        *records,
        *vertices,
        "C 0 1 door 4 door 0 0 0 0 0",
        "C 1 2 chair 3 chair 0 0 0 0 0",
        *objects,
    ]
    path.write_text("\n".join(lines) + "\n")
    return path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--resolution", type=float, default=0.05)
    parser.add_argument("--big", type=int, default=0, metavar="N", help="also a generated N x N house")
    args = parser.parse_args(argv)
    settings = Settings(resolution_m=args.resolution)
    print(f"imports {_IMPORT_S:.3f} s, peak RSS after imports {_peak_rss_mb():.0f} MB")
    jobs = [("mp3d", lambda: import_house(EXAMPLES / "example_mp3d_scene.house", settings))]
    try:
        from sgplan.importers.hydra import import_dsg

        with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as handle:
            handle.write("5: chair\n11: lamp\n16: table\n")
        labels = read_label_map(handle.name)
        import spark_dsg  # noqa: F401 - only to know it is there

        jobs.append(("hydra", lambda: import_dsg(EXAMPLES / "apartment_dsg.json", labels, settings)))
    except ImportError:
        print("spark-dsg is not installed: the Hydra apartment is skipped")
    if args.big:
        big = big_house(args.big, Path(tempfile.mkdtemp()) / "big.house")
        jobs.append((f"mp3d {args.big}x{args.big} rooms", lambda: import_house(big, settings)))
    for kind, job in jobs:
        best = float("inf")
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            result = job()
            best = min(best, time.perf_counter() - t0)
        with tempfile.TemporaryDirectory() as folder:
            t0 = time.perf_counter()
            write_native_scene(result.building, folder)
            write_s = time.perf_counter() - t0
        rows, cols = result.building.grid_shape
        print(
            f"{kind}: import {best:.3f} s (best of {args.repeat}), write {write_s:.3f} s, "
            f"{rows} x {cols} cells, peak RSS so far {_peak_rss_mb():.0f} MB"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
