"""The hierarchical planning domain of one problem: cells, labels, automaton, composite actions, heuristics.

Levels (reference-algorithm.md §3, SYSTEM.md §3.7): 1 occupancy (8-connected steps and stairs),
2 object (from a cell where some object is within reach: go to the reach region of another object of the
same room), 3 room (from a cell of a non-staircase room: go through the door cells into a connected
non-staircase room), 4 floor (from any cell: walk to this floor's stairs portal and take the stairs).
The anchor (level 0) is the union. A state belongs to level 2 iff its cell lies in an object's reach
region, and to levels 1, 3, 4 and the anchor always (every traversable cell is in a room).

Every composite action follows an EXACT shortest path over the same cells (multi-source Dijkstra from the
action's target cells, built lazily inside the search the first time the action is needed): over the
floor for floor actions, over the cells of the action's room for object and room actions (their paths
never leave the room they start in, except for a room action's final door cell), and advances the
automaton over every cell of that path after the current one. So each composite action is exactly a
sequence of occupancy moves, and the optimum over the product graph is unchanged by adding them. If the
automaton accepts part-way along the path, the action stops there (a shorter sequence of moves).
"""

from __future__ import annotations

import hashlib
import time
from collections import namedtuple
from collections.abc import Hashable
from dataclasses import dataclass, field
from functools import partial
from typing import Protocol, runtime_checkable

import numpy as np

from sgplan.errors import PlanningError
from sgplan.planning._dijkstra import PRED_NONE, PRED_SOURCE, PRED_STAIRS, PRED_STEP, next_cell
from sgplan.planning._memory import sparse_zeros
from sgplan.planning.cells import CellGraph, build_cell_graph
from sgplan.planning.llm_heuristic import LlmHeuristic, build_llm_heuristic
from sgplan.planning.ltl_heuristic import (
    LtlHeuristic,
    build_ltl_heuristic,
    label_boundary,
    label_fields,
    reachable_states,
)
from sgplan.planning.problem import PlanningProblem
from sgplan.planning.shared import shared_part
from sgplan.scene.model import CatCode, Room
from sgplan.scene.reach import object_reach_cells

# Arrays handed to the compiled search, grouped by role (numba accepts named tuples of arrays).
KernelGraph = namedtuple(
    "KernelGraph",
    "cell_at cell_pos step_offset step_cost stairs_first stairs_from stairs_to stairs_cost floor_offset "
    "cell_floor cell_label cell_room in_object_region centre_x centre_y centre_z",
)
KernelActions = namedtuple(
    "KernelActions",
    "room_obj_ptr room_obj_map room_room_ptr room_room_map floor_up_map floor_down_map map_floor "
    "map_src_ptr map_src map_stop_room map_stop_count map_exit_cell map_exit_cost",
)
KernelMaps = namedtuple("KernelMaps", "done dist pred run order count built")
"""Composite action maps: ``dist``, ``pred (M, n)``, ``count``, ``built (M,)`` the shortest-path
fields, shared by the problems of a session (:class:`MapStore`); ``run (M, n)`` the label runs over them
and ``done (M,)`` uint8 (map and runs ready), shared by the problems with the same cell labels
(:class:`LabelRuns`); ``order (n,)`` scratch."""
KernelLogic = namedtuple(
    "KernelLogic",
    "trans accepting dead idempotent hmap q_row h_ready h_dist h_unit h_ptr h_label h_add llm_sum llm_target "
    "llm_valid",
)

MAP_OBJECT, MAP_ROOM, MAP_FLOOR_UP, MAP_FLOOR_DOWN = 0, 1, 2, 3


@runtime_checkable
class KeptParts(Protocol):
    """Per-cell parts of a problem's current grid and labels that its ``shared`` parts keep up to date
    across changes of the building (a run's: :class:`sgplan.execution.parts.RunParts`), served to the
    domain instead of being computed for the problem. A session's
    :class:`~sgplan.planning.shared.SharedParts` share parts by key only and serve none of these."""

    def cell_labels(self, grid: Hashable, graph: CellGraph, labels: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
        """``(label_masks, cell_label)`` of the label raster ``labels`` over ``graph``'s cells, as
        :func:`build_domain` compacts them."""

    def reachable(self, grid: Hashable, graph: CellGraph, start_cell: int, avoid: np.ndarray) -> np.ndarray:
        """``(N,)`` bool: the cells of ``graph`` reachable from ``start_cell``. It may leave out what is
        reachable only through cells of the bitmasks ``avoid`` (labels every move onto which ends the
        mission: the search never stands there)."""

    def label_boundary(self, grid: Hashable, graph: CellGraph) -> np.ndarray:
        """:func:`~sgplan.planning.ltl_heuristic.label_boundary` of ``graph`` and the labels served by
        :meth:`cell_labels`."""

    def label_fields(self, grid: Hashable, graph: CellGraph, masks: np.ndarray, unit_m: float,
                     avoid: np.ndarray) -> np.ndarray | float:
        """The ``(N, F)`` distance fields (h_LTL's, :func:`~sgplan.planning.ltl_heuristic.label_fields`) of
        the whole regions of the label bitmasks ``masks``; they may leave out of the graph the cells of the
        bitmasks ``avoid`` (labels every move onto which ends the mission)."""

    def action_parts(self, problem: PlanningProblem, graph: CellGraph, cell_label: np.ndarray,
                     reachable: np.ndarray) -> ActionParts:
        """The composite action parts of ``problem`` (:func:`_action_parts`: tables, maps, label runs)."""


def _kept_parts(problem: PlanningProblem) -> KeptParts | None:
    """The problem's parts as :class:`KeptParts`, if they keep them; else ``None`` (the domain computes
    them, sharing with a session what depends on the building only)."""
    return problem.shared if isinstance(problem.shared, KeptParts) else None


@dataclass(frozen=True)
class ActionMap:
    """One composite action family: shortest paths to its target cells from anywhere on ``floor`` (floor
    actions) or in the family's room (object and room actions, paths within the room).

    ``kind`` is one of MAP_OBJECT / MAP_ROOM / MAP_FLOOR_UP / MAP_FLOOR_DOWN; ``entity`` the object uuid,
    the ``(room uuid, neighbour room uuid)`` pair, or the floor index.
    """

    kind: int
    entity: object
    floor: int


@dataclass(eq=False)
class PlanningDomain:
    """Precomputed, search-ready data of a :class:`PlanningProblem`.

    Attributes
    ----------
    graph:
        the cell graph.
    cell_label:
        ``(N,)`` compact label id per cell; ``label_masks[id]`` is the proposition bitmask.
    trans:
        ``(Q, L)`` next automaton state per compact label.
    start_cell, q_start:
        the start product state (q_start per the profile).
    ltl, llm:
        heuristics (``llm`` built only when the problem carries guidance).
    maps:
        the composite action families, indexed like the kernel's map arrays (none below level 2).
    max_level:
        the highest planning level this domain serves: below 2 (the A* setup) the composite action
        tables are not built, and the kernel gets placeholders (:func:`_no_actions`);
        :meth:`ensure_level` builds them when a later plan needs them.
    precompute_s:
        seconds spent building this domain, including :meth:`build_actions` once it ran.
    timings:
        seconds per part of :func:`build_domain` (cells, labels, reachable, ltl, action_tables; the
        benchmarks print them).
    """

    graph: CellGraph
    cell_label: np.ndarray
    label_masks: np.ndarray
    trans: np.ndarray
    accepting: np.ndarray
    start_cell: int
    q_start: int
    ltl: LtlHeuristic
    llm: LlmHeuristic | None
    room_uuids: list[int]
    maps: list[ActionMap]
    kgraph: KernelGraph
    kactions: KernelActions
    kmaps: KernelMaps
    klogic: KernelLogic
    precompute_s: float
    max_level: int = 4
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def num_states(self) -> int:
        return int(self.trans.shape[0])

    def action_cells(self, k: int, start: int, end: int) -> list[int]:
        """The cells (after ``start``, up to ``end`` inclusive) of composite action family ``k`` taken from
        cell ``start`` and ending at ``end``: the stored shortest path, plus the stairs for floor actions.

        Raises
        ------
        PlanningError
            if the action's path from ``start`` does not pass through ``end`` (an internal error).
        """
        lo = int(self.graph.floor_offset[self.kactions.map_floor[k]])
        pred = self.kmaps.pred[k]
        cells: list[int] = []
        x = start
        while x != end:
            p = int(pred[x - lo]) if 0 <= x - lo < pred.shape[0] else PRED_NONE
            if PRED_STEP <= p < PRED_STAIRS:
                x = int(next_cell(self.graph.cell_at, self.graph.cell_pos, self.graph.step_offset, x, p))
            else:
                x = int(self.kactions.map_exit_cell[k]) if p == PRED_SOURCE else -1
            if x < 0 or len(cells) > pred.shape[0]:
                raise PlanningError(
                    f"internal error: action {self.maps[k]} from cell {start} misses cell {end}"
                )
            cells.append(x)
        return cells

    def ensure_level(self, problem: PlanningProblem, max_level: int) -> None:
        """Make the domain serve planning levels up to ``max_level``: builds the composite action tables
        (adding the seconds to ``precompute_s``) if they were skipped and ``max_level >= 2``. ``problem``
        must be the one this domain was built for."""
        if max_level <= self.max_level or self.max_level >= 2:
            self.max_level = max(self.max_level, max_level)
            return
        t0 = time.perf_counter()
        reachable = self.graph.reachable(self.start_cell)
        parts = _action_parts(problem, self.graph, self.cell_label, reachable)
        self.maps, self.kactions, self.kmaps = parts.maps, parts.kactions, parts.kmaps
        self.kgraph = self.kgraph._replace(cell_room=parts.cell_room, in_object_region=parts.in_region)
        self.max_level = max_level
        self.precompute_s += time.perf_counter() - t0

    def release_map_fields(self) -> None:
        """Free the composite action maps' distances and label runs, keeping the move codes that
        :meth:`action_cells` follows: for a search whose remaining iterations read no map (the anchor
        alone on occupancy moves) and whose maps no other problem shares. The domain then serves level 1
        only (the maps' placeholders are empty); :meth:`ensure_level` builds fresh action parts for a
        later search with composite actions."""
        if self.max_level < 2:
            return
        maps = self.kmaps
        self.kmaps = maps._replace(dist=np.zeros((0, 0), dtype=maps.dist.dtype),
                                   run=np.zeros((0, 0), dtype=maps.run.dtype),
                                   order=np.zeros(0, dtype=maps.order.dtype))
        self.max_level = 1

    def build_actions(self) -> float:
        """Build every composite action map now instead of lazily during search; returns the seconds
        spent (also added to ``precompute_s``). Costs 1-3 s on the Gibson scenes; afterwards the first
        path comes after a handful of expansions, as in the authors' planner whose maps are prebuilt."""
        from sgplan.planning._search import build_all_maps

        t0 = time.perf_counter()
        build_all_maps(self.kgraph, self.kactions, self.kmaps)
        spent = time.perf_counter() - t0
        self.precompute_s += spent
        return spent


def domain_of(problem: PlanningProblem, max_level: int = 4) -> PlanningDomain:
    """The precomputed planning domain of ``problem`` for a plan using levels up to ``max_level``, built on
    first use and then kept on the problem (``problem.built_domain``) for every plan of it: built without
    the composite action tables when ``max_level < 2`` (the A* setup); a later call with a higher level
    adds them (:meth:`PlanningDomain.ensure_level`).

    Raises
    ------
    PlanningError
        ``status="invalid-start"`` or ``status="infeasible"``, see :func:`build_domain`.
    """
    built: PlanningDomain | None = problem.built_domain
    if built is None:
        built = build_domain(problem, max_level)
        problem.built_domain = built
    else:
        built.ensure_level(problem, max_level)
    return built


def build_domain(problem: PlanningProblem, max_level: int = 4) -> PlanningDomain:
    """Validate the start and precompute everything the search needs at planning levels up to
    ``max_level`` except the action maps (built lazily by the search); below level 2 the composite
    action tables are skipped (see ``PlanningDomain.max_level``).

    Raises
    ------
    PlanningError
        ``status="invalid-start"``: the start is outside the grid or not traversable (with why), or its
        label sends the automaton to a state from which nothing is accepted.
        ``status="infeasible"``: no path from the start can satisfy the mission (with which propositions
        or which automaton progress cannot be reached).
    """
    t0 = time.perf_counter()
    clock = _Clock()
    graph = shared_part(problem.shared, "cell_graph", problem.grid, lambda: build_cell_graph(problem.grid))
    clock.lap("cells")
    start_cell = _check_start(problem, graph)
    automaton = problem.automaton
    logic = _CellLogic.of(problem, graph)
    clock.lap("labels")
    q_start = _start_state(problem, logic, start_cell)

    avoid = logic.label_masks[_fatal_labels(logic.trans, logic.dead, automaton.initial)]
    kept = _kept_parts(problem)
    component = None if kept is None else kept.reachable(problem.grid, graph, start_cell, avoid)
    reachable = component if component is not None else graph.reachable(start_cell)
    clock.lap("reachable")
    boundary = kept.label_boundary(problem.grid, graph) if kept is not None else shared_part(
        problem.shared, "label_boundary", (problem.grid, _labelling_digest(logic.cell_label)),
        lambda: label_boundary(graph, logic.cell_label))
    fields = partial(_label_fields, problem, graph, logic.cell_label, logic.label_masks, reachable, avoid)
    ltl = build_ltl_heuristic(graph, logic.cell_label, logic.trans, logic.accepting, q_start, reachable,
                              fields=fields, start_cell=start_cell, boundary=boundary)
    del fields
    clock.lap("ltl")
    if not logic.accepting[q_start] and not np.isfinite(ltl.value(start_cell, q_start)):
        everywhere = reachable if component is None else graph.reachable(start_cell)  # the message's
        raise PlanningError(
            _infeasible_reason(problem, logic.label_masks[logic.cell_label], everywhere, q_start),
            status="infeasible",
        )

    room_uuids = [room.uuid for room in problem.building.rooms()]  # room index -> uuid, as cell_room
    parts = (_action_parts(problem, graph, logic.cell_label, reachable) if max_level >= 2
             else _no_actions(graph, len(room_uuids)))
    del reachable
    clock.lap("action_tables")

    llm = (
        build_llm_heuristic(problem.guidance, problem.building, room_uuids, automaton.num_states)
        if problem.guidance is not None
        else None
    )
    guide = llm if llm is not None else build_llm_heuristic({}, problem.building, room_uuids,
                                                            automaton.num_states)
    return PlanningDomain(
        graph=graph,
        cell_label=logic.cell_label,
        label_masks=logic.label_masks,
        trans=logic.trans,
        accepting=logic.accepting,
        start_cell=start_cell,
        q_start=q_start,
        ltl=ltl,
        llm=llm,
        room_uuids=room_uuids,
        maps=parts.maps,
        kgraph=_kernel_graph(graph, logic.cell_label, parts),
        kactions=parts.kactions,
        kmaps=parts.kmaps,
        klogic=_kernel_logic(logic, ltl, guide),
        precompute_s=time.perf_counter() - t0,
        max_level=max_level,
        timings=clock.laps,
    )


@dataclass(frozen=True)
class _CellLogic:
    """The automaton over the cells' labels: ``label_masks`` (compact label -> proposition bitmask),
    ``cell_label`` (per cell, its compact label), ``trans (Q, labels)`` the automaton table over compact
    labels, ``accepting`` and ``dead`` (no accepting state reachable) per automaton state."""

    label_masks: np.ndarray
    cell_label: np.ndarray
    trans: np.ndarray
    accepting: np.ndarray
    dead: np.ndarray

    @classmethod
    def of(cls, problem: PlanningProblem, graph: CellGraph) -> _CellLogic:
        """Read the problem's label raster at every cell and compact it to the labels that occur (or take
        the compact labels the problem's parts keep: :meth:`KeptParts.cell_labels`, a run's)."""
        automaton = problem.automaton
        kept = _kept_parts(problem)
        compacted = None if kept is None else kept.cell_labels(problem.grid, graph, problem.labels)
        label_masks, cell_label = compacted if compacted is not None else _labelling(graph, problem.labels,
                                                                                      automaton)
        if label_masks.size and int(label_masks.max()) >= automaton.num_labels:
            raise PlanningError(
                f"label raster holds bitmask {int(label_masks.max())} but the automaton has only "
                f"{len(automaton.aps)} propositions ({', '.join(automaton.aps)})"
            )
        trans = np.ascontiguousarray(automaton.table[:, label_masks], dtype=np.int32)
        accepting = np.asarray(automaton.accepting, dtype=bool)
        dead = _dead_states(np.asarray(automaton.table), accepting)
        return cls(label_masks, cell_label, trans, accepting, dead)


def _start_state(problem: PlanningProblem, logic: _CellLogic, start_cell: int) -> int:
    """The automaton state at the start: the problem's ``start_state`` when it resumes a mission
    part-way, else the start cell's label read under ``ltlf`` (not under ``authors``); refused when no
    accepting state can be reached from it."""
    automaton = problem.automaton
    start_mask = int(logic.label_masks[logic.cell_label[start_cell]])
    if problem.start_state is not None:
        q_start = int(problem.start_state)
        if logic.dead[q_start]:
            raise PlanningError(f"automaton state {q_start} at the start can no longer accept: the "
                                "mission is violated", status="infeasible")
    elif problem.profile == "ltlf":
        q_start = int(automaton.table[automaton.initial, start_mask])
        if logic.dead[q_start]:
            true_aps = [problem.ap_name(i) for i in range(len(automaton.aps)) if start_mask >> i & 1]
            raise PlanningError(
                f"start {problem.start} violates the mission: with {_listing(true_aps)} true there the "
                "automaton can no longer accept; start elsewhere",
                status="invalid-start",
            )
    else:
        q_start = int(automaton.initial)
    if logic.dead[q_start]:
        raise PlanningError("the mission automaton accepts no word at all", status="infeasible")
    return q_start


def _kernel_logic(logic: _CellLogic, ltl: LtlHeuristic, guide: LlmHeuristic) -> KernelLogic:
    """The automaton and heuristic arrays the compiled search reads."""
    trans = logic.trans
    idempotent = bool(np.all(trans[trans, np.arange(trans.shape[1])[None, :]] == trans))
    return KernelLogic(
        trans=trans,
        accepting=logic.accepting,
        dead=logic.dead,
        idempotent=np.array([idempotent]),
        hmap=ltl.hmap,
        q_row=ltl.q_row,
        h_ready=ltl.ready,
        h_dist=ltl.dist,
        h_unit=ltl.unit_m,
        h_ptr=ltl.term_ptr,
        h_label=ltl.term_label,
        h_add=ltl.term_add,
        llm_sum=guide.leg_sum,
        llm_target=guide.target,
        llm_valid=guide.has_target,
    )


def _kernel_graph(graph: CellGraph, cell_label: np.ndarray, parts: ActionParts) -> KernelGraph:
    """The cell graph's arrays the compiled search reads, with the cells' labels, rooms and object
    regions."""
    return KernelGraph(
        cell_at=graph.cell_at,
        cell_pos=graph.cell_pos,
        step_offset=graph.step_offset,
        step_cost=graph.step_cost,
        stairs_first=graph.stairs_first,
        stairs_from=graph.stairs_from,
        stairs_to=graph.stairs_to,
        stairs_cost=graph.stairs_cost,
        floor_offset=graph.floor_offset,
        cell_floor=graph.cell_floor,
        cell_label=cell_label,
        cell_room=parts.cell_room,
        in_object_region=parts.in_region,
        centre_x=graph.centre_tables[0],
        centre_y=graph.centre_tables[1],
        centre_z=graph.centre_tables[2],
    )


def _labelling_digest(cell_label: np.ndarray) -> bytes:
    """A digest of the cells' compact labels: the key part of what depends on which cells share a label
    (label runs, the label boundary), so that problems with the same labelling share it."""
    return hashlib.blake2b(np.ascontiguousarray(cell_label).data, digest_size=16).digest()  # no copy


ActionParts = namedtuple("ActionParts", "maps kactions kmaps cell_room in_region")
"""What :func:`build_domain` hands the kernel for the composite actions: the families, their tables,
their maps (this problem's view of the shared store), and the per-cell room index / object-region flag."""


def _action_parts(
    problem: PlanningProblem, graph: CellGraph, cell_label: np.ndarray, reachable: np.ndarray
) -> ActionParts:
    """The composite action tables of the problem's grid (shared by a session), the map store of the
    start's connected component and the label runs of this labelling (both filled by the search); or the
    parts kept by the problem's parts when they keep them across changes (:meth:`KeptParts.action_parts`,
    a run's)."""
    kept = _kept_parts(problem)
    if kept is not None:
        return kept.action_parts(problem, graph, cell_label, reachable)
    reach = (problem.reach_radius_m, problem.reach_model)
    tables = shared_part(problem.shared, "action_tables", (problem.grid, *reach),
                         lambda: _action_tables(problem, graph))
    # The maps' early stops depend on which cells the search can stand on: the start's component, named
    # by its lowest cell.
    component = int(np.argmax(reachable))
    store = shared_part(problem.shared, "action_maps", (problem.grid, *reach, component),
                        lambda: MapStore.empty(tables, graph, reachable))
    # Label runs follow which cells share a label: shared by the problems with the same cell labels.
    runs = shared_part(problem.shared, "label_runs",
                       (problem.grid, *reach, component, _labelling_digest(cell_label)),
                       lambda: LabelRuns.empty(store))
    kmaps = KernelMaps(
        done=runs.done,
        dist=store.dist,
        pred=store.pred,
        run=runs.run,
        order=np.zeros(store.dist.shape[1], dtype=np.int32),
        count=store.count,
        built=store.built,
    )
    return ActionParts(maps=tables.maps, kactions=tables.kactions._replace(map_stop_count=store.stop_count),
                       kmaps=kmaps, cell_room=tables.cell_room, in_region=tables.in_region)


def _no_actions(graph: CellGraph, num_rooms: int) -> ActionParts:
    """Placeholders for a search without composite actions (max level 1), typed as the kernel expects:
    no families (empty tables; per-room pointers of ``num_rooms`` empty rooms, no floor maps) and
    ``(0, 0)`` maps. ``cell_room`` and ``in_region`` are lazily committed zero arrays of one entry per
    cell (no memory): a level-1 search without LLM queues never reads them (every setup with LLM queues
    has max level 4)."""
    floors = graph.shape[0]
    none32, none64 = np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.int64)
    kactions = KernelActions(
        room_obj_ptr=np.zeros(num_rooms + 1, dtype=np.int64),
        room_obj_map=none32,
        room_room_ptr=np.zeros(num_rooms + 1, dtype=np.int64),
        room_room_map=none32,
        floor_up_map=np.full(floors, -1, dtype=np.int32),
        floor_down_map=np.full(floors, -1, dtype=np.int32),
        map_floor=none32,
        map_src_ptr=np.zeros(1, dtype=np.int64),
        map_src=none64,
        map_stop_room=none32,
        map_stop_count=none64,
        map_exit_cell=none64,
        map_exit_cost=np.zeros(0, dtype=np.float64),
    )
    kmaps = KernelMaps(
        done=np.zeros(0, dtype=np.uint8),
        dist=np.zeros((0, 0), dtype=np.float64),
        pred=np.zeros((0, 0), dtype=np.uint8),
        run=np.zeros((0, 0), dtype=np.int32),
        order=none32,
        count=none64,
        built=np.zeros(0, dtype=np.uint8),
    )
    return ActionParts(maps=[], kactions=kactions, kmaps=kmaps,
                       cell_room=sparse_zeros(graph.num_cells, room_index_dtype(num_rooms)),
                       in_region=sparse_zeros(graph.num_cells, np.bool_))


class _Clock:
    """Seconds per named part of :func:`build_domain` (``PlanningDomain.timings``)."""

    def __init__(self) -> None:
        self.laps: dict[str, float] = {}
        self._last = time.perf_counter()

    def lap(self, name: str) -> None:
        now = time.perf_counter()
        self.laps[name] = now - self._last
        self._last = now


def compact_labels(masks: np.ndarray, num_labels: int) -> tuple[np.ndarray, np.ndarray]:
    """``(label_masks, cell_label)``: the distinct bitmasks (ascending, int64) and each cell's index into
    them (:func:`label_index_dtype`: a byte a cell on most missions). A lookup table when the automaton's
    label space is small, else a sort."""
    if num_labels <= 1 << 22:
        present = np.zeros(num_labels, dtype=np.bool_)
        present[masks] = True
        label_masks = np.flatnonzero(present)
        lut = np.zeros(num_labels, dtype=label_index_dtype(len(label_masks)))
        lut[label_masks] = np.arange(len(label_masks))
        return label_masks.astype(np.int64), lut[masks]
    label_masks, cell_label = np.unique(masks, return_inverse=True)
    return label_masks.astype(np.int64), cell_label.astype(label_index_dtype(len(label_masks)))


def label_index_dtype(count: int) -> type[np.integer]:
    """The dtype of a cell's compact label id among ``count`` distinct labels: uint8 up to 256, uint16 up
    to 65,536, else int32 (a search reads it once per successor, so it is kept small, not widened)."""
    return np.uint8 if count <= 1 << 8 else np.uint16 if count <= 1 << 16 else np.int32


def room_index_dtype(num_rooms: int) -> type[np.integer]:
    """The dtype of a cell's room index (-1: no room) among ``num_rooms`` rooms: int16 when they fit, else
    int32."""
    return np.int16 if num_rooms < 1 << 15 else np.int32


def _listing(items: list[str]) -> str:
    return ", ".join(items) if items else "no proposition"


def _dead_states(table: np.ndarray, accepting: np.ndarray) -> np.ndarray:
    """``(Q,)`` bool: states from which no label sequence reaches an accepting state."""
    alive = accepting.copy()
    while True:
        grown = alive | alive[table].any(axis=1)
        if (grown == alive).all():
            return ~alive
        alive = grown


def _check_start(problem: PlanningProblem, graph: CellGraph) -> int:
    """The start's cell index, or PlanningError(status="invalid-start") saying why it cannot be used."""
    row, col, floor = problem.start
    floors, rows, cols = graph.shape
    where = f"start (row {row}, col {col}, floor {floor})"
    if not (0 <= floor < floors and 0 <= row < rows and 0 <= col < cols):
        raise PlanningError(
            f"{where} lies outside the grid ({floors} floors of {rows} x {cols} cells)",
            status="invalid-start",
        )
    cell = graph.cell_id(row, col, floor)
    if cell >= 0:
        return cell
    room_id = int(problem.grid.room_map[floor, row, col])
    cat = problem.building.floors[floor].cat_map if floor < problem.building.num_floors else None
    if room_id <= 0:
        why = "lies in no room"
    elif cat is not None and cat.shape == (rows, cols) and cat[row, col] != CatCode.GROUND:
        value = int(cat[row, col])
        what = CatCode(value).name.lower() if value <= 0 else f"object id {value}"
        why = f"is not free ground ({what})"
    else:
        why = "is inside the inflated obstacle region" + _clearance(problem, cat, row, col)
    raise PlanningError(f"{where} {why}; choose a free cell", status="invalid-start")


def _clearance(problem: PlanningProblem, cat: np.ndarray | None, row: int, col: int) -> str:
    """`` (nearest obstacle X m away, robot radius R m)`` from the category map, when available."""
    radius = problem.grid.robot_radius_m
    if cat is None or radius <= 0:
        return ""
    res_x, res_y = problem.grid.resolution_m
    pad_r, pad_c = int(np.ceil(radius / res_x)) + 2, int(np.ceil(radius / res_y)) + 2
    r0, c0 = max(row - pad_r, 0), max(col - pad_c, 0)
    window = cat[r0 : row + pad_r + 1, c0 : col + pad_c + 1]
    blocked = (window != CatCode.GROUND) & (window != CatCode.STAIRS_UP) & (window != CatCode.STAIRS_DOWN)
    rr, cc = np.nonzero(blocked)
    if rr.size == 0:
        return f" (robot radius {radius:g} m)"
    nearest = float(np.min(np.hypot((rr + r0 - row) * res_x, (cc + c0 - col) * res_y)))
    return f": the nearest obstacle is {nearest:.3f} m away, less than the robot radius {radius:g} m"


def _infeasible_reason(
    problem: PlanningProblem, masks: np.ndarray, reachable: np.ndarray, q_start: int
) -> str:
    """Which propositions can never hold on a reachable cell, or which automaton progress is blocked."""
    seen = np.bitwise_or.reduce(masks[reachable]) if reachable.any() else 0
    missing = [problem.ap_name(i) for i in range(len(problem.automaton.aps)) if not seen >> i & 1]
    where = f"no path from start {problem.start} satisfies the mission"
    if missing:
        return f"{where}: {_listing(missing)} never holds on a cell reachable from the start"
    return (
        f"{where}: every proposition holds somewhere reachable, but no order of visits leads the automaton "
        f"from state {q_start} to acceptance (a required place is reachable only through a forbidden one, "
        "or two required propositions never hold together)"
    )


@dataclass(eq=False)
class ActionTables:
    """The composite action families of a grid and reach radius, and what the kernel needs to choose
    them (no mission, no start: shared by a session's problems).

    ``kactions.map_stop_count`` is a placeholder: the stop counts follow the start's component
    (:class:`MapStore`)."""

    families: list[Family]
    kactions: KernelActions
    in_region: np.ndarray
    cell_room: np.ndarray
    room_uuids: list[int]
    num_rooms: int

    @property
    def maps(self) -> list[ActionMap]:
        return [family.action for family in self.families]

    def nbytes(self) -> int:
        return self.in_region.nbytes + self.cell_room.nbytes + sum(a.nbytes for a in self.kactions)


@dataclass(eq=False)
class MapStore:
    """The shortest-path fields of every action family of an :class:`ActionTables`, for starts in one
    connected component, filled by the search the first time a family is needed
    (:func:`sgplan.planning._search.build_map`) and then reused by every later problem of the session.

    ``dist`` / ``pred`` ``(M, n)`` float64 / uint8 move codes (lazily committed: a family costs 9 bytes
    per cell its Dijkstra touched), ``count (M,)`` cells settled, ``built (M,)`` uint8 1 once the
    family's Dijkstra ran (it runs once per store)."""

    stop_count: np.ndarray
    dist: np.ndarray
    pred: np.ndarray
    count: np.ndarray
    built: np.ndarray

    @classmethod
    def empty(cls, tables: ActionTables, graph: CellGraph, reachable: np.ndarray) -> MapStore:
        n_max = int(np.diff(graph.floor_offset).max()) if graph.num_cells else 0
        m = len(tables.maps)
        return cls(
            stop_count=stop_counts(tables.cell_room, reachable, tables.num_rooms,
                                   tables.kactions.map_stop_room),
            dist=sparse_zeros((m, n_max), np.float64),
            pred=sparse_zeros((m, n_max), np.uint8),
            count=np.zeros(m, dtype=np.int64),
            built=np.zeros(m, dtype=np.uint8),
        )

    def nbytes(self) -> int:
        """Bytes committed, estimated from the cells settled (the few cells reached but not settled at
        an early stop, and page rounding, are not counted)."""
        return int(self.count.sum()) * 9 + self.count.nbytes + self.stop_count.nbytes + self.built.nbytes


@dataclass(eq=False)
class LabelRuns:
    """The label runs (:func:`sgplan.planning._dijkstra.label_runs`) over the maps of a :class:`MapStore`
    for one cell labelling: ``run (M, n)`` lazily committed, ``done (M,)`` uint8 1 once family k's map
    and runs are ready (the kernel's ``KernelMaps.done``)."""

    store: MapStore
    run: np.ndarray
    done: np.ndarray

    @classmethod
    def empty(cls, store: MapStore) -> LabelRuns:
        return cls(store=store, run=sparse_zeros(store.dist.shape, np.int32),
                   done=np.zeros(store.count.shape[0], dtype=np.uint8))

    def nbytes(self) -> int:
        """Bytes committed, estimated as 4 per settled cell of the ready maps (the store's own bytes are
        counted with the store)."""
        return int(self.store.count[self.done.astype(bool)].sum()) * 4 + self.done.nbytes


def _labelling(graph: CellGraph, labels: np.ndarray, automaton) -> tuple[np.ndarray, np.ndarray]:
    """``(label_masks, cell_label)`` of the label raster ``labels`` over the cells of ``graph``
    (:func:`compact_labels`)."""
    masks = graph.gather(labels)
    if masks.size and int(masks.min()) < 0:
        raise PlanningError(f"label raster holds a negative bitmask ({int(masks.min())})")
    return compact_labels(masks, max(automaton.num_labels, int(masks.max(initial=0)) + 1))


def _fatal_labels(trans: np.ndarray, dead: np.ndarray, initial: int) -> np.ndarray:
    """The compact labels that take every live state reachable from ``initial`` to a dead one (a room the
    mission forbids throughout): a move onto them always ends the mission."""
    live = np.flatnonzero(reachable_states(trans, initial) & ~dead)
    if not live.size:
        return np.zeros(0, dtype=np.int64)
    return np.flatnonzero(dead[trans[live]].all(axis=0))


def _label_fields(problem: PlanningProblem, graph: CellGraph, cell_label: np.ndarray, label_masks: np.ndarray,
                  reachable: np.ndarray, avoid: np.ndarray, labels: np.ndarray, unit_m: float
                  ) -> np.ndarray | float:
    """The distance fields of the regions of compact labels ``labels`` (h_LTL's ``fields``): kept by the
    problem's parts when they keep them by label (:meth:`KeptParts.label_fields`; they may leave out
    the cells of the bitmasks ``avoid``, which no move of the search enters: :func:`_fatal_labels`), else
    one
    :func:`~sgplan.planning.ltl_heuristic.unit_field` per region within ``reachable``, each from the
    session's parts when there are some (:meth:`SharedParts.distance_field`)."""
    kept = _kept_parts(problem)
    if kept is not None:
        return kept.label_fields(problem.grid, graph, label_masks[labels], unit_m, avoid)
    shared = problem.shared
    if shared is None:
        return label_fields(graph, cell_label, reachable, labels, unit_m)
    return label_fields(graph, cell_label, reachable, labels, unit_m,
                        distances=lambda cells, unit: shared.distance_field(problem.grid, graph, cells, unit))


def _action_tables(problem: PlanningProblem, graph: CellGraph) -> ActionTables:
    """The composite action families of the problem's grid and reach radius, and their per-room /
    per-floor tables for the kernel."""
    rooms = list(problem.building.rooms())
    return action_tables(action_families(problem, graph, rooms), room_indices(problem, graph, rooms), rooms,
                         graph.shape[0])


def room_indices(problem: PlanningProblem, graph: CellGraph, rooms: list) -> np.ndarray:
    """``(N,)``: the index in ``rooms`` of the room holding each cell of ``graph`` (-1: none)."""
    room_lut = np.full(max([room.id for room in rooms], default=0) + 2, -1, dtype=np.int32)
    for i, room in enumerate(rooms):
        room_lut[room.id] = i
    room_ids = graph.gather(problem.grid.room_map)
    inside = (room_ids > 0) & (room_ids < len(room_lut) - 1)
    cell_room = np.full(graph.num_cells, -1, dtype=room_index_dtype(len(rooms)))
    cell_room[inside] = room_lut[room_ids[inside]]
    return cell_room


@dataclass(frozen=True)
class Family:
    """One composite action family as the tables hold it: the action, its target cells (cell indices,
    ascending), the room (index) its paths keep to (-1: its floor), the room whose cells may take it (-1:
    any cell of the floor, a floor action), and a floor action's far portal and stairs cost."""

    action: ActionMap
    sources: np.ndarray
    stop_room: int
    from_room: int
    exit_cell: int = -1
    exit_cost: float = 0.0


def object_family(problem: PlanningProblem, graph: CellGraph, rooms: list[Room], r: int, obj,
                  in_room: np.ndarray | None = None) -> Family | None:
    """The family of reaching ``obj`` from the cells of room ``rooms[r]`` (its room), ``None`` when no cell
    of ``graph`` reaches it; ``in_room``: the room's traversable cells (:func:`_room_cells`), computed when
    ``None``."""
    room = rooms[r]
    if in_room is None:
        in_room = _room_cells(problem, room)
    cells = _reach_region(problem, graph, room, obj, in_room)
    if not cells.size:
        return None
    return Family(ActionMap(MAP_OBJECT, obj.uuid, room.floor), cells.astype(np.int64),
                  -1 if room.is_staircase else r, r)


def action_families(problem: PlanningProblem, graph: CellGraph, rooms: list[Room]) -> list[Family]:
    """The composite action families over ``graph``: per room (in the order of ``rooms``) its objects' and
    its doors' into each connected room, then the stairs of each floor."""
    floors = graph.shape[0]
    room_index = {room.id: i for i, room in enumerate(rooms)}
    families: list[Family] = []
    for r, room in enumerate(rooms):
        if room.floor >= floors:
            continue
        in_room = _room_cells(problem, room) if room.objects else None  # once per room, not per object
        reached = (object_family(problem, graph, rooms, r, obj, in_room) for obj in room.objects.values())
        families += [family for family in reached if family is not None]
        if room.is_staircase:
            continue
        for other_id in room.connected_room_ids:
            other = room_index.get(other_id)
            doors = room.door_cells.get(other_id)
            if other is None or rooms[other].is_staircase or doors is None or len(doors) == 0:
                continue
            ids = _cell_ids(graph, room.floor, np.asarray(doors, dtype=np.int64).reshape(-1, 2))
            if ids.size:
                families.append(Family(ActionMap(MAP_ROOM, (room.uuid, rooms[other].uuid), room.floor),
                                       ids, r, r))
    for link in problem.grid.stairs:
        low = graph.cell_id(link.lower_cell[0], link.lower_cell[1], link.lower_floor)
        up = graph.cell_id(link.upper_cell[0], link.upper_cell[1], link.upper_floor)
        if low < 0 or up < 0:
            continue
        families.append(Family(ActionMap(MAP_FLOOR_UP, link.lower_floor, link.lower_floor),
                               np.array([low], dtype=np.int64), -1, -1, up, link.cost_m))
        families.append(Family(ActionMap(MAP_FLOOR_DOWN, link.upper_floor, link.upper_floor),
                               np.array([up], dtype=np.int64), -1, -1, low, link.cost_m))
    return families


def action_tables(families: list[Family], cell_room: np.ndarray, rooms: list, floors: int) -> ActionTables:
    """The kernel's tables of ``families`` (indexed in list order): per room the object and door families
    its cells may take, per floor the stairs families, the families' targets, rooms, floors and exits, and
    which cells lie in some object's reach."""
    room_obj: list[list[int]] = [[] for _ in rooms]
    room_room: list[list[int]] = [[] for _ in rooms]
    floor_up = np.full(floors, -1, dtype=np.int32)
    floor_down = np.full(floors, -1, dtype=np.int32)
    in_region = np.zeros(cell_room.shape[0], dtype=np.bool_)
    for k, family in enumerate(families):
        kind = family.action.kind
        if kind == MAP_OBJECT:
            room_obj[family.from_room].append(k)
            in_region[family.sources] = True
        elif kind == MAP_ROOM:
            room_room[family.from_room].append(k)
        else:
            (floor_up if kind == MAP_FLOOR_UP else floor_down)[family.action.floor] = k
    obj_ptr, obj_map = _csr(room_obj)
    room_ptr, room_map = _csr(room_room)
    src_ptr = np.zeros(len(families) + 1, dtype=np.int64)
    src_ptr[1:] = np.cumsum([len(f.sources) for f in families])
    map_src = np.concatenate([f.sources for f in families]) if families else np.zeros(0, dtype=np.int64)
    kactions = KernelActions(
        room_obj_ptr=obj_ptr,
        room_obj_map=obj_map,
        room_room_ptr=room_ptr,
        room_room_map=room_map,
        floor_up_map=floor_up,
        floor_down_map=floor_down,
        map_floor=np.array([f.action.floor for f in families], dtype=np.int32),
        map_src_ptr=src_ptr,
        map_src=map_src.astype(np.int64),
        map_stop_room=np.array([f.stop_room for f in families], dtype=np.int32),
        map_stop_count=np.zeros(len(families), dtype=np.int64),  # per component: MapStore.stop_count
        map_exit_cell=np.array([f.exit_cell for f in families], dtype=np.int64),
        map_exit_cost=np.array([f.exit_cost for f in families], dtype=np.float64),
    )
    return ActionTables(families=families, kactions=kactions, in_region=in_region, cell_room=cell_room,
                        room_uuids=[room.uuid for room in rooms], num_rooms=len(rooms))


def _csr(lists: list[list[int]]) -> tuple[np.ndarray, np.ndarray]:
    """Offsets and concatenation of ``lists`` (int64 offsets, int32 items)."""
    ptr = np.zeros(len(lists) + 1, dtype=np.int64)
    ptr[1:] = np.cumsum([len(x) for x in lists])
    flat = np.array([m for x in lists for m in x], dtype=np.int32)
    return ptr, flat


_CHUNK = 1 << 20


def stop_counts(
    cell_room: np.ndarray, reachable: np.ndarray, num_rooms: int, stop_rooms: np.ndarray
) -> np.ndarray:
    """``(M,)`` int64: for each action map, the cells of its stop room reachable from the start; 0 for
    maps without a stop room.

    A map's Dijkstra (confined to its room) stops once it has settled that many cells of the room: the
    search only ever stands on reachable cells, so it stops right after the last one it can serve.
    Counting every room cell instead ran it to exhaustion whenever part of the room is cut off (a pocket
    behind furniture). Room cells reachable from the start but not from the sources inside the room are
    never settled: the run then ends by exhaustion of the room, and those cells have no such action."""
    per_room = np.zeros(num_rooms, dtype=np.int64)
    for lo in range(0, cell_room.shape[0], _CHUNK):  # chunks: temporaries of a few MB, not 8 bytes a cell
        rooms = cell_room[lo : lo + _CHUNK][reachable[lo : lo + _CHUNK]]
        per_room += np.bincount(rooms[rooms >= 0], minlength=num_rooms)[:num_rooms]
    return np.where(stop_rooms >= 0, per_room[np.maximum(stop_rooms, 0)], 0).astype(np.int64)


def _cell_ids(graph: CellGraph, floor: int, cells: np.ndarray) -> np.ndarray:
    """Sorted unique cell indices of the traversable ``(row, col)`` cells among ``cells`` on ``floor``."""
    _, rows, cols = graph.shape
    inside = (cells[:, 0] >= 0) & (cells[:, 0] < rows) & (cells[:, 1] >= 0) & (cells[:, 1] < cols)
    ids = graph.cell_ids((floor * rows + cells[inside, 0]) * cols + cells[inside, 1])
    return np.unique(ids[ids >= 0])


def _room_cells(problem: PlanningProblem, room) -> np.ndarray:
    """``(rows, cols)`` bool: the traversable cells of ``room`` on its floor."""
    return (problem.grid.room_map[room.floor] == room.id) & problem.grid.traversable[room.floor]


def _reach_region(problem: PlanningProblem, graph: CellGraph, room, obj, in_room: np.ndarray) -> np.ndarray:
    """Cell indices of ``room`` from which ``obj`` is reached: the cells of its ``reach`` label at the
    problem's reach radius and model (:func:`sgplan.scene.reach.object_reach_cells`) among the room's
    traversable cells ``in_room``."""
    floor = problem.building.floors[room.floor]
    if not floor.has_maps:
        return np.zeros(0, dtype=np.int64)
    flat = object_reach_cells(floor, obj, problem.reach_radius_m, str(problem.reach_model), among=in_room)
    rows, cols = floor.shape
    ids = graph.cell_ids(room.floor * rows * cols + flat)
    return ids[ids >= 0]
