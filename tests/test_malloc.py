"""sgplan.runtime.malloc: a freed multi-MB array leaves the resident set at once (in a fresh process each)."""

from __future__ import annotations

import platform
import subprocess
import sys

import pytest

from sgplan.runtime.malloc import return_freed_memory_promptly

# Frees a 16 MB array (which raises glibc's dynamic mmap threshold), then fills 6 MB arrays, each followed
# by a small one that stays (as a plan's longer-lived arrays do), frees the 6 MB ones and prints the MiB
# still resident from them.
_PROBE = """
import sys
import numpy as np
from sgplan.runtime.malloc import return_freed_memory_promptly
if sys.argv[1] == "fixed":
    assert return_freed_memory_promptly()
def rss():
    for line in open("/proc/self/status"):
        if line.startswith("VmRSS"):
            return int(line.split()[1]) / 1024
big = np.ones(2 << 20)
del big
before = rss()
parts, kept = [], []
for _ in range(4):
    parts.append(np.ones(3 << 18))
    kept.append(np.ones(1 << 14))
del parts
print(rss() - before)
"""


def _retained_mib(mode: str) -> float:
    done = subprocess.run([sys.executable, "-c", _PROBE, mode], capture_output=True, text=True, timeout=60,
                          check=True)
    return float(done.stdout)


@pytest.mark.skipif(platform.libc_ver()[0] != "glibc", reason="glibc's allocator only")
def test_freed_arrays_leave_the_resident_set() -> None:
    assert _retained_mib("default") > 12  # glibc's default keeps the 24 MB freed inside its heap
    assert _retained_mib("fixed") < 2


def test_other_c_libraries_are_left_alone() -> None:
    assert return_freed_memory_promptly() is (platform.libc_ver()[0] == "glibc")
