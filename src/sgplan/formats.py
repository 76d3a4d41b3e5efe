"""Format dispatch: which reader reads a scene path, :func:`load_scene`.

It sits above both :mod:`sgplan.scene` (sgplan's own formats and the authors') and :mod:`sgplan.importers`
(other tools' formats, which build on :mod:`sgplan.scene`), so neither of them imports the other's side.
"""

from __future__ import annotations

from pathlib import Path

from sgplan.errors import SceneError
from sgplan.scene.authors import is_authors_scene
from sgplan.scene.cache import load_authors_scene_cached
from sgplan.scene.gibson_npz import is_gibson_npz, load_gibson_npz
from sgplan.scene.model import Building
from sgplan.scene.native import is_native_scene, read_native_scene


def load_scene(path: str | Path) -> Building:
    """Load the scene at ``path``, whichever format it is in.

    - a folder with ``building.yaml`` (or that file): the authors' scene, with rasters (through the
      on-disk cache of :mod:`sgplan.scene.cache`);
    - a folder with ``scene.json`` (or a ``.json`` file): sgplan's native format;
    - a ``.npz`` file: a raw 3D Scene Graph (graph only, ``Floor.has_maps`` False);
    - a source of another tool, imported on the fly (:mod:`sgplan.importers.detect`): a Matterport3D
      ``.house`` file, a ROS ``map.yaml`` with its rooms file beside it, a Hydra scene-graph ``.json``
      with its label file beside it.

    Raises
    ------
    SceneError
        The path does not exist or is none of these, or the loader of its format rejects it.
    """
    path = Path(path).expanduser()
    try:
        if not path.exists():
            raise SceneError("scene path does not exist", path)
        # Telling the formats apart looks into the folder: an unreadable one fails here.
        kind = "authors" if is_authors_scene(path) else "native" if is_native_scene(path) else (
            "npz" if is_gibson_npz(path) else None)
    except OSError as error:
        raise SceneError(f"cannot read the scene: {error.strerror or error}", path) from None
    if kind == "authors":
        return load_authors_scene_cached(path)
    if kind == "native" and path.is_dir():
        # Every importer reads a file, never a folder: no need to load them (their rasterising imports
        # scipy.spatial and with it scipy.linalg, which a bench worker would pay per native scene).
        return read_native_scene(path)
    from sgplan.importers.detect import detect_kind, import_scene  # scipy: only for a source to import

    source = detect_kind(path)
    if source is not None:
        return import_scene(source, path).building
    if kind == "native":
        return read_native_scene(path)
    if kind == "npz":
        return load_gibson_npz(path)
    raise SceneError(
        "not a scene: expected a folder holding building.yaml (authors' format) or scene.json (sgplan's "
        "format), a raw 3DSceneGraph_<name>.npz file, or a source to import (a Matterport3D .house, a ROS "
        "map.yaml, a Hydra scene-graph .json)",
        path,
    )
