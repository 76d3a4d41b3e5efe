"""Big, sparsely used arrays: zero-filled and committed page by page as they are touched.

``np.zeros`` of a large array maps fresh zero pages, so only the pages a search actually writes cost
memory. NumPy however asks Linux for transparent huge pages on large allocations, which makes every first
touch commit (and zero) 2 MB instead of 4 kB: on a sparse product-state array that inflates memory and
turns the first expansions of a search into milliseconds of page zeroing. :func:`sparse_zeros` allocates
without that request.
"""

from __future__ import annotations

import numpy as np

try:  # NumPy's switch for madvise(MADV_HUGEPAGE); absent on some versions/platforms.
    from numpy._core.multiarray import _set_madvise_hugepage  # type: ignore[attr-defined]
except ImportError:  # pragma: no cover - depends on the NumPy build
    try:
        from numpy.core.multiarray import _set_madvise_hugepage  # type: ignore[no-redef]
    except ImportError:
        _set_madvise_hugepage = None


def sparse_zeros(shape: int | tuple[int, ...], dtype: type | np.dtype) -> np.ndarray:
    """``np.zeros(shape, dtype)`` backed by ordinary (not huge) lazily committed pages."""
    if _set_madvise_hugepage is None:
        return np.zeros(shape, dtype=dtype)
    previous = _set_madvise_hugepage(False)
    try:
        return np.zeros(shape, dtype=dtype)
    finally:
        _set_madvise_hugepage(previous)
