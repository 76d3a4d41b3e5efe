"""Files the LLM layer shares (run records, cache entries) get the usual mode of new files."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from sgplan.files import write_text_atomically
from sgplan.llm.records import RunRecord


@pytest.mark.parametrize(("umask", "mode"), [(0o022, 0o644), (0o077, 0o600)])
def test_atomic_writes_get_the_mode_of_new_files(tmp_path: Path, umask: int, mode: int) -> None:
    previous = os.umask(umask)
    try:
        record = RunRecord("test").save(tmp_path / "llm_record.json")
        write_text_atomically(tmp_path / "other.txt", "text\n")
    finally:
        os.umask(previous)
    for path in (record, tmp_path / "other.txt"):
        assert stat.S_IMODE(path.stat().st_mode) == mode
    assert sorted(p.name for p in tmp_path.iterdir()) == ["llm_record.json", "other.txt"]  # no temporary left
