"""Hydra scene graphs (spark-dsg ``DynamicSceneGraph`` files) -> a building.

Needs the optional ``spark-dsg`` package (``pip install 'sgplan[hydra]'``; wheels for CPython 3.10-3.13
on Linux x86_64 / aarch64, macOS arm64 and Windows amd64).

Mapping
-------
- **Free space** comes from the mesh when the file has one (:func:`mesh_free_space`: cells where the
  mesh shows floor and nothing up to robot height), else from the places layer (``PLACES``, layer 3):
  each place is the centre of a ball of free space of radius ``distance``; the floor's free cells are
  the discs of those radii around the places, plus, along every edge between two places, the capsule of
  the smaller radius (Hydra links places whose balls overlap, so the capsule is free too). A one-cell
  ring around the free space is drawn as wall; the rest is outside. The places are needed either way:
  they carry the rooms.
- **Rooms** come from the room layer (``ROOMS``, layer 4) and their child places: a free cell belongs to
  the room of the nearest place. Places under no room join the room of their nearest place that has
  one. A file without rooms (Hydra did not segment any) becomes one room covering all the free space;
  a note says so, since missions can then name objects but not distinct rooms.
- **Floors**: rooms are clustered by height (a gap above ``floor_gap_m`` starts a new floor). An object
  is on the floor of its nearest place. A floor's ground is the lowest bottom of its objects' boxes
  (objects stand on it), else the lowest point the free-space balls of its places reach.
- **Objects** come from the object layer (``OBJECTS``, layer 2) with their bounding boxes (rotated ones
  included); their integer ``semantic_label`` is named through a label file (:mod:`.labelspace`).
  Whether one blocks is decided by its height, as for every importer (:mod:`.assemble`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

from sgplan.english import count
from sgplan.errors import SceneError
from sgplan.importers.assemble import FloorDraft, ImportResult, ObjectDraft, RoomDraft, Settings, assemble
from sgplan.importers.labelspace import LabelMap
from sgplan.importers.raster import GridFrame, capsules_mask
from sgplan.scene.model import NO_ROOM, CatCode

LAYER_IDS = {"OBJECTS": 2, "PLACES": 3, "ROOMS": 4}
"""Hydra's layer ids (used when the file does not name its layers)."""
DEFAULT_FLOOR_GAP_M = 1.5
FLOOR_BAND_M = 0.15
"""Mesh vertices within this height of the ground are floor."""
BODY_HEIGHT_M = 1.5
"""Mesh vertices from the floor band up to this height above the ground block the robot."""


def spark_dsg() -> Any:
    """The ``spark_dsg`` module, or a :class:`SceneError` saying how to install it."""
    try:
        import spark_dsg
    except ImportError:
        raise SceneError(
            "reading Hydra scene graphs needs the spark-dsg package: pip install 'sgplan[hydra]' "
            "(wheels exist for CPython 3.10-3.13 on Linux x86_64/aarch64, macOS arm64 and Windows amd64)"
        ) from None
    return spark_dsg


def looks_like_dsg(path: Path) -> bool:
    """A JSON file whose start holds spark-dsg's keys (checked without parsing the whole file)."""
    if not (path.is_file() and path.suffix.lower() == ".json"):
        return False
    try:
        with path.open("rb") as handle:
            head = handle.read(4096)
    except OSError:
        return False
    if b'"sgplan-scene"' in head:
        return False
    return any(key in head for key in (b'"SPARK_ORIGIN_HEADER"', b'"directed"', b'"layer_ids"'))


@dataclass
class _Place:
    id: int
    xyz: np.ndarray
    radius_m: float
    room: int | None


def import_dsg(
    path: str | Path,
    labels: LabelMap | None,
    settings: Settings | None = None,
    floor_gap_m: float = DEFAULT_FLOOR_GAP_M,
) -> ImportResult:
    """The building of a Hydra scene graph file (see the module docstring).

    Raises
    ------
    SceneError
        if spark-dsg is missing or cannot read the file, the places layer is missing or holds no place
        with a positive free-space radius, an object's label is not in ``labels`` (naming every unknown
        label), objects exist but no label file was given, or a layer's data is inconsistent.
    """
    settings = settings or Settings()
    path = Path(path)
    dsg = spark_dsg()
    try:
        graph = dsg.DynamicSceneGraph.load(str(path))
    except Exception as error:  # noqa: BLE001 - the C++ reader raises RuntimeError, json and pybind errors
        raise SceneError(f"spark-dsg cannot read this scene graph: {error}", path) from None
    layers = _layer_ids(graph)
    notes: list[str] = []
    places = _places(graph, layers, path, notes)
    room_names = _room_names(graph, layers, labels)
    if not room_names:
        notes.append(
            "the scene graph has no rooms (Hydra segmented none): one room covers all the free space, so "
            "missions can name objects but not distinct rooms"
        )
        room_names = {0: "room"}
        for place in places:
            place.room = 0
    elif len(room_names) == 1:
        notes.append(
            "Hydra segmented a single room for the whole scene: missions can name objects but not distinct "
            "rooms"
        )
    _adopt_orphans(graph, layers, places)
    room_ids = {node: k + 1 for k, node in enumerate(sorted(room_names))}
    floor_of_room, place_grounds = _floors(places, room_ids, floor_gap_m)
    place_floor = [floor_of_room[room_ids[p.room]] for p in places]  # type: ignore[index]
    objects = _objects(graph, layers, labels, places, place_floor, path)
    grounds = [  # objects stand on the floor: the lowest box bottom is the ground
        float(min((o.corners()[:, 2].min() for o in objects if o.floor == k), default=ground))
        for k, ground in enumerate(place_grounds)
    ]
    mesh = _mesh_points(graph)
    if mesh is not None:
        notes.append(
            "free space comes from the scene graph's mesh (floor and obstacle vertices), rooms from its "
            "places"
        )
    edges = _place_edges(graph, layers, {p.id: k for k, p in enumerate(places)})
    frame, floors = _floor_drafts(places, place_floor, edges, room_ids, grounds, mesh, settings)
    rooms = [
        RoomDraft(room_ids[node], room_names[node], floor_of_room[room_ids[node]])
        for node in sorted(room_names)
    ]
    result = assemble(path.stem, frame, floors, rooms, objects, settings)
    result.notes[:0] = notes
    return result


def _floor_drafts(
    places: list[_Place],
    place_floor: list[int],
    edges: np.ndarray,
    room_ids: dict[int, int],
    grounds: list[float],
    mesh: np.ndarray | None,
    settings: Settings,
) -> tuple[GridFrame, list[FloorDraft]]:
    """The shared grid (around the places' free space and the mesh) and every floor's rasters."""
    xy = np.array([p.xyz[:2] for p in places])
    radius = np.array([p.radius_m for p in places])
    lo, hi = (xy - radius[:, None]).min(axis=0), (xy + radius[:, None]).max(axis=0)
    if mesh is not None:
        lo, hi = np.minimum(lo, mesh[:, :2].min(axis=0)), np.maximum(hi, mesh[:, :2].max(axis=0))
    frame = GridFrame.around(lo, hi, settings.resolution_m, 0.5)
    floors = []
    for k, ground in enumerate(grounds):
        members = np.array([f == k for f in place_floor])
        if mesh is not None:
            free = mesh_free_space(frame, mesh, ground)
        else:
            free = places_free_space(frame, places, members, edges)
        floors.append(_floor(frame, free, places, members, room_ids, ground, chr(ord("A") + k)))
    return frame, floors


def _layer_ids(graph: Any) -> dict[str, int]:
    named = getattr(graph, "layer_names", None)
    ids = dict(LAYER_IDS)
    if isinstance(named, dict):
        ids.update({key: _layer_number(value) for key, value in named.items() if key in LAYER_IDS})
    return ids


def _layer_number(key: Any) -> int:
    """A layer id from spark-dsg's ``LayerKey`` (newer files) or a plain integer."""
    return int(key.layer) if hasattr(key, "layer") else int(key)


def _nodes(graph: Any, layer: int) -> list[Any]:
    return list(graph.get_layer(layer).nodes) if graph.has_layer(layer) else []


def _places(graph: Any, layers: dict[str, int], path: Path, notes: list[str]) -> list[_Place]:
    if not graph.has_layer(layers["PLACES"]):
        raise SceneError(
            f"the scene graph has no places layer (layer {layers['PLACES']}): it says nothing about free "
            "space",
            path,
        )
    rooms = {int(n.id.value): n for n in _nodes(graph, layers["ROOMS"])}
    place_room: dict[int, int] = {}
    for room_id, room in rooms.items():
        for child in room.children():
            place_room[int(child)] = room_id
    places = []
    skipped = 0
    for node in _nodes(graph, layers["PLACES"]):
        attributes = node.attributes
        radius = float(getattr(attributes, "distance", 0.0))
        xyz = np.asarray(attributes.position, dtype=float)
        if not (np.isfinite(radius) and radius > 0 and np.isfinite(xyz).all()):
            skipped += 1
            continue
        places.append(_Place(int(node.id.value), xyz, radius, place_room.get(int(node.id.value))))
    if not places:
        raise SceneError(
            f"the places layer (layer {layers['PLACES']}) holds no place with a positive free-space "
            "distance: "
            "nothing tells where the robot may go",
            path,
        )
    if skipped:
        notes.append(
            f"{count(skipped, 'place')} without a positive free-space distance or a finite position "
            f"{'is' if skipped == 1 else 'are'} ignored"
        )
    return places


def _room_names(graph: Any, layers: dict[str, int], labels: LabelMap | None) -> dict[int, str]:
    """Room node id -> category: from the label file's rooms section when it names the room's label."""
    names = {}
    for node in _nodes(graph, layers["ROOMS"]):
        label = int(getattr(node.attributes, "semantic_label", -1))
        names[int(node.id.value)] = labels.room_name(label) if labels is not None else "room"
    return names


def _adopt_orphans(graph: Any, layers: dict[str, int], places: list[_Place]) -> None:
    """Places under no room join the room of their nearest place that has one.

    When no place has a room (a file whose rooms list no children), each place joins the room whose
    node position is nearest.
    """
    orphans = [p for p in places if p.room is None]
    if not orphans:
        return
    roomed = [p for p in places if p.room is not None]
    if roomed:
        anchors = np.array([p.xyz for p in roomed])
        owners = [p.room for p in roomed]
    else:
        nodes = _nodes(graph, layers["ROOMS"])
        anchors = np.array([np.asarray(n.attributes.position, dtype=float) for n in nodes])
        owners = [int(n.id.value) for n in nodes]
    _, nearest = cKDTree(anchors).query(np.array([p.xyz for p in orphans]))
    for place, k in zip(orphans, np.atleast_1d(nearest)):
        place.room = owners[int(k)]


def _floors(
    places: list[_Place], room_ids: dict[int, int], floor_gap_m: float
) -> tuple[dict[int, int], list[float]]:
    """Floor index of every room (clustered by the median height of its places) and each floor's ground."""
    height = {
        room_ids[node]: float(np.median([p.xyz[2] for p in places if p.room == node]))
        for node in room_ids
        if any(p.room == node for p in places)
    }
    for room in room_ids.values():  # a room without places: the lowest floor (it covers no cell, with a note)
        height.setdefault(room, min(height.values(), default=0.0))
    ordered = sorted(height, key=lambda r: height[r])
    floor_of: dict[int, int] = {}
    floor = 0
    for previous, room in zip([None, *ordered], ordered):
        if previous is not None and height[room] - height[previous] > floor_gap_m:
            floor += 1
        floor_of[room] = floor
    grounds = []
    for k in range(floor + 1):
        lows = [p.xyz[2] - p.radius_m for p in places if floor_of[room_ids[p.room]] == k]  # type: ignore[index]
        grounds.append(float(min(lows)) if lows else float("nan"))
    return floor_of, grounds


def _place_edges(graph: Any, layers: dict[str, int], index: dict[int, int]) -> np.ndarray:
    """Edges between kept places as index pairs ``(n, 2)``."""
    pairs = [
        (index[int(edge.source)], index[int(edge.target)])
        for edge in graph.get_layer(layers["PLACES"]).edges
        if int(edge.source) in index and int(edge.target) in index
    ]
    return np.array(pairs, dtype=np.int64).reshape(-1, 2)


def places_free_space(
    frame: GridFrame, places: list[_Place], members: np.ndarray, edges: np.ndarray
) -> np.ndarray:
    """The free cells of one floor from its places: discs of their radii, capsules along their edges."""
    xy = np.array([p.xyz[:2] for p in places])
    radius = np.array([p.radius_m for p in places])
    free = capsules_mask(frame, xy[members], xy[members], radius[members])
    on_floor = edges[members[edges[:, 0]] & members[edges[:, 1]]] if len(edges) else edges
    if len(on_floor):
        free |= capsules_mask(
            frame,
            xy[on_floor[:, 0]],
            xy[on_floor[:, 1]],
            np.minimum(radius[on_floor[:, 0]], radius[on_floor[:, 1]]),
        )
    return free


def mesh_free_space(frame: GridFrame, points: np.ndarray, ground_z: float) -> np.ndarray:
    """The free cells of one floor from mesh vertices ``(n, 3)``: floor seen, no obstacle above it.

    A cell is floor when it holds a vertex within :data:`FLOOR_BAND_M` of ``ground_z`` (gaps between
    vertices are closed over two cells); it is blocked when it holds a vertex between that band and
    :data:`BODY_HEIGHT_M` above the ground (walls, furniture; not the ceiling, not the floor above).
    """
    cells = frame.cell_of(points[:, :2])
    on_grid = frame.contains(cells)
    height = points[:, 2] - ground_z
    floor, blocked = frame.empty(), frame.empty()
    seen = on_grid & (np.abs(height) <= FLOOR_BAND_M)
    floor[cells[seen, 0], cells[seen, 1]] = True
    high = on_grid & (height > FLOOR_BAND_M) & (height <= BODY_HEIGHT_M)
    blocked[cells[high, 0], cells[high, 1]] = True
    floor = ndimage.binary_closing(floor, iterations=2)
    return floor & ~blocked


def _mesh_points(graph: Any) -> np.ndarray | None:
    """The mesh's vertex positions ``(n, 3)``, or ``None`` without a mesh."""
    if not graph.has_mesh() or graph.mesh.num_vertices() == 0:
        return None
    points = np.asarray(graph.mesh.get_vertices(), dtype=float)[:3].T
    points = points[np.isfinite(points).all(axis=1)]
    return points if len(points) else None


def _floor(
    frame: GridFrame,
    free: np.ndarray,
    places: list[_Place],
    members: np.ndarray,
    room_ids: dict[int, int],
    ground_z: float,
    name: str,
) -> FloorDraft:
    """The floor's rasters: ``free`` cells as ground, each in the room of its nearest place; a wall ring."""
    xy = np.array([p.xyz[:2] for p in places])
    room_of_place = np.array([room_ids[p.room] for p in places], dtype=np.int16)[members]  # type: ignore[index]
    cells = np.argwhere(free)
    room_map = np.full(frame.shape, NO_ROOM, dtype=np.int16)
    if len(cells):
        centres = np.asarray(frame.origin_m) + (cells + 0.5) * frame.resolution_m
        _, nearest = cKDTree(xy[members]).query(centres)
        room_map[cells[:, 0], cells[:, 1]] = room_of_place[nearest]
    ring = ndimage.binary_dilation(free, iterations=1) & ~free
    cat = np.full(frame.shape, CatCode.OUTSIDE, dtype=np.int16)
    cat[free] = CatCode.GROUND
    cat[ring] = CatCode.WALL
    return FloorDraft(name, ground_z, cat, room_map)


def _objects(
    graph: Any,
    layers: dict[str, int],
    labels: LabelMap | None,
    places: list[_Place],
    place_floor: list[int],
    path: Path,
) -> list[ObjectDraft]:
    nodes = _nodes(graph, layers["OBJECTS"])
    if not nodes:
        return []
    found = sorted({int(n.attributes.semantic_label) for n in nodes})
    if labels is None:
        raise SceneError(
            f"the scene graph's objects carry integer labels {found} and no label file was given: pass "
            "--labels FILE (Hydra's label-space yaml, or a YAML / CSV map id -> name)",
            path,
        )
    unknown = [label for label in found if labels.object_name(label) is None]
    if unknown:
        raise SceneError(f"object label(s) {unknown} are not in the label file {labels.path}", path)
    tree = cKDTree(np.array([p.xyz for p in places]))
    objects = []
    for node in nodes:
        attributes = node.attributes
        box = attributes.bounding_box
        center = np.asarray(box.world_P_center, dtype=float)
        half = np.abs(np.asarray(box.dimensions, dtype=float)) / 2.0
        rotation = np.asarray(box.world_R_center, dtype=float) if box.has_rotation() else np.eye(3)
        if not (box.is_valid() and np.isfinite(center).all() and np.isfinite(half).all()):
            raise SceneError(f"object {node.id} has no valid bounding box", path)
        _, nearest = tree.query(center)
        objects.append(
            ObjectDraft(
                name=labels.object_name(int(attributes.semantic_label)) or "object",
                floor=place_floor[int(nearest)],
                center_m=center,
                axes=rotation.T,  # columns of world_R_center are the box axes in the world frame
                half_sizes_m=half,
                source=f"node {node.id}",
            )
        )
    return objects
