"""The benchmarks' best reference: a compiled, blind, exact Dijkstra over the product graph.

:func:`solve` runs ``product_dijkstra.c`` (beside this file) on a :class:`~sgplan.planning.PlanningProblem`'s
raw inputs -- occupancy raster, label raster, automaton table, stairs links, start and profile -- so it is
independent of sgplan.planning's cell graph, heuristics and search. The C file is compiled on first use with
the machine's C compiler (``$CC``, else ``cc`` / ``gcc`` / ``clang``) into a cache directory
(``$SGPLAN_BENCH_CACHE`` or ``~/.cache/sgplan-bench``) and loaded with ctypes.

    from benchmarks.dijkstra_reference.reference import solve
    ref = solve(problem)   # {"cost": m, "search_s": s, "setup_s": s, "pops": n, ...}
"""

from __future__ import annotations

import ctypes
import hashlib
import os
import shutil
import subprocess
from functools import lru_cache
from pathlib import Path

import numpy as np

SOURCE = Path(__file__).with_name("product_dijkstra.c")


class NoCompilerError(RuntimeError):
    """No C compiler was found: the reference cannot be built on this machine."""


def find_compiler() -> str:
    """Path of the C compiler to use; :class:`NoCompilerError` (saying what to install) if none exists."""
    for name in (os.environ.get("CC"), "cc", "gcc", "clang"):
        if name and shutil.which(name):
            return str(shutil.which(name))
    raise NoCompilerError(
        "no C compiler found ($CC, cc, gcc, clang): the compiled Dijkstra reference cannot be built; "
        "install one (e.g. `apt-get install gcc`) or set CC"
    )


@lru_cache(maxsize=1)
def library() -> ctypes.CDLL:
    """The compiled reference (built once per source version, then reused from the cache directory)."""
    source = SOURCE.read_bytes()
    digest = hashlib.sha256(source).hexdigest()[:16]
    cache = Path(os.environ.get("SGPLAN_BENCH_CACHE", Path.home() / ".cache" / "sgplan-bench"))
    target = cache / f"product_dijkstra-{digest}.so"
    if not target.exists():
        cache.mkdir(parents=True, exist_ok=True)
        partial = target.with_suffix(f".{os.getpid()}.tmp")
        cmd = [
            find_compiler(),
            "-O3",
            "-march=native",
            "-shared",
            "-fPIC",
            "-o",
            str(partial),
            str(SOURCE),
            "-lm",
        ]
        built = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if built.returncode != 0:
            raise RuntimeError(f"compiling {SOURCE} failed ({' '.join(cmd)}):\n{built.stderr}")
        partial.replace(target)
    lib = ctypes.CDLL(str(target))
    ptr = ctypes.c_void_p
    i32, i64, f64 = ctypes.c_int32, ctypes.c_int64, ctypes.c_double
    lib.product_dijkstra.argtypes = [
        i32, i32, i32, ptr, ptr, i32, i64, ptr, ptr, i32, ptr, ptr, f64, f64, i32, i32, i32, i32, ptr,
    ]
    lib.product_dijkstra.restype = ctypes.c_int
    return lib


def solve(problem) -> dict:
    """Optimal cost (metres, ``inf`` without a path) of ``problem`` by blind product-graph Dijkstra.

    Returns ``cost``, ``search_s`` (the Dijkstra loop only), ``setup_s`` (indexing the raster, the
    stairs and the live automaton states), ``pops`` (states settled), ``pushes``, ``touched`` (distinct
    product states reached), ``goal`` = (floor, row, col, q) or None. Same semantics as the planner:
    under profile ``ltlf`` the start cell's label is read, under ``authors`` it is not.
    """
    grid, automaton = problem.grid, problem.automaton
    floors, rows, cols = grid.shape
    traversable = np.ascontiguousarray(grid.traversable, dtype=np.uint8)
    labels = np.ascontiguousarray(problem.labels, dtype=np.int64)
    table = np.ascontiguousarray(automaton.table, dtype=np.int32)
    accepting = np.ascontiguousarray(automaton.accepting, dtype=np.uint8)
    row, col, floor = problem.start
    q_start = (
        int(table[automaton.initial, labels[floor, row, col]])
        if problem.profile == "ltlf"
        else automaton.initial
    )
    stairs = np.array(
        [(s.lower_floor, *s.lower_cell, s.upper_floor, *s.upper_cell) for s in grid.stairs], dtype=np.int32
    ).reshape(-1, 6)
    stairs_cost = np.array([s.cost_m for s in grid.stairs], dtype=np.float64)
    res_x, res_y = grid.resolution_m
    out = np.zeros(8, dtype=np.float64)

    def p(a: np.ndarray) -> int:
        return a.ctypes.data

    code = library().product_dijkstra(
        floors,
        rows,
        cols,
        p(traversable),
        p(labels),
        table.shape[0],
        table.shape[1],
        p(table),
        p(accepting),
        len(stairs_cost),
        p(stairs),
        p(stairs_cost),
        float(res_x),
        float(res_y),
        floor,
        row,
        col,
        int(q_start),
        p(out),
    )
    if code != 0:
        raise MemoryError("the reference Dijkstra ran out of memory")
    goal = None
    if out[6] >= 0:
        f, rest = divmod(int(out[6]), rows * cols)
        goal = (f, *divmod(rest, cols), int(out[7]))
    return {
        "cost": float(out[0]), "search_s": float(out[1]), "setup_s": float(out[2]), "pops": int(out[3]),
        "pushes": int(out[4]), "touched": int(out[5]), "goal": goal,
    }
