"""Time and peak memory of importing the two real scenes of ../shared/datasets/scene-examples.

Usage::

    .venv/bin/python benchmarks/import_scenes.py [--repeat N] [--resolution M]

Imports the Matterport3D house and the Hydra apartment (the latter only when spark-dsg is installed;
its label file names the apartment's three labels, chair / lamp / table) and writes each to sgplan's
format in a temporary folder. Reported per scene: the best import time over the repetitions (parse,
rasterise, assemble, start cells; the libraries already imported), the write time, and the process's
peak RSS (which includes the interpreter and the libraries, measured separately after the imports).
"""

from __future__ import annotations

import argparse
import resource
import sys
import tempfile
import time
from pathlib import Path

_T0 = time.perf_counter()
from sgplan.importers.assemble import Settings  # noqa: E402
from sgplan.importers.labelspace import read_label_map  # noqa: E402
from sgplan.importers.mp3d import import_house  # noqa: E402
from sgplan.scene.native import write_native_scene  # noqa: E402

_IMPORT_S = time.perf_counter() - _T0
EXAMPLES = Path(__file__).resolve().parents[1] / ".." / "shared" / "datasets" / "scene-examples"


def _peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--resolution", type=float, default=0.05)
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
