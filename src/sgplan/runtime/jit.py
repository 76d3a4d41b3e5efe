"""Numba housekeeping for the planner's kernels.

- Whether they are compiled and cached yet, so a front end can say why the first run on a machine is
  silent for a while (numba compiles the kernels once and caches them on disk). Detection reads numba's
  on-disk cache index for every cached kernel of the planner; it uses numba internals, so any surprise
  from them means "unknown" and no notice, never an error.
- :func:`skip_blas_probe`, for sgplan's own processes only: numba's first kernel load does not import
  scipy.linalg to find out whether a BLAS exists (the kernels use none). If numba's internals differ,
  the hook does nothing and numba loads the normal way.
"""

from __future__ import annotations

import contextlib
import importlib.machinery
import logging
import os
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from importlib.abc import Loader
    from importlib.machinery import ModuleSpec
    from types import ModuleType

log = logging.getLogger("sgplan")

NOTICE = ("compiling the planner's numba kernels (first run on this machine or after an update: about 15 s, "
          "once; they are cached for later runs)")


def kernels_cached() -> bool | None:
    """True if the planner's numba kernels have valid on-disk cache entries, False if some kernel will be
    compiled on first use (no entries at all, or stale ones), ``None`` if this cannot be told."""
    try:
        from numba.core.registry import CPUDispatcher

        from sgplan.outputs import _segments
        from sgplan.planning import _dijkstra, _heap, _search
        from sgplan.scene import _sight

        kernels = [
            value for module in (_heap, _dijkstra, _search, _segments, _sight)
            for value in vars(module).values()
            if isinstance(value, CPUDispatcher) and getattr(value, "_cache", None) is not None
        ]
        files = [getattr(kernel, "_cache")._cache_file for kernel in kernels]  # noqa: B009 - private in numba
        # Helpers only ever inlined into other kernels have no index file; the entry points have one once
        # compiled, and an index whose source stamp is stale loads as empty (the kernel will be recompiled).
        indexed = [f for f in files if os.path.exists(f._index_path)]
        return bool(indexed) and all(bool(f._load_index()) for f in indexed)
    except Exception:  # noqa: BLE001 - numba internals changed: say nothing rather than fail a run
        return None


_seen_cached = False
"""Whether :func:`announce_compile` found the kernels cached, or said they are not, in this process
already: either way they are compiled and cached from then on (a process does not change its own
sources), so later plans skip reading numba's index files and say nothing."""


def announce_compile() -> bool:
    """Log :data:`NOTICE` (level INFO) when the kernels are known not to be cached; returns whether it did.
    Once they were found cached, or the notice was said, later calls in this process return False at once
    (the kernels compile once per process)."""
    global _seen_cached
    if _seen_cached:
        return False
    cached = kernels_cached()
    _seen_cached = cached is not None
    if cached is False:
        log.info(NOTICE)
        return True
    return False


# Numba's registry of array functions (numba.np.arraymath, imported the first time a kernel is compiled or
# loaded from the cache) probes once whether a BLAS exists by importing scipy.linalg.cython_blas, which
# imports all of scipy.linalg (time and memory per process: benchmarks/results/runtime.md). sgplan's kernels
# call no BLAS (no np.dot, @, np.linalg, np.correlate or np.convolve), so a process that runs only sgplan's
# kernels can let the probe fail fast. The answer only decides how numba compiles np.correlate / np.convolve
# later (a plain loop instead of BLAS); np.dot and np.linalg still import scipy when they are compiled. That
# is a choice for the process's owner: only sgplan's own entry points (the CLI, the bench worker) make it,
# never ``import sgplan`` inside a user's program.
_ARRAYMATH = "numba.np.arraymath"
_BLAS = "scipy.linalg.cython_blas"


class _SkipBlasProbe:
    """One-shot import hook (a meta path finder and loader): runs numba's arraymath module with
    ``sys.modules[_BLAS] = None`` (an import of it then raises ImportError at once, without importing
    scipy.linalg), then restores sys.modules. (Not derived from importlib.abc: importing that loads
    importlib.resources, a cost on every start.)"""

    def __init__(self) -> None:
        self._inner: Loader | None = None

    def find_spec(self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
                  ) -> ModuleSpec | None:
        if fullname != _ARRAYMATH:
            return None
        with contextlib.suppress(ValueError):  # one shot: later imports go the normal way
            sys.meta_path.remove(self)
        try:
            spec = importlib.machinery.PathFinder.find_spec(fullname, path, target)
        except Exception:  # noqa: BLE001 - numba's layout changed: let the normal finders handle it
            return None
        if spec is None or spec.loader is None or not hasattr(spec.loader, "exec_module"):
            return None
        self._inner, spec.loader = spec.loader, self  # type: ignore[assignment]  # a Loader by duck typing
        return spec

    def create_module(self, spec: ModuleSpec) -> ModuleType | None:
        assert self._inner is not None
        return self._inner.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        assert self._inner is not None
        # The module keeps its real loader (as if this hook had never been there).
        module.__loader__ = self._inner
        if module.__spec__ is not None:
            module.__spec__.loader = self._inner
        if _BLAS in sys.modules:  # scipy.linalg is loaded already: the probe costs nothing
            self._inner.exec_module(module)
            return
        sys.modules[_BLAS] = None  # type: ignore[assignment]  # None: an import fails at once
        try:
            self._inner.exec_module(module)
        finally:
            if _BLAS in sys.modules and sys.modules[_BLAS] is None:
                del sys.modules[_BLAS]


def skip_blas_probe() -> bool:
    """In a process that only runs sgplan's kernels (the CLI, a bench worker): make numba's one-time BLAS
    probe fail fast instead of importing scipy.linalg (see the comment above). Call it before numba's
    registries load; returns whether the hook was installed (False: they are loaded already, or the hook
    is in place). Never call it from library code: it changes how numba compiles the user's own kernels."""
    if _ARRAYMATH in sys.modules or any(isinstance(f, _SkipBlasProbe) for f in sys.meta_path):
        return False
    sys.meta_path.insert(0, _SkipBlasProbe())
    return True
