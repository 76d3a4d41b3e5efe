"""Small file-system helpers shared by every writer of sgplan's outputs: atomic files, atomic folders.

Every output (plan results, mission folders, run records, caches, benchmark results) is written so that
a failure or a crash at any point leaves the earlier version whole or the new one complete.
"""

from __future__ import annotations

import contextlib
import ctypes
import fcntl
import os
import secrets
import shutil
from collections.abc import Callable, Iterator, Mapping
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


def write_file_atomically(path: Path, write: Callable[[Path], object]) -> None:
    """Have ``write(tmp_path)`` write a file (an image, an npz archive) beside ``path``, then rename it over
    ``path``: readers see the old file or the whole new one. The temporary name keeps ``path``'s suffix,
    for writers that choose the format by it. OSError propagates; callers add which file it was."""
    tmp_path = path.with_name(f".{path.stem[:24]}.{secrets.token_hex(8)}.tmp{path.suffix}")
    try:
        write(tmp_path)
        os.replace(tmp_path, path)
    finally:
        tmp_path.unlink(missing_ok=True)


@contextlib.contextmanager
def folder_lock(folder: Path) -> Iterator[None]:
    """Hold an exclusive advisory lock (``flock``) for rewriting ``folder``; waits for the current holder.

    The lock file is ``.<name>.lock`` beside the folder, not inside it, since :func:`rebuild_folder`
    swaps the folder itself. The lock is released when the block ends or the process dies.
    OSError (the parent folder cannot be written) propagates.
    """
    path = folder.parent / f".{folder.name}.lock"
    with open(path, "a+b") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


class FolderInUse(Exception):
    """Another process holds the folder (:func:`claim_folder`); ``holder_pid`` is its process id, if it
    could be read."""

    def __init__(self, folder: Path, holder_pid: int | None) -> None:
        super().__init__(f"{folder} is in use by process {holder_pid or 'unknown'}")
        self.folder = folder
        self.holder_pid = holder_pid


def claim_file(folder: Path) -> Path:
    """The lock file of :func:`claim_folder`: ``.<name>.writer.lock`` beside the folder (not inside it, where
    it would be one more file among the outputs), holding the pid of the folder's last writer."""
    folder = folder.resolve()
    return folder.parent / f".{folder.name}.writer.lock"


@contextlib.contextmanager
def claim_folder(folder: Path) -> Iterator[None]:
    """Hold ``folder`` (created if missing) for this process's writes for the length of the block, or
    refuse at once if another process holds it: several processes writing the same file names into one
    folder would silently overwrite each other's files.

    The claim is an exclusive ``flock`` on :func:`claim_file` beside the folder, which holds the holder's
    pid (for the refusal to name it). The kernel drops the lock when the block ends or the process dies,
    so a crashed holder never leaves the folder claimed; the file itself stays (removing it would let a
    waiting process lock a file no longer in the folder).

    Raises
    ------
    FolderInUse
        Another process holds the folder.
    OSError
        The folder cannot be made or written (callers add which option named it).
    """
    folder.mkdir(parents=True, exist_ok=True)
    fd = os.open(claim_file(folder), os.O_RDWR | os.O_CREAT, 0o666)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise FolderInUse(folder, _pid_in(fd)) from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        yield
    finally:
        os.close(fd)  # releases the lock


def _pid_in(fd: int) -> int | None:
    """The pid written in a claim file, or ``None`` (not written yet, or not a number)."""
    text = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
    return int(text) if text.isdigit() else None


def rebuild_folder(folder: Path, build: Callable[[Path], None], carry_over: Callable[[str], bool]) -> None:
    """Replace ``folder`` by a new version, whole: readers see the old folder or the new one, never a mix.

    The new version is made in a staging folder beside ``folder``: the entries of the old one for which
    ``carry_over(name)`` is true are copied in, then ``build(staging)`` writes the rest. Only then is the
    staging folder swapped with ``folder`` (one atomic ``renameat2(RENAME_EXCHANGE)`` where the system
    has it, else two renames), under :func:`folder_lock`, so concurrent rebuilds leave one of them whole.
    If anything fails before the swap, ``folder`` is untouched and the staging folder removed.
    """
    folder = folder.resolve() if folder.is_symlink() else folder
    with folder_lock(folder):
        staging = folder.parent / f".{folder.name}.{secrets.token_hex(6)}.new"
        staging.mkdir()
        try:
            if folder.is_dir():
                for entry in folder.iterdir():
                    if not carry_over(entry.name):
                        continue
                    if entry.is_dir() and not entry.is_symlink():
                        shutil.copytree(entry, staging / entry.name, symlinks=True)
                    else:
                        shutil.copy2(entry, staging / entry.name, follow_symlinks=False)
            build(staging)
            _fsync_folder(staging)
            if folder.exists():
                _swap(staging, folder)  # staging now holds the old version, removed below
            else:
                os.rename(staging, folder)
            _fsync_folder(folder.parent)
        finally:
            shutil.rmtree(staging, ignore_errors=True)


_RENAME_EXCHANGE = 2
_AT_FDCWD = -100


def _swap(a: Path, b: Path) -> None:
    """Exchange two folders atomically (Linux ``renameat2``); elsewhere move ``b`` aside, then ``a`` in."""
    libc = ctypes.CDLL(None, use_errno=True)
    renameat2 = getattr(libc, "renameat2", None)
    if renameat2 is not None:
        result = renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE)
        if result == 0:
            return
        errno = ctypes.get_errno()
        if errno not in (38, 22, 95):  # ENOSYS, EINVAL, EOPNOTSUPP: fall back below
            raise OSError(errno, os.strerror(errno), str(b))
    aside = b.with_name(f".{b.name}.{secrets.token_hex(6)}.old")
    os.rename(b, aside)
    os.rename(a, b)
    os.rename(aside, a)


def _fsync_folder(folder: Path) -> None:
    """Flush a folder's entries (new names, renames) to disk; a no-op where folders cannot be opened."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
