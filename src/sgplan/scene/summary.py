"""A summary of a building and its occupancy grid, as data (for the CLI, JSON output and tests).

:func:`summarize` returns a :class:`SceneSummary`; :func:`summary_lines` formats one as text lines;
``dataclasses.asdict(summary)`` gives plain dicts and lists for JSON.
"""

from __future__ import annotations

from dataclasses import dataclass

from sgplan.english import count
from sgplan.scene.grid import OccupancyGrid, build_occupancy_grid, component_sizes
from sgplan.scene.model import Building, Room


@dataclass(frozen=True)
class RoomSummary:
    """One room: ``key`` is ``room_<uuid>``; ``connected`` lists the keys of the rooms it connects to."""

    key: str
    id: int
    uuid: int
    category: str
    floor: int
    objects: tuple[str, ...]
    """``"<class> object_<uuid>"`` for each object in the room."""
    connected: tuple[str, ...]


@dataclass(frozen=True)
class FloorSummary:
    """One floor: its rooms, object count, free (traversable) cells and their 8-connected components."""

    index: int
    name: str
    rooms: tuple[RoomSummary, ...]
    num_objects: int
    free_cells: int | None
    """``None`` when the building has no maps (no grid)."""
    component_sizes: tuple[int, ...]
    """Sizes of the floor's 8-connected components of free cells, largest first (at most ten)."""
    up_portal: tuple[int, int] | None
    down_portal: tuple[int, int] | None


@dataclass(frozen=True)
class StairsSummary:
    """Stairs between ``lower_cell`` on ``lower_floor`` and ``upper_cell`` one floor up, at ``cost_m``."""

    lower_floor: int
    lower_cell: tuple[int, int]
    upper_cell: tuple[int, int]
    cost_m: float


@dataclass(frozen=True)
class SceneSummary:
    """Everything ``sgplan inspect`` reports about a scene."""

    name: str
    source: str | None
    grid_shape: tuple[int, int]
    """``(rows, cols)`` of every floor."""
    resolution_m: tuple[float, float]
    robot_radius_m: float | None
    """The radius the free cells were counted with (``None`` without maps)."""
    reach_radius_m: float | None
    floors: tuple[FloorSummary, ...]
    stairs: tuple[StairsSummary, ...]
    initial_cells: tuple[tuple[int, int, int], ...]
    initial_cells_free: tuple[bool | None, ...] = ()
    """Per initial cell: whether a robot of ``robot_radius_m`` may stand there (inside the grid, not in an
    inflated obstacle, in a room); ``None`` without maps."""

    @property
    def num_rooms(self) -> int:
        return sum(len(f.rooms) for f in self.floors)

    @property
    def num_objects(self) -> int:
        return sum(f.num_objects for f in self.floors)


def _room_summary(building: Building, room: Room) -> RoomSummary:
    return RoomSummary(
        key=room.key,
        id=room.id,
        uuid=room.uuid,
        category=room.name,
        floor=room.floor,
        objects=tuple(f"{o.name} {o.key}" for o in room.objects.values()),
        connected=tuple(building.room(id=i).key for i in room.connected_room_ids),
    )


def summarize(building: Building, grid: OccupancyGrid | None = None) -> SceneSummary:
    """Summarise ``building``; free cells come from ``grid`` (default: the grid for the building's own
    robot radius, or 0 m if it has none). A building without maps (raw ``.npz``) gets no grid figures."""
    has_maps = all(f.has_maps for f in building.floors)
    if grid is None and has_maps:
        grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    free = grid.traversable.sum(axis=(1, 2)).tolist() if grid is not None else [None] * building.num_floors
    components = component_sizes(grid) if grid is not None else [()] * building.num_floors
    floors = tuple(
        FloorSummary(
            index=f.index,
            name=f.name,
            rooms=tuple(_room_summary(building, r) for r in f.rooms.values()),
            num_objects=sum(len(r.objects) for r in f.rooms.values()),
            free_cells=free[f.index],
            component_sizes=tuple(int(s) for s in components[f.index][:10]),
            up_portal=f.up_stairs.portal if f.up_stairs else None,
            down_portal=f.down_stairs.portal if f.down_stairs else None,
        )
        for f in building.floors
    )
    return SceneSummary(
        name=building.name,
        source=str(building.source) if building.source is not None else None,
        grid_shape=building.grid_shape,
        resolution_m=building.resolution_m,
        robot_radius_m=grid.robot_radius_m if grid is not None else None,
        reach_radius_m=building.reach_radius_m,
        floors=floors,
        stairs=tuple(
            StairsSummary(s.lower_floor, s.lower_cell, s.upper_cell, s.cost_m)
            for s in (grid.stairs if grid is not None else ())
        ),
        initial_cells=tuple(building.initial_cells),
        initial_cells_free=tuple(
            grid.is_traversable(floor, (row, col)) if grid is not None else None
            for row, col, floor in building.initial_cells
        ),
    )


def summary_lines(summary: SceneSummary, *, objects: bool = True) -> list[str]:
    """The summary as text lines (no trailing newlines); ``objects=False`` leaves out the object lists."""
    rows, cols = summary.grid_shape
    res_x, res_y = summary.resolution_m
    lines = [
        f"building {summary.name}" + (f"  ({summary.source})" if summary.source else ""),
        f"  {count(len(summary.floors), 'floor')}, {count(summary.num_rooms, 'room')}, "
        f"{count(summary.num_objects, 'object')}",
    ]
    if summary.robot_radius_m is None:
        lines.append("  no maps: no occupancy grid")
    else:
        lines.append(f"  grid {rows} x {cols} cells per floor, cell {res_x:.4f} x {res_y:.4f} m")
        lines.append(
            f"  robot radius {summary.robot_radius_m:g} m"
            + (f", reach radius {summary.reach_radius_m:g} m" if summary.reach_radius_m is not None else "")
        )
    if summary.initial_cells:
        free = summary.initial_cells_free or (None,) * len(summary.initial_cells)
        lines.append("  initial cells (row, col, floor): " + ", ".join(
            f"{k}: {cell}" + (" NOT FREE" if ok is False else "")
            for k, (cell, ok) in enumerate(zip(summary.initial_cells, free))
        ))
        blocked = [k for k, ok in enumerate(free) if ok is False]
        if blocked:
            lines.append(
                f"  warning: initial cell(s) {', '.join(map(str, blocked))} lie in an obstacle (inflated "
                f"by the robot radius {summary.robot_radius_m:g} m) or outside every room: a plan "
                "cannot start there"
            )
    if summary.floors:
        lines.append("  rooms and objects by key (room_<uuid>, object_<uuid>: the names missions and "
                     "formulas use); '(id N)' is the room's id in the scene's maps")
    for floor in summary.floors:
        head = (f"floor {floor.index} ({floor.name}): {count(len(floor.rooms), 'room')}, "
                f"{count(floor.num_objects, 'object')}")
        if floor.free_cells is not None:
            parts = "; ".join(f"{s:,}" for s in floor.component_sizes)
            many = "+" if len(floor.component_sizes) == 10 else ""
            head += (f", {count(floor.free_cells, 'free cell')} in "
                     f"{count(len(floor.component_sizes), 'component')}{many} of [{parts}] cells")
        lines.append(head)
        for end, cell in (("up", floor.up_portal), ("down", floor.down_portal)):
            if cell is not None:
                lines.append(f"  stairs {end} portal at {cell}")
        for room in floor.rooms:
            link = ", ".join(room.connected) if room.connected else "none"
            lines.append(f"  {room.key} {room.category} (id {room.id}) -> {link}")
            if objects and room.objects:
                lines.append(f"      objects: {', '.join(room.objects)}")
    for s in summary.stairs:
        lines.append(
            f"stairs floor {s.lower_floor} {s.lower_cell} <-> floor {s.lower_floor + 1} {s.upper_cell}: "
            f"{s.cost_m:.4f} m"
        )
    return lines
