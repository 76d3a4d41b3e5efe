"""Matterport3D ``.house`` files (the ASCII 1.1 house annotation) -> a building.

The file is plain text, one record per line, its kind in the first token (Matterport3D's
data_organization.md documents the fields). Used here:

====  ===============================================================================================
H     counts of every record kind (checked against the records found: a short count = a cut file)
L     level: index, bounding box                                       -> a floor (lowest first)
R     region: index, level, one-letter label, bounding box, height     -> a room (:data:`REGION_NAMES`)
S     surface: index, region, label                                    -> a floor polygon of that room
V     vertex: index, surface, position                                 -> the polygon's corners, in order
C     category: index, raw name, mpcat40 name                          -> object names
O     object: index, region, category, centre, two box axes, half sizes -> an object / obstacle / door
P     portal: region pair, bounding box                                -> a passage, as a door
====  ===============================================================================================

How the map is drawn (all metric, then rasterised at the chosen resolution):

- every room is the union of its floor polygons; a cell in no polygon is wall near a room, outside
  beyond ``WALL_BAND_M``;
- the file holds no wall geometry other than the gaps between floor polygons: two rooms whose polygons
  come closer than ``open_gap_m`` (default 0.14 m, thinner than an interior wall) share an open
  boundary, and the gap between them is floor; a wider gap is a wall;
- a door (mpcat40 ``door``: doors and door frames) opens the wall across its width between the two
  rooms covering most of its footprint (deepened to ``DOOR_REACH_M`` on each side to span the wall);
  a door touching one room only (a front door) opens nothing; a portal (P) opens the wall between its
  two regions;
- other objects become sgplan objects named by their raw category (``coffee#table`` ->
  "coffee table"); whether one blocks the robot is decided by its height (:mod:`.assemble`). Walls,
  floors, ceilings and void annotations are not objects (a ``wall`` box spans its whole region).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import ndimage

from sgplan.english import series
from sgplan.errors import SceneError
from sgplan.importers import DEFAULT_OPEN_GAP_M
from sgplan.importers.assemble import FloorDraft, ImportResult, ObjectDraft, RoomDraft, Settings, assemble
from sgplan.importers.raster import (
    GridFrame,
    box_corners,
    hull_cells,
    polygon_area_m2,
    polygon_cells,
    polygon_distance_m,
)
from sgplan.scene.model import NO_ROOM, CatCode

REGION_NAMES: dict[str, str] = {
    "a": "bathroom",
    "b": "bedroom",
    "c": "closet",
    "d": "dining_room",
    "e": "lobby",  # entryway / foyer / lobby
    "f": "family_room",
    "g": "garage",
    "h": "corridor",  # hallway
    "i": "library",
    "j": "laundry_room",  # laundry room / mudroom
    "k": "kitchen",
    "l": "living_room",
    "m": "meeting_room",
    "n": "lounge",
    "o": "office",
    "p": "porch",  # porch / terrace / deck / driveway
    "r": "rec_room",  # recreation / game room
    "s": "stairs",
    "t": "toilet_room",  # a small room with only a toilet; "toilet" would clash with the object
    "u": "utility_room",  # utility room / tool room
    "v": "tv_room",
    "w": "gym",  # workout / gym / exercise
    "x": "outdoor",
    "y": "balcony",
    "z": "other_room",
    "B": "bar",
    "C": "classroom",
    "D": "dining_booth",
    "S": "spa",  # spa / sauna
    "T": "vehicle",  # transportation
    "-": "room",  # no label
}
"""Matterport3D region labels (data_organization.md) -> sgplan room categories (Gibson-style names
where Gibson has the category: lobby, corridor)."""

NOT_OBJECTS = frozenset({"wall", "floor", "ceiling", "door", "void"})
"""mpcat40 categories that are structure or annotation leftovers, not objects."""
NOT_OBJECT_NAMES = frozenset({"unknown", "remove", "delete"})

WALL_BAND_M = 0.5
"""Cells within this distance of a room but in none are wall; farther ones are outside."""
DOOR_REACH_M = 0.5
"""A door box is deepened to at least this on each side of its plane, so it spans the wall it sits in."""


@dataclass
class _Region:
    index: int
    level: int
    label: str
    height_m: float
    polygons: list[np.ndarray] = field(default_factory=list)


@dataclass
class House:
    """The records of a ``.house`` file that the importer uses (see the module docstring)."""

    path: Path
    levels: dict[int, np.ndarray]
    """level index -> bounding box ``[xlo, ylo, zlo, xhi, yhi, zhi]``."""
    regions: dict[int, _Region]
    categories: dict[int, tuple[str, str]]
    """category index -> (raw name, mpcat40 name)."""
    objects: list[tuple[int, int, int, np.ndarray]]
    """(object index, region, category, 15 numbers: centre, axis 0, axis 1, half sizes)."""
    portals: list[tuple[int, int, int, np.ndarray]]
    """(portal index, region 0, region 1, bounding box)."""
    surface_z: dict[int, list[float]]
    """region index -> heights of its floor surfaces."""


# -- parsing -------------------------------------------------------------------------------------------


def is_house_file(path: Path) -> bool:
    return path.is_file() and path.suffix.lower() == ".house"


def _records(path: Path) -> Iterator[tuple[int, list[str]]]:
    try:
        with path.open(encoding="utf-8") as handle:
            first = handle.readline().split()
            if first[:1] != ["ASCII"]:
                raise SceneError("not a Matterport3D .house file: the first line must be 'ASCII 1.1'", path)
            for number, line in enumerate(handle, start=2):
                tokens = line.split()
                if tokens:
                    yield number, tokens
    except (OSError, UnicodeDecodeError) as error:
        raise SceneError(f"cannot read: {error}", path) from None


_MIN_TOKENS = {"H": 13, "L": 13, "R": 16, "S": 8, "V": 7, "C": 6, "O": 16, "P": 11}
_COUNT_FIELD = {"V": 5, "S": 6, "O": 8, "C": 9, "R": 10, "P": 11, "L": 12}
"""Position in the H record of each record kind's count."""


@dataclass
class _Records:
    """The records of a file as parsed, before their references are checked."""

    header: list[str] | None = None
    counts: dict[str, int] = field(default_factory=lambda: dict.fromkeys(_COUNT_FIELD, 0))
    levels: dict[int, np.ndarray] = field(default_factory=dict)
    regions: dict[int, _Region] = field(default_factory=dict)
    surfaces: dict[int, tuple[int, str, float]] = field(default_factory=dict)
    vertices: dict[int, list[tuple[int, float, float]]] = field(default_factory=dict)
    categories: dict[int, tuple[str, str]] = field(default_factory=dict)
    objects: list[tuple[int, int, int, np.ndarray]] = field(default_factory=list)
    portals: list[tuple[int, int, int, np.ndarray]] = field(default_factory=list)

    def add(self, t: list[str]) -> None:
        """Store one record (``t`` = its tokens); ``ValueError`` for a field that is not a number."""
        kind = t[0]
        self.counts[kind] = self.counts.get(kind, 0) + 1
        if kind == "H":
            self.header = t
        elif kind == "L":
            self.levels[int(t[1])] = np.array(t[7:13], dtype=float)
        elif kind == "R":
            self.regions[int(t[1])] = _Region(int(t[1]), int(t[2]), t[5], float(t[15]))
        elif kind == "S":
            self.surfaces[int(t[1])] = (int(t[2]), t[4], float(t[7]))
        elif kind == "V":
            self.vertices.setdefault(int(t[2]), []).append((int(t[1]), float(t[4]), float(t[5])))
        elif kind == "C":
            self.categories[int(t[1])] = (t[3].replace("#", " ").lower(), t[5].lower())
        elif kind == "O":
            self.objects.append((int(t[1]), int(t[2]), int(t[3]), np.array(t[4:16], dtype=float)))
        elif kind == "P":
            self.portals.append((int(t[1]), int(t[2]), int(t[3]), np.array(t[5:11], dtype=float)))


def read_house(path: str | Path) -> House:
    """Parse a ``.house`` file (see the module docstring for the records used).

    Raises
    ------
    SceneError
        naming the file and line for a short record or a field that is not a number; naming the
        entity for a reference to a missing level, region or surface, a degenerate floor polygon, an
        unknown region label, a count in the H record that disagrees with the records, or a file
        without H, levels or regions.
    """
    path = Path(path)
    records = _Records()
    for line, tokens in _records(path):
        kind = tokens[0]
        if kind not in _MIN_TOKENS:
            continue
        if len(tokens) < _MIN_TOKENS[kind]:
            message = f"line {line}: a {kind} record needs {_MIN_TOKENS[kind]} fields, found {len(tokens)}"
            raise SceneError(message, path)
        try:
            records.add(tokens)
        except ValueError:
            raise SceneError(f"line {line}: a {kind} record has a field that is not a number", path) from None
    _check_counts(records, path)
    surface_z = _attach_polygons(records, path)
    _check_references(records, path)
    return House(
        path, records.levels, records.regions, records.categories, records.objects, records.portals, surface_z
    )


def _check_counts(records: _Records, path: Path) -> None:
    header = records.header
    if header is None:
        raise SceneError("no H (house) record: not a Matterport3D .house file", path)
    for kind, position in _COUNT_FIELD.items():
        declared = int(header[position]) if header[position].lstrip("-").isdigit() else -1
        if declared != records.counts[kind]:
            raise SceneError(
                f"the H record declares {header[position]} {kind} records but the file holds "
                f"{records.counts[kind]} (a cut or edited file?)",
                path,
            )
    if not records.levels or not records.regions:
        raise SceneError("the house has no levels (L) or no regions (R): nothing to plan on", path)


def _attach_polygons(records: _Records, path: Path) -> dict[int, list[float]]:
    """Give every region its floor polygons (vertices in index order); returns the surfaces' heights."""
    surface_z: dict[int, list[float]] = {}
    for surface, corners in sorted(records.vertices.items()):
        if surface not in records.surfaces:
            raise SceneError(f"vertices name surface {surface}, which has no S record", path)
        region_index, _, z = records.surfaces[surface]
        if region_index not in records.regions:
            raise SceneError(f"surface {surface} names region {region_index}, which has no R record", path)
        polygon = np.array([(x, y) for _, x, y in sorted(corners)], dtype=float)
        if len(polygon) < 3 or polygon_area_m2(polygon) < 1e-4:
            raise SceneError(
                f"surface {surface} (region {region_index}) is a degenerate floor polygon "
                f"({len(polygon)} vertices, area {polygon_area_m2(polygon):.2g} m^2)",
                path,
            )
        records.regions[region_index].polygons.append(polygon)
        surface_z.setdefault(region_index, []).append(z)
    return surface_z


def _check_references(records: _Records, path: Path) -> None:
    levels, regions = records.levels, records.regions
    for region in regions.values():
        if region.level not in levels:
            message = (
                f"region {region.index} is on level {region.level}, but the file has levels {sorted(levels)}"
            )
            raise SceneError(message, path)
        if region.label not in REGION_NAMES:
            message = f"region {region.index} has label {region.label!r}, not a Matterport3D region label"
            raise SceneError(message, path)
    for index, region_index, category, _ in records.objects:
        if category >= 0 and category not in records.categories:
            raise SceneError(f"object {index} names category {category}, which has no C record", path)
        if region_index >= 0 and region_index not in regions:
            raise SceneError(f"object {index} names region {region_index}, which has no R record", path)
    for index, r0, r1, _ in records.portals:
        if r0 not in regions or r1 not in regions:
            raise SceneError(f"portal {index} joins regions {r0} and {r1}; one has no R record", path)


# -- building ------------------------------------------------------------------------------------------


def import_house(
    path: str | Path, settings: Settings | None = None, open_gap_m: float = DEFAULT_OPEN_GAP_M
) -> ImportResult:
    """The building of a Matterport3D ``.house`` file (see the module docstring for the mapping)."""
    settings = settings or Settings()
    house = read_house(path)
    notes: list[str] = []
    drawn = {i: r for i, r in house.regions.items() if r.polygons}
    undrawn = sorted(set(house.regions) - set(drawn))
    if undrawn:
        one = len(undrawn) == 1
        notes.append(
            f"{'region' if one else 'regions'} {series([str(r) for r in undrawn])} "
            f"{'has' if one else 'have'} no floor polygon and {'is' if one else 'are'} left out (their "
            "objects join the nearest room)"
        )
    if not drawn:
        raise SceneError("no region has a floor polygon (S and V records): nothing to rasterise", house.path)
    ground = _level_grounds(house, drawn)
    order = sorted(ground, key=lambda level: ground[level])  # floors lowest first
    floor_of = {level: k for k, level in enumerate(order)}
    corners = np.vstack([p for r in drawn.values() for p in r.polygons])
    frame = GridFrame.around(
        corners.min(axis=0), corners.max(axis=0), settings.resolution_m, WALL_BAND_M + 0.5
    )

    rooms = [
        RoomDraft(i + 1, REGION_NAMES[r.label], floor_of[r.level], r.height_m)
        for i, r in sorted(drawn.items())
    ]
    floors = []
    for level in order:
        on_level = {i: r for i, r in drawn.items() if r.level == level}
        floors.append(
            _floor(house, frame, on_level, ground[level], f"{chr(ord('A') + floor_of[level])}", open_gap_m)
        )
    objects = list(_objects(house, drawn, floor_of, ground))
    result = assemble(house.path.stem, frame, floors, rooms, objects, settings)
    result.notes[:0] = notes
    return result


def _level_grounds(house: House, drawn: dict[int, _Region]) -> dict[int, float]:
    """Ground height per level: the median height of its regions' floor surfaces (else its box bottom)."""
    grounds = {}
    for level, box in house.levels.items():
        heights = [z for i, r in drawn.items() if r.level == level for z in house.surface_z.get(i, [])]
        grounds[level] = float(np.median(heights)) if heights else float(box[2])
    return {level: z for level, z in grounds.items() if any(r.level == level for r in drawn.values())}


def _floor(
    house: House, frame: GridFrame, regions: dict[int, _Region], ground_z: float, name: str, open_gap_m: float
) -> FloorDraft:
    room_map = np.full(frame.shape, NO_ROOM, dtype=np.int16)
    for index, region in sorted(regions.items()):
        for polygon in region.polygons:
            cells = polygon_cells(frame, polygon)
            room_map[cells[:, 0], cells[:, 1]] = index + 1
    polygons = room_map.copy()  # distances are measured to the polygons, before any gap is bridged
    near_room = ndimage.distance_transform_edt(room_map <= 0, sampling=frame.resolution_m) <= WALL_BAND_M
    cat = np.where(room_map > 0, CatCode.GROUND, np.where(near_room, CatCode.WALL, CatCode.OUTSIDE))
    floor = FloorDraft(name, ground_z, cat.astype(np.int16), room_map)
    bridge = _Bridges(floor, polygons, frame.resolution_m, regions)
    for a, b in bridge.pairs_within(open_gap_m):
        bridge(a, b, None)
    for _, _, category, numbers in house.objects:
        if category >= 0 and house.categories[category][1] == "door":
            cells = _door_cells(frame, numbers)
            # a door joins two spaces: the two rooms covering most of its footprint
            counts = np.bincount(np.maximum(polygons[cells[:, 0], cells[:, 1]], 0), minlength=1)[1:]
            touched = [int(k) for k in np.argsort(-counts, kind="stable")[:2] if counts[k] > 0]
            if len(touched) == 2:
                bridge(min(touched), max(touched), cells)
    for _, r0, r1, box in house.portals:
        if r0 in regions and r1 in regions and r0 != r1:
            lo, hi = box[:2] - DOOR_REACH_M, box[3:5] + DOOR_REACH_M
            rectangle = np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]])
            bridge(min(r0, r1), max(r0, r1), polygon_cells(frame, rectangle))
    return floor


class _Bridges:
    """Opens the wall between two regions of one floor (``__call__``), measuring near the two rooms only.

    The cells between regions ``a`` and ``b`` are the non-room cells whose distances to the two
    polygons add up to at most the gap between them (plus two cells); each joins the nearer room and
    becomes floor. Distances are computed in the window around the two rooms, so a bridge costs what the
    two rooms cover, not what the floor holds.
    """

    def __init__(
        self, floor: FloorDraft, polygons: np.ndarray, res: float, regions: dict[int, _Region]
    ) -> None:
        self.floor, self.polygons, self.res, self.regions = floor, polygons, res, regions
        self.boxes = ndimage.find_objects(np.maximum(polygons, 0))
        self.gaps: dict[tuple[int, int], float] = {}

    def box(self, region: int) -> tuple[slice, slice] | None:
        return self.boxes[region] if region < len(self.boxes) else None

    def gap(self, a: int, b: int) -> float:
        """Metric distance between the floor polygons of regions ``a < b`` (cached)."""
        if (a, b) not in self.gaps:
            self.gaps[(a, b)] = min(
                polygon_distance_m(p, q) for p in self.regions[a].polygons for q in self.regions[b].polygons
            )
        return self.gaps[(a, b)]

    def pairs_within(self, limit_m: float) -> list[tuple[int, int]]:
        """Region pairs ``(a, b)``, ``a < b``, whose polygons come within ``limit_m`` of each other."""
        bounds = {
            i: (np.vstack(r.polygons).min(axis=0), np.vstack(r.polygons).max(axis=0))
            for i, r in self.regions.items()
        }
        pairs = []
        for a in sorted(self.regions):
            for b in sorted(self.regions):
                if a < b:
                    apart = np.maximum(bounds[a][0] - bounds[b][1], bounds[b][0] - bounds[a][1]).max()
                    if apart <= limit_m and self.gap(a, b) <= limit_m:
                        pairs.append((a, b))
        return pairs

    def __call__(self, a: int, b: int, within: np.ndarray | None) -> None:
        box_a, box_b = self.box(a), self.box(b)
        if box_a is None or box_b is None:
            return
        gap, res = self.gap(a, b), self.res
        margin = int(np.ceil((gap + 2 * res) / res)) + 1
        rows, cols = self.polygons.shape
        window = (
            slice(
                max(0, min(box_a[0].start, box_b[0].start) - margin),
                min(rows, max(box_a[0].stop, box_b[0].stop) + margin),
            ),
            slice(
                max(0, min(box_a[1].start, box_b[1].start) - margin),
                min(cols, max(box_a[1].stop, box_b[1].stop) + margin),
            ),
        )
        polygons = self.polygons[window]
        da = ndimage.distance_transform_edt(polygons != a + 1, sampling=res)
        db = ndimage.distance_transform_edt(polygons != b + 1, sampling=res)
        room_map, cat = self.floor.room_map[window], self.floor.cat_map[window]  # views
        between = (room_map == NO_ROOM) & (da + db <= gap + 2 * res) & (np.maximum(da, db) <= gap + 2 * res)
        if within is not None:
            inside = np.zeros_like(between)
            local = within - (window[0].start, window[1].start)
            keep = (
                (local >= 0).all(axis=1) & (local[:, 0] < inside.shape[0]) & (local[:, 1] < inside.shape[1])
            )
            inside[local[keep, 0], local[keep, 1]] = True
            between &= inside
        room_map[between] = np.where(da[between] <= db[between], a + 1, b + 1)
        cat[between] = CatCode.GROUND


def _box_axes(numbers: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centre, unit axes (rows; the third = axis 0 x axis 1) and half sizes of an O record's box."""
    center, a0, a1, half = numbers[:3], numbers[3:6], numbers[6:9], numbers[9:12]
    axes = np.array([a0, a1, np.cross(a0, a1)])
    norms = np.linalg.norm(axes, axis=1, keepdims=True)
    return center, axes / np.where(norms > 0, norms, 1.0), np.abs(half)


def _door_cells(frame: GridFrame, numbers: np.ndarray) -> np.ndarray:
    """A door's footprint cells, deepened to :data:`DOOR_REACH_M` on each side so it spans its wall."""
    center, axes, half = _box_axes(numbers)
    vertical = int(np.argmax(np.abs(axes[:, 2])))
    horizontal = [k for k in range(3) if k != vertical]
    thin = min(horizontal, key=lambda k: half[k])
    half = half.copy()
    half[thin] = max(half[thin], DOOR_REACH_M)
    return hull_cells(frame, box_corners(center, axes, half)[:, :2])


def _objects(
    house: House, drawn: dict[int, _Region], floor_of: dict[int, int], ground: dict[int, float]
) -> Iterator[ObjectDraft]:
    for index, region, category, numbers in house.objects:
        if category < 0:
            continue
        raw, mpcat = house.categories[category]
        if mpcat in NOT_OBJECTS or raw in NOT_OBJECT_NAMES:
            continue
        center, axes, half = _box_axes(numbers)
        if region in house.regions and house.regions[region].level in floor_of:
            level = house.regions[region].level
        else:  # no usable region: the level whose ground is nearest below the box
            level = min(floor_of, key=lambda lv: abs(center[2] - ground[lv]))
        yield ObjectDraft(
            name=raw,
            floor=floor_of[level],
            center_m=center,
            axes=axes,
            half_sizes_m=half,
            room_id=region + 1 if region in drawn else None,
            source=f"O record {index}",
        )
