"""Which importer a source needs, and reading a source directly as a scene (``--scene map.yaml``).

Direct use works where nothing else is needed: a ``.house`` file; a ROS ``map.yaml`` with its rooms
file beside it (:data:`ROOMS_BESIDE`); a Hydra ``.json`` whose label file sits beside it
(:data:`LABELS_BESIDE`) or whose graph has no objects. Otherwise ``sgplan import`` names the extra file.
"""

from __future__ import annotations

from pathlib import Path

from sgplan.errors import SceneError
from sgplan.importers import DEFAULT_OPEN_GAP_M, KINDS, Kind
from sgplan.importers.assemble import ImportResult, Settings
from sgplan.importers.hydra import import_dsg, looks_like_dsg
from sgplan.importers.labelspace import read_label_map
from sgplan.importers.mp3d import import_house, is_house_file
from sgplan.importers.ros import import_ros_map, is_ros_map

ROOMS_BESIDE = ("{stem}_rooms.yaml", "rooms.yaml")
LABELS_BESIDE = ("{stem}_labels.yaml", "{stem}_labels.csv", "labels.yaml", "labels.csv")


def detect_kind(path: Path) -> Kind | None:
    """The importer for ``path``, or ``None`` if it is no importable source."""
    if is_house_file(path):
        return "mp3d"
    if looks_like_dsg(path):
        return "hydra"
    if is_ros_map(path):
        return "ros"
    return None


def _beside(path: Path, patterns: tuple[str, ...]) -> Path | None:
    for pattern in patterns:
        candidate = path.parent / pattern.format(stem=path.stem)
        if candidate.is_file():
            return candidate
    return None


def import_scene(
    kind: str,
    source: str | Path,
    settings: Settings | None = None,
    *,
    labels: str | Path | None = None,
    rooms: str | Path | None = None,
    open_gap_m: float = DEFAULT_OPEN_GAP_M,
) -> ImportResult:
    """Import ``source`` with the importer of ``kind``.

    ``labels`` (hydra) and ``rooms`` (ros) default to a file beside the source (module docstring).

    Raises
    ------
    SceneError
        for an unknown kind, a missing source, a ROS map without a rooms file, or whatever the
        importer rejects.
    """
    source = Path(source).expanduser()
    if not source.exists():
        raise SceneError("source does not exist", source)
    if kind == "mp3d":
        return import_house(source, settings, open_gap_m)
    if kind == "hydra":
        label_path = Path(labels) if labels is not None else _beside(source, LABELS_BESIDE)
        return import_dsg(source, read_label_map(label_path) if label_path is not None else None, settings)
    if kind == "ros":
        rooms_path = Path(rooms) if rooms is not None else _beside(source, ROOMS_BESIDE)
        if rooms_path is None:
            raise SceneError(
                f"a ROS map needs a rooms file (room polygons with names): pass --rooms FILE or put "
                f"{ROOMS_BESIDE[0].format(stem=source.stem)} beside the map",
                source,
            )
        return import_ros_map(source, rooms_path, settings)
    raise SceneError(f"unknown importer {kind!r}: use one of {', '.join(KINDS)}")
