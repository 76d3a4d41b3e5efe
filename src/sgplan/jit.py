"""Whether the planner's numba kernels are compiled and cached yet, so a front end can say why the first
run on a machine is silent for ~15 s (numba compiles the kernels once and caches them on disk).

Detection reads numba's on-disk cache index for every cached kernel of the planner; it uses numba
internals, so any surprise from them means "unknown" and no notice, never an error.
"""

from __future__ import annotations

import logging
import os

log = logging.getLogger("sgplan")

NOTICE = ("compiling the planner's numba kernels (first run on this machine or after an update: about 15 s, "
          "once; they are cached for later runs)")


def kernels_cached() -> bool | None:
    """True if the planner's numba kernels have valid on-disk cache entries, False if some kernel will be
    compiled on first use (no entries at all, or stale ones), ``None`` if this cannot be told."""
    try:
        from numba.core.registry import CPUDispatcher

        from sgplan import heap
        from sgplan.planning import _dijkstra, _search

        kernels = [
            value for module in (heap, _dijkstra, _search) for value in vars(module).values()
            if isinstance(value, CPUDispatcher) and getattr(value, "_cache", None) is not None
        ]
        files = [getattr(kernel, "_cache")._cache_file for kernel in kernels]  # noqa: B009 - private in numba
        # Helpers only ever inlined into other kernels have no index file; the entry points have one once
        # compiled, and an index whose source stamp is stale loads as empty (the kernel will be recompiled).
        indexed = [f for f in files if os.path.exists(f._index_path)]
        return bool(indexed) and all(bool(f._load_index()) for f in indexed)
    except Exception:  # noqa: BLE001 - numba internals changed: say nothing rather than fail a run
        return None


def announce_compile() -> bool:
    """Log :data:`NOTICE` (level INFO) when the kernels are known not to be cached; returns whether it did."""
    if kernels_cached() is False:
        log.info(NOTICE)
        return True
    return False
