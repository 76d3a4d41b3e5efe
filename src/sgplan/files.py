"""Small file-system helpers shared by the caches, run records and benchmark results."""

from __future__ import annotations

import os
import secrets
from collections.abc import Mapping
from pathlib import Path


def write_text_atomically(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` so readers see no file, the old file or the whole new one; see
    :func:`write_texts_atomically`."""
    write_texts_atomically({path: text})


def write_texts_atomically(texts: Mapping[Path, str]) -> None:
    """Write each text (UTF-8, newlines untranslated) to its path so readers see the old file or the
    whole new one, and, for several files, all old ones unless every new one was written in full.

    Each text goes to a temporary file in its path's folder and is flushed to disk; only when all are
    written are they renamed over their paths (:func:`os.replace` is atomic on one file system). A file
    gets the mode of any new file, ``0o666`` less the umask (``0o644`` with the usual umask 022).
    OSError propagates; callers add which file it was.
    """
    written: list[tuple[Path, Path]] = []
    try:
        for path, text in texts.items():
            tmp_path = path.with_name(f".{path.name[:24]}.{secrets.token_hex(8)}.tmp")
            # Not tempfile.mkstemp: it creates 0600 files, and records and caches are meant to be shared.
            fd = os.open(tmp_path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
            written.append((tmp_path, path))
            with os.fdopen(fd, "w", encoding="utf-8", newline="") as tmp:
                tmp.write(text)
                tmp.flush()
                os.fsync(tmp.fileno())
        for tmp_path, path in written:
            os.replace(tmp_path, path)
    except BaseException:
        # Any failure (disk full, interrupt) before the renames: drop the temporary files.
        for tmp_path, _ in written:
            tmp_path.unlink(missing_ok=True)
        raise
