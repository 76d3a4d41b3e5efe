"""Where one ``sgplan plan`` spends its wall time and memory: seconds and RSS (MiB) at the entry and exit
of each part, in one process (the CLI's own code path; run it twice for a warm numba and scene cache).

Each listed function is wrapped to record ``time.perf_counter()`` and ``VmRSS`` / ``VmHWM`` (peak) of
``/proc/self/status`` when it starts and ends; the table prints them in order with the seconds since the
previous mark. Numba's cached kernels are listed too (seconds to load each, RSS after), since the first
load also initialises numba's compiler (~0.1 s, ~45 MB). Like the console script, it sets the process up
with :func:`sgplan.runtime.process.prepare_own_process` (no BLAS probe, fewer garbage-collector passes);
``--library-process`` leaves it as a program importing sgplan would have it.

    .venv/bin/python benchmarks/plan_parts.py plan --scene Benevolence --setup 'A*' --profile authors \\
        --mission-dir ../shared/datasets/gibson-3dsg/Benevolence/missions/4 --json /tmp/p.json
"""

from __future__ import annotations

import functools
import importlib
import sys
import time
from collections.abc import Callable
from typing import Any

T0 = time.perf_counter()
MARKS: list[tuple[str, float, int, int]] = []
PARTS = (
    ("sgplan.commands.plan", "load_scene_arg"), ("sgplan", "load_mission"),
    ("sgplan.commands.plan", "check_folder_fits"), ("sgplan.commands.plan", "say_back"),
    ("sgplan.api", "Session.grid"), ("sgplan.api", "Session.labels"), ("sgplan.api", "make_problem"),
    ("sgplan.api", "_check_in_scene"), ("sgplan.planning.amra", "plan"),
    ("sgplan.planning.domain", "build_domain"), ("sgplan.planning.domain", "build_cell_graph"),
    ("sgplan.planning.domain", "build_ltl_heuristic"), ("sgplan.planning.domain", "_action_tables"),
    ("sgplan.planning.amra", "_warm_up"), ("sgplan.api", "_explanation"), ("sgplan.api", "_add_outputs"),
    ("sgplan.commands.plan", "_write_json"),
)


def _memory_mib() -> tuple[int, int]:
    """(VmRSS, VmHWM) of this process, MiB."""
    found = {}
    with open("/proc/self/status") as status:
        for line in status:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                found[key] = int(value.split()[0]) // 1024
    return found["VmRSS"], found["VmHWM"]


def mark(name: str) -> None:
    MARKS.append((name, time.perf_counter() - T0, *_memory_mib()))


def _wrap(module_name: str, attr: str) -> None:
    module = importlib.import_module(module_name)
    owner_name, _, name = attr.rpartition(".")
    owner = getattr(module, owner_name) if owner_name else module
    inner: Callable[..., Any] = getattr(owner, name)

    @functools.wraps(inner)
    def timed(*args: Any, **kwargs: Any) -> Any:
        mark(f"> {attr}")
        try:
            return inner(*args, **kwargs)
        finally:
            mark(f"< {attr}")

    setattr(owner, name, timed)


def _watch_kernel_loads() -> None:
    from numba.core import caching

    load = caching.FunctionCache.load_overload

    def timed(self: Any, sig: Any, target_context: Any) -> Any:
        started = time.perf_counter()
        try:
            return load(self, sig, target_context)
        finally:
            mark(f"  numba cache load {self._py_func.__qualname__} ({time.perf_counter() - started:.3f} s)")

    caching.FunctionCache.load_overload = timed  # type: ignore[method-assign]


def main() -> int:
    mark("interpreter up")
    import sgplan.cli
    from sgplan.runtime.process import prepare_own_process

    argv = sys.argv[1:]
    if "--library-process" in argv:
        argv.remove("--library-process")
    else:
        prepare_own_process()  # as sgplan.cli.main does in the console script

    mark("sgplan.cli imported")
    for module_name, attr in PARTS:
        _wrap(module_name, attr)
    _watch_kernel_loads()
    mark("the parts' modules imported (numba, the planner: their import time is above, not below)")
    code = sgplan.cli._run(argv)
    mark("done")
    previous = 0.0
    print(f"{'s':>7} {'+s':>7} {'RSS':>5} {'peak':>5}  part (exit code {code})", file=sys.stderr)
    for name, at, rss, peak in MARKS:
        print(f"{at:7.3f} {at - previous:7.3f} {rss:5d} {peak:5d}  {name}", file=sys.stderr)
        previous = at
    return code


if __name__ == "__main__":
    sys.exit(main())
