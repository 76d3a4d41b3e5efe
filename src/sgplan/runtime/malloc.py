"""The C allocator's handling of freed memory, for processes that are sgplan's own.

glibc serves allocations from 128 kB up with their own ``mmap`` (returned to the system on ``free``), but
raises that threshold to the size of every such block freed (up to 32 MB) and its heap-trim threshold to
twice that. After the first few freed arrays of a plan (a cell graph's scratch, a distance field's
buffers), arrays of a few MB come from the heap, and once freed their pages stay resident unless they
happen to sit at its top, so the peak RSS of a large plan carries such freed memory (issue 12;
benchmarks/results/runtime.md). A fixed threshold turns that adjustment off, so every freed array of at
least :data:`MMAP_THRESHOLD_BYTES` is unmapped at once. Values and results are untouched; it costs a page
fault per 4 kB on each fresh array above the threshold (see :data:`MMAP_THRESHOLD_BYTES`).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import platform

MMAP_THRESHOLD_BYTES = 4 << 20
"""Allocations at least this large get their own mapping. 4 MiB (a distance field of 500,000 cells)
saves as much peak RSS as a lower threshold with about as many page faults as glibc's default: a lower
one faults every fresh multi-MB temporary in again (benchmarks/results/runtime.md)."""
_M_MMAP_THRESHOLD = -3  # mallopt parameter of glibc's malloc.h


def return_freed_memory_promptly() -> bool:
    """Fix glibc's mmap threshold at :data:`MMAP_THRESHOLD_BYTES` for this process; True if it was set
    (False on another C library, where nothing changes)."""
    if platform.libc_ver()[0] != "glibc":
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        return bool(libc.mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES))
    except (OSError, AttributeError):  # no loadable libc or no mallopt: leave the allocator as it is
        return False
