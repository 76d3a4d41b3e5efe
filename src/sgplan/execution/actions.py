"""A run's composite actions (every setup but A*), kept across scene changes: the families keep their
indices, and only the maps a change can have altered are rebuilt.

A composite action family follows exact shortest paths to its targets (:mod:`sgplan.planning.domain`):
within one room for the object and door families, over a floor for the stairs families (and for the
objects of a staircase). Its map -- the Dijkstra the search fills the first time it needs it -- depends
only on the cells of that room or floor, its targets, and how many of the room's cells the robot can
reach (the map stops once it has settled them). So after a change :class:`RunActions` keeps

- the **tables** -- every family over the run's whole numbering (:mod:`sgplan.execution.graph`), its
  targets including those masked now (the map's Dijkstra leaves out the targets off the graph), so a
  closed door or a block never adds or removes a family and every index stays; a moved or removed object,
  and every object of a room where cells left or joined the graph (what an object is visible from may
  have changed), gets its family's targets and room anew in place; only an added object appends a family
  (and starts the maps afresh: their arrays have a row per family);
- the **maps** of every family whose room (floor) holds no cell that left or joined the graph, none of
  whose targets did, whose object did not move, and whose room the robot cannot reach more of than when
  the map stopped (a map that stopped later than it needs to is still exact);
- the **label runs** over each kept map unless a cell of its room changed label (the run's compact label
  ids stay the cells' own across changes, :mod:`sgplan.execution.cell_labels`).

A forgotten map is cleared where its Dijkstra wrote (its room's cells, which the numbering keeps
contiguous, and its targets; or its floor) and rebuilt by the next search that needs it.
``tests/execution/test_actions.py`` compares every kept map and label run with those built afresh on the
changed building.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Collection, Mapping

import numpy as np

from sgplan.planning.cells import CellGraph
from sgplan.planning.domain import (
    MAP_OBJECT,
    ActionMap,
    ActionParts,
    ActionTables,
    KernelMaps,
    LabelRuns,
    MapStore,
    action_families,
    action_tables,
    object_family,
    room_indices,
    stop_counts,
)
from sgplan.planning.problem import PlanningProblem
from sgplan.scene.reach import sight_may_change


class RunActions:
    """The composite action parts of a run's problems (see the module), kept over the run's numbering.

    ``counts`` tallies ``tables`` (built from scratch), ``objects`` (families refreshed for a changed
    object), ``maps_forgotten`` and ``runs_forgotten``, for tests and benchmarks."""

    def __init__(self, candidates: CellGraph) -> None:
        self.candidates = candidates
        self.tables: ActionTables | None = None
        self.store: MapStore | None = None
        self.runs: LabelRuns | None = None
        self._objects: set[int] = set()  # uuids of the objects whose families need new targets
        self._sight: dict[int, list[np.ndarray]] = {}  # floor -> cells that changed category since
        self._spans: np.ndarray | None = None  # per room, the [first, last + 1) cells of its block
        self.counts: Counter[str] = Counter()

    def parts(self, problem: PlanningProblem, reachable: np.ndarray) -> ActionParts:
        """The tables, maps and label runs for ``problem`` (the run's current grid and labels) from the
        robot's component ``reachable``, what changed since brought up to date.

        Cost: the first time, the tables (every object's reach region); then a count of the reachable
        cells per room, and the families of changed objects."""
        if self.tables is None:
            rooms = list(problem.building.rooms())
            self.tables = action_tables(action_families(problem, self.candidates, rooms),
                                        room_indices(problem, self.candidates, rooms), rooms,
                                        self.candidates.shape[0])
            self._spans = _room_spans(self.tables.cell_room, self.tables.num_rooms)
            self.counts["tables"] += 1
        else:
            self._sight_changes(problem)
        if self._objects:
            self._refresh_objects(problem)
        tables = self.tables
        stop = stop_counts(tables.cell_room, reachable, tables.num_rooms, tables.kactions.map_stop_room)
        if self.store is None:
            self.store = MapStore.empty(tables, self.candidates, reachable)
            self.runs = None
        else:
            self.forget(np.flatnonzero(stop > self.store.stop_count), maps=True)
            self.store.stop_count = stop
        if self.runs is None:
            self.runs = LabelRuns.empty(self.store)
        store, runs = self.store, self.runs
        kmaps = KernelMaps(done=runs.done, dist=store.dist, pred=store.pred, run=runs.run,
                           order=np.zeros(store.dist.shape[1], dtype=np.int32), count=store.count,
                           built=store.built)
        kactions = tables.kactions._replace(map_stop_count=store.stop_count)
        return ActionParts(maps=tables.maps, kactions=kactions, kmaps=kmaps, cell_room=tables.cell_room,
                           in_region=tables.in_region)

    def advance(self, moved: np.ndarray, relabelled: np.ndarray, objects: Collection[int],
                changed: Mapping[int, np.ndarray] | None = None) -> None:
        """Follow a change: ``moved`` the cells (numbers) that left or joined the graph, ``relabelled``
        those whose label changed, ``objects`` the uuids of the objects moved, added or removed,
        ``changed`` the cells (floor -> flat positions) whose category changed. Forgets the maps and label
        runs they may have altered (see the module)."""
        if self.tables is None:
            return
        for floor, cells in (changed or {}).items():
            self._sight.setdefault(floor, []).append(cells)
        touched = self._families_touching(moved)
        # A cell that left or joined the graph can change what an object of its room is visible from
        # (the visible reach model): those objects' targets are made anew too, not only the moved ones'.
        near = {_object_uuid(f.action) for f, hit in zip(self.tables.families, touched)
                if hit and f.action.kind == MAP_OBJECT}
        self._renew(set(objects) | near, touched)
        self.forget(np.flatnonzero(self._families_touching(relabelled)), maps=False)

    def _renew(self, objects: set[int], touched: np.ndarray | None = None) -> None:
        """Give ``objects`` (uuids) new targets at the next :meth:`parts` and forget their families' maps,
        with those of ``touched`` (a bool per family)."""
        assert self.tables is not None
        self._objects |= objects
        touched = np.zeros(len(self.tables.families), bool) if touched is None else touched
        for k, family in enumerate(self.tables.families):
            if family.action.kind == MAP_OBJECT and family.action.entity in self._objects:
                touched[k] = True
        self.forget(np.flatnonzero(touched), maps=True)

    def _sight_changes(self, problem: PlanningProblem) -> None:
        """The objects whose lines of sight the category changes since the last :meth:`parts` may have
        blocked or opened (any room: a wall-side object is seen across a door), renewed; the problem gives
        the reach radius and model this needs."""
        if not self._sight:
            return
        changed = {floor: np.concatenate(cells) for floor, cells in self._sight.items()}
        self._sight.clear()
        building = problem.building
        self._renew({obj.uuid for obj in building.objects()
                     if sight_may_change(building, obj, changed, problem.reach_radius_m,
                                         str(problem.reach_model))})

    def forget(self, families: np.ndarray, maps: bool) -> None:
        """Clear the label runs of ``families`` (indices) and, if ``maps``, their maps too, where they were
        written; the next search that needs them builds them again."""
        if self.store is None or not families.size:
            return
        self.counts["maps_forgotten" if maps else "runs_forgotten"] += len(families)
        arrays = [self.runs.run] if self.runs is not None else []
        if maps:
            arrays += [self.store.dist, self.store.pred]
        for k in families.tolist():
            for lo, hi in self._written(k):
                for array in arrays:
                    array[k, lo:hi] = 0
            if self.runs is not None:
                self.runs.done[k] = 0
            if maps:
                self.store.built[k] = 0
                self.store.count[k] = 0

    def _written(self, k: int) -> list[tuple[int, int]]:
        """The local index ranges of the cells family ``k``'s map may have written: its room's block and
        its targets, or its whole floor."""
        assert self.tables is not None and self._spans is not None
        family = self.tables.families[k]
        graph = self.candidates
        floor_lo = int(graph.floor_offset[family.action.floor])
        if family.stop_room < 0 or self._spans[family.stop_room, 0] < 0:
            return [(0, int(graph.floor_offset[family.action.floor + 1]) - floor_lo)]
        first, last = (int(v) - floor_lo for v in self._spans[family.stop_room])
        local = family.sources - floor_lo
        return [(first, last)] + [(c, c + 1) for c in local[(local < first) | (local >= last)].tolist()]

    def _families_touching(self, cells: np.ndarray) -> np.ndarray:
        """``(M,)`` bool: the families whose map's cells (room or floor, and targets) hold some of
        ``cells``."""
        assert self.tables is not None
        touched = np.zeros(len(self.tables.families), dtype=bool)
        if not cells.size:
            return touched
        rooms = np.zeros(self.tables.num_rooms + 1, dtype=bool)
        rooms[self.tables.cell_room[cells].astype(np.int64)] = True  # -1: the last slot, no room
        floors = np.zeros(self.candidates.shape[0], dtype=bool)
        floors[self.candidates.cell_floor[cells]] = True
        marked = np.zeros(self.candidates.num_cells, dtype=bool)
        marked[cells] = True
        for k, family in enumerate(self.tables.families):
            where = rooms[family.stop_room] if family.stop_room >= 0 else floors[family.action.floor]
            # An object's targets lie in its room; a door's in the next room, a stairs' at a portal.
            beyond = family.action.kind != MAP_OBJECT and bool(marked[family.sources].any())
            touched[k] = bool(where) or beyond
        return touched

    def _refresh_objects(self, problem: PlanningProblem) -> None:
        """The families of the changed objects anew (targets, room, floor) in place; an object that has
        none yet appends one, and the maps start afresh."""
        assert self.tables is not None
        tables, building = self.tables, problem.building
        rooms = list(building.rooms())
        where = {room.id: r for r, room in enumerate(rooms)}
        families = list(tables.families)
        index = {f.action.entity: k for k, f in enumerate(families) if f.action.kind == MAP_OBJECT}
        for uuid in sorted(self._objects):
            family = None
            if building.has_object(uuid):
                obj = building.object(uuid=uuid)
                family = object_family(problem, self.candidates, rooms, where[obj.room_id], obj)
            if uuid in index:  # a removed object keeps its family, with no target left
                old = families[index[uuid]]
                families[index[uuid]] = family or type(old)(old.action, old.sources[:0], old.stop_room,
                                                            old.from_room)
            elif family is not None:
                families.append(family)
        self._objects.clear()
        self.counts["objects"] += 1
        self.tables = action_tables(families, tables.cell_room, rooms, self.candidates.shape[0])
        if len(families) != len(tables.families):
            self.store = None


def _room_spans(cell_room: np.ndarray, num_rooms: int) -> np.ndarray:
    """``(R, 2)`` per room index the first and last + 1 cell of its block in the numbering (cells are
    numbered room by room within a floor, :mod:`sgplan.planning.cells`), ``(-1, -1)`` for a room whose cells
    are not one block (a staircase drawn on two floors) or that has none."""
    spans = np.full((num_rooms, 2), -1, dtype=np.int64)
    if not cell_room.size:
        return spans
    starts = np.concatenate([[0], np.flatnonzero(np.diff(cell_room)) + 1])
    ends = np.concatenate([starts[1:], [cell_room.size]])
    values = cell_room[starts].astype(np.int64)
    blocks = np.bincount(values[values >= 0], minlength=num_rooms)
    for value, first, last in zip(values.tolist(), starts.tolist(), ends.tolist()):
        if value >= 0 and blocks[value] == 1:
            spans[value] = (first, last)
    return spans


def with_other_labels(actions: RunActions) -> RunActions:
    """``actions`` for the same numbering and building with other labels (another mission's): the tables
    and maps shared, the label runs anew."""
    other = RunActions(actions.candidates)
    other.tables, other.store, other._spans = actions.tables, actions.store, actions._spans
    other._objects = set(actions._objects)
    other._sight = {floor: list(cells) for floor, cells in actions._sight.items()}
    return other


def _object_uuid(action: ActionMap) -> int:
    """The uuid of an object action's object (``ActionMap.entity`` holds a uuid for ``MAP_OBJECT``)."""
    entity = action.entity
    assert isinstance(entity, int), entity
    return entity
