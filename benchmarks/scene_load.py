"""Time and peak memory of loading a Gibson scene with all its rasters, its grid and a label raster.

Issue 2 requires, for Benevolence on a 2-core machine: < 2 s and < 1 GB peak resident memory.

Usage::

    .venv/bin/python benchmarks/scene_load.py [SCENE_DIR] [--repeat N]

SCENE_DIR defaults to Benevolence under the Gibson data folder (see sgplan.datasets). Reported:
import time, then per repetition the load / grid / labels times, and the process's peak RSS (which
includes the interpreter and the imported libraries, measured separately as "after imports").
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from pathlib import Path

_T0 = time.perf_counter()
from sgplan.datasets import scene_dir
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import MAX_PROPOSITIONS, Proposition, label_raster

_IMPORT_S = time.perf_counter() - _T0


def _peak_rss_mb() -> float:
    # Linux reports ru_maxrss in KiB.
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", type=Path, help="scene folder (default: Benevolence)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    path = args.scene or scene_dir("Benevolence")
    rss_imports = _peak_rss_mb()
    print(f"scene {path}")
    print(f"imports {_IMPORT_S:.3f} s, peak RSS after imports {rss_imports:.0f} MB")
    best = float("inf")
    for i in range(args.repeat):
        t0 = time.perf_counter()
        building = load_authors_scene(path)
        t1 = time.perf_counter()
        grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
        t2 = time.perf_counter()
        # Every room, then objects, up to the 32 propositions a label raster holds.
        props = [Proposition("enter", r.uuid) for r in building.rooms()]
        props += [Proposition("reach", o.uuid) for o in building.objects()][: MAX_PROPOSITIONS - len(props)]
        labels = label_raster(building, props)
        t3 = time.perf_counter()
        total = t3 - t0
        best = min(best, total)
        print(
            f"run {i + 1}: load {t1 - t0:.3f} s, grid {t2 - t1:.3f} s (r = {grid.robot_radius_m} m), "
            f"labels {t3 - t2:.3f} s ({len(props)} propositions, {labels.nbytes / 2**20:.0f} MB), "
            f"total {total:.3f} s"
        )
    peak = _peak_rss_mb()
    print(f"best total {best:.3f} s; peak RSS {peak:.0f} MB ({peak - rss_imports:.0f} MB above imports)")
    ok = best < 2.0 and peak < 1024.0
    print("within budget (< 2 s, < 1 GB)" if ok else "OVER BUDGET (< 2 s, < 1 GB)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
