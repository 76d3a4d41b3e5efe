"""Small file-system helpers shared by the caches, run records and benchmark results."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def write_text_atomically(path: Path, text: str) -> None:
    """Write ``text`` (UTF-8, newlines untranslated) to ``path`` so readers see no file or the whole file.

    The text goes to a temporary file in the same folder, is flushed to disk, then renamed over ``path``
    (:func:`os.replace` is atomic on one file system). OSError propagates; callers add which file it was.
    """
    fd, tmp_name = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name[:24]}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as tmp:
            tmp.write(text)
            tmp.flush()
            os.fsync(tmp.fileno())
        os.replace(tmp_name, path)
    except BaseException:
        # Any failure (disk full, interrupt) before the rename: drop the partial temporary file.
        Path(tmp_name).unlink(missing_ok=True)
        raise
