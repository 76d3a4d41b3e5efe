"""Small file-system helpers shared by the caches, run records and benchmark results."""

from __future__ import annotations

import os
import secrets
from pathlib import Path


def write_text_atomically(path: Path, text: str) -> None:
    """Write ``text`` (UTF-8, newlines untranslated) to ``path`` so readers see no file or the whole file.

    The text goes to a temporary file in the same folder, is flushed to disk, then renamed over ``path``
    (:func:`os.replace` is atomic on one file system). The file gets the mode of any new file, ``0o666``
    less the umask (``0o644`` with the usual umask 022). OSError propagates; callers add which file it was.
    """
    tmp_path = path.with_name(f".{path.name[:24]}.{secrets.token_hex(8)}.tmp")
    # Not tempfile.mkstemp: it creates 0600 files, and records and caches are meant to be shared.
    fd = os.open(tmp_path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as tmp:
            tmp.write(text)
            tmp.flush()
            os.fsync(tmp.fileno())
        os.replace(tmp_path, path)
    except BaseException:
        # Any failure (disk full, interrupt) before the rename: drop the partial temporary file.
        tmp_path.unlink(missing_ok=True)
        raise
