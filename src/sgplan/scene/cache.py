"""An on-disk cache of what sgplan derives from a scene folder: the loaded building and its occupancy grids.

Loading a Gibson scene parses its YAML and decodes its PNG maps, and its occupancy grid inflates every
obstacle; every CLI call and bench case paid both (benchmarks/results/comment_measurements.md). Like numba's
cache of compiled code, entries live in the user's cache folder and are found by a hash of everything they
were made from, so a stale entry is never used:

- a building entry is keyed by the scene's ``building.yaml`` (path and bytes) and the source code of the
  loader; it lists every file the loader read (maps, initial positions, radius file; an optional file
  that was absent is listed as absent) with the SHA-256 of its bytes, and is used only if all of them
  still hash the same;
- a grid entry is keyed by the building itself (a hash of its pickled bytes, so a building changed in
  memory, or made in code, gets its own entry), the robot radius and the source code of the grid builder.

A change of any input file or of sgplan's code therefore rebuilds the entry (and overwrites it). An
unreadable, truncated or foreign entry is ignored and rebuilt, never an error; errors of the scene itself
always come from the loader, which then runs as without the cache.

Where: ``$SGPLAN_CACHE_DIR``, else ``$XDG_CACHE_HOME/sgplan``, else ``~/.cache/sgplan``. Off with
``SGPLAN_NO_CACHE=1``. Entries are pickles (as numba's cache index is), so the folder is created private
(mode 0700) and not used if it is writable by other users. Writes are atomic (temporary file + rename);
the folder is kept under :data:`MAX_CACHE_BYTES` by deleting the least recently used entries.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import logging
import os
import pickle
import secrets
import stat
import sys
from collections.abc import Callable, Iterable
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from sgplan.scene.grid import OccupancyGrid
    from sgplan.scene.model import Building

log = logging.getLogger("sgplan")

DIR_ENV = "SGPLAN_CACHE_DIR"
"""Environment variable naming the cache folder."""
OFF_ENV = "SGPLAN_NO_CACHE"
"""Environment variable that turns the cache off when set to anything but ``""`` / ``0``."""
MAX_CACHE_BYTES = 1 << 30
"""Size the cache folder is kept under (least recently used entries are deleted on writes)."""
FORMAT = "sgplan-scene-cache-1"
"""Changes whenever the entries' layout changes, so older entries are never read."""
SUFFIX = ".pickle"

BUILDING_CODE = ("sgplan.scene.authors", "sgplan.scene.model", "sgplan.scene.fields", "sgplan.safeio",
                 "sgplan.limits")
"""Modules whose source decides what a building entry holds."""
GRID_CODE = ("sgplan.scene.grid", "sgplan.scene.footprint")
"""Modules whose source decides what a grid entry holds (besides the building)."""

T = TypeVar("T")

STATS: dict[str, int] = {"hits": 0, "misses": 0, "writes": 0}
"""Counts of this process (for tests and benchmarks)."""



def cache_dir() -> Path | None:
    """The cache folder, or ``None`` when the cache is off (``$SGPLAN_NO_CACHE``)."""
    if os.environ.get(OFF_ENV, "").strip() not in ("", "0"):
        return None
    configured = os.environ.get(DIR_ENV, "").strip()
    if configured:
        return Path(configured).expanduser()
    base = os.environ.get("XDG_CACHE_HOME", "").strip() or str(Path.home() / ".cache")
    return Path(base).expanduser() / "sgplan"


def load_authors_scene_cached(path: str | Path) -> Building:
    """The building of the authors' scene at ``path`` (as :func:`sgplan.scene.authors.load_authors_scene`),
    from the cache when its entry is still valid, else loaded and stored."""
    from sgplan.scene import authors

    folder = _usable_dir()
    try:
        scene_folder, yaml_path = authors.locate(path)
        yaml_path = yaml_path.resolve()
        key = _hash([FORMAT, _code(BUILDING_CODE), str(yaml_path).encode(), yaml_path.read_bytes()])
    except (OSError, authors.SceneError):  # the loader says what is wrong
        folder = None
    if folder is None:
        return authors.load_authors_scene(path)
    entry = _read(folder, "building", key)
    if entry is not None and _inputs_unchanged(entry["inputs"]):
        building: Building = entry["building"]
        # The entry is shared by every path to this scene: the source is the caller's, as the loader's.
        building.source = scene_folder
        return building
    building, inputs = authors.load_authors_scene_with_inputs(path)
    try:
        hashes = {str(p.resolve()): _file_hash(p) for p in inputs}
    except OSError:  # an input vanished or changed meanwhile: keep the building, skip the cache
        return building
    _write(folder, "building", key, {"inputs": hashes, "building": building})
    return building


def occupancy_grid_cached(
    building: Building, robot_radius_m: float, build: Callable[[Building, float], OccupancyGrid]
) -> OccupancyGrid:
    """``build(building, robot_radius_m)``, from the cache when a grid of this building (exactly as it is
    now, whatever its source) and radius was stored (hashing the building, :func:`content_hash`, costs
    far less than building its grid)."""
    folder = _usable_dir()
    source, building.source = building.source, None  # where it was read from does not change its grid
    try:
        content = content_hash(building)
    except (pickle.PicklingError, TypeError, AttributeError, ValueError):  # something unpicklable in it
        folder = None
    finally:
        building.source = source
    if folder is None:
        return build(building, robot_radius_m)
    key = _hash([FORMAT, _code(GRID_CODE), content, repr(float(robot_radius_m)).encode()])
    entry = _read(folder, "grid", key)
    if entry is not None:
        return entry["grid"]
    grid = build(building, robot_radius_m)
    _write(folder, "grid", key, {"grid": grid})
    return grid


def content_hash(obj: object) -> bytes:
    """SHA-256 of ``obj`` as pickled (protocol 5): equal for equal contents, whatever their source. The
    arrays' bytes are hashed where they lie instead of being copied into the pickle first (out-of-band
    buffers), and SHA-256 runs in hardware on most CPUs (faster here than blake2b over a full pickle;
    benchmarks/results/comment_measurements.md).

    Raises
    ------
    pickle.PicklingError, TypeError, AttributeError
        ``obj`` holds something unpicklable.
    """
    buffers: list[pickle.PickleBuffer] = []
    stream = pickle.dumps(obj, protocol=5, buffer_callback=buffers.append)  # None: every buffer out of band
    digest = hashlib.sha256(stream)
    for buffer in buffers:
        raw = buffer.raw()  # numpy puts only contiguous arrays out of band: a flat view, never a copy
        digest.update(raw.nbytes.to_bytes(8, "little"))
        digest.update(raw)
    return digest.digest()


# -- entries -------------------------------------------------------------------------------------------


def _usable_dir() -> Path | None:
    """The cache folder if it is on and safe to read pickles from (ours, not writable by others); made
    (mode 0700) if missing. ``None`` otherwise."""
    folder = cache_dir()
    if folder is None:
        return None
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
        info = folder.stat()
    except OSError as error:
        log.debug("scene cache off: cannot make %s: %s", folder, error)
        return None
    if info.st_mode & (stat.S_IWGRP | stat.S_IWOTH) or (hasattr(os, "getuid") and info.st_uid != os.getuid()):
        log.debug("scene cache off: %s is writable by others or not ours", folder)
        return None
    return folder


def _entry_path(folder: Path, kind: str, key: str) -> Path:
    return folder / f"{kind}-{key[:40]}{SUFFIX}"


def _read(folder: Path, kind: str, key: str) -> dict[str, Any] | None:
    """The entry stored under ``key``, or ``None`` (missing, unreadable, or not an entry of this key)."""
    path = _entry_path(folder, kind, key)
    try:
        with open(path, "rb") as stream:
            entry = pickle.load(stream)
        os.utime(path)  # recently used: pruned last
    except FileNotFoundError:
        entry = None
    except Exception as error:  # noqa: BLE001 - any broken entry (truncated, foreign, old classes): rebuild
        log.debug("scene cache: ignoring %s: %s", path, error)
        entry = None
    if not (isinstance(entry, dict) and entry.get("format") == FORMAT and entry.get("key") == key):
        STATS["misses"] += 1
        return None
    STATS["hits"] += 1
    return entry


def _write(folder: Path, kind: str, key: str, entry: dict[str, Any]) -> None:
    """Store ``entry`` atomically (a failure only costs the next run the rebuild), then prune."""
    path = _entry_path(folder, kind, key)
    tmp = path.with_name(f".{path.name}.{secrets.token_hex(6)}.tmp")
    try:
        with open(tmp, "wb") as stream:
            pickle.dump({"format": FORMAT, "key": key, **entry}, stream, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
        STATS["writes"] += 1
    except (OSError, pickle.PicklingError) as error:
        log.debug("scene cache: cannot write %s: %s", path, error)
        with contextlib.suppress(OSError):
            tmp.unlink()
        return
    _prune(folder)


def _prune(folder: Path, limit: int = MAX_CACHE_BYTES) -> None:
    """Delete the least recently used entries until the folder's entries fit in ``limit`` bytes."""
    try:
        entries = []
        for item in os.scandir(folder):
            if item.name.endswith(SUFFIX) and item.is_file(follow_symlinks=False):
                info = item.stat(follow_symlinks=False)
                entries.append((info.st_mtime, info.st_size, item.path))
    except OSError:
        return
    total = sum(size for _, size, _ in entries)
    for _, size, path in sorted(entries):
        if total <= limit:
            break
        with contextlib.suppress(OSError):
            os.unlink(path)
            total -= size


def _inputs_unchanged(inputs: dict[str, str | None]) -> bool:
    try:
        return all(_file_hash(Path(path)) == digest for path, digest in inputs.items())
    except OSError:
        return False


def _file_hash(path: Path) -> str | None:
    """SHA-256 of the file's bytes; ``None`` if there is no file (an optional input that is absent)."""
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except FileNotFoundError:
        return None


def _hash(parts: Iterable[bytes | str]) -> str:
    digest = hashlib.sha256()
    for part in parts:
        data = part.encode() if isinstance(part, str) else part
        digest.update(len(data).to_bytes(8, "little"))
        digest.update(data)
    return digest.hexdigest()


@cache
def _code(modules: tuple[str, ...]) -> str:
    """A hash of the source of ``modules`` and of the versions the pickles depend on."""
    import numpy

    from sgplan.version import __version__

    parts: list[bytes | str] = [__version__, sys.version, numpy.__version__]
    for name in modules:
        spec = importlib.util.find_spec(name)
        origin = spec.origin if spec is not None else None
        parts.append(Path(origin).read_bytes() if origin else name)
    return _hash(parts)
