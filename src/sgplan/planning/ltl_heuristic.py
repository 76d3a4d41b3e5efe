"""h_LTL: a consistent lower bound on the cost to finish the mission from a product state (cell, q).

The paper's construction (eq. for g(l, q)) bounds the cost to go by the exact distance ``d_l(cell)`` to the
region of the next label ``l`` plus a cost to go ``G(l, q')`` computed between label regions, with the
region-to-region cost ``min over cells of l of d_l'``. That lets the robot "teleport" inside each region it
passes: it arrives at the point nearest to where it came from and leaves from the point nearest to where it
goes next. With several goals the slack adds up (unordered goals: benchmarks/goals_analysis.py,
benchmarks/results/comment_measurements.md), and A* floods a wide band of every automaton state.

Here the regions are cut into **pieces**, and the cost to go remembers the piece where the robot entered a
region. Only the cells where the automaton can change state matter as entry points: the *entry cells* of
label ``l`` are its cells with a neighbour of another label (a robot coming from outside enters there), the
start's neighbours (the ``authors`` profile reads the start's label only on the first move) and, for a
label that moves some state twice in a row, all its cells. The entry cells of a label are binned into
squares of about :data:`PIECE_M` (at most :data:`MAX_PIECES` per label).

Distances to a piece are bounded from below with the exact label distance fields ``d_f`` (multi-source
Dijkstra over the search graph; every leaving label's region is one field) used as landmarks: the cell
graph is undirected (cells.py: a step joins two traversable 8-neighbours, stairs go both ways at one
cost), so each ``d_f`` is 1-Lipschitz and for every cell ``y`` of piece ``k``,
``d(x, y) >= |d_f(x) - d_f(y)|``. With ``lo[k, f]`` / ``hi[k, f]`` the smallest / largest ``d_f`` over the
piece,

    phi_k(x) = max(0, max over f of (lo[k, f] - d_f(x)), max over f of (d_f(x) - hi[k, f]))  <= d(x, piece k)

and ``phi_k`` is 1-Lipschitz (a max of 1-Lipschitz functions). Its own label's field gives
``phi_k >= d_l``, so phi never undercuts the paper's term; the other labels' fields add the far side of
the region as seen from where the robot was (the "arrival side" the region-level bound ignores). Then,
with ``T`` the transition table,

    h(x, q)    = 0                                                     if q is accepting
    h(x, q)    = min over pieces k of labels l with T(q, l) != q of  phi_k(x) + G(k, T(q, l))
    G(j, q)    = min over cells y of piece j of h(y, q)
               = min over the same terms as h(., q) of  LB(j, k) + G(k, T(q, l)),   LB(j, k) = min over y in j
                                                                                       of phi_k(y)

(no term: h = inf, no way to acceptance). G is a backward shortest path over (piece, automaton state),
exact over the pieces (LB is a min over the piece's cells, not an estimate).

Consistency on every move (x, q) -> (x', q'), cost w: if q' = q, ``h(x, q) <= w + h(x', q)`` as h(., q) is
a min of 1-Lipschitz functions. If q' != q, x' is an entry cell of its label l (the move crossed into the
region, or left the start, or l moves states twice), so it lies in a piece k of l, ``phi_k(x') = 0`` and
``h(x', q) <= G(k, q') <= h(x', q')``; with the first case, ``h(x, q) <= w + h(x', q')``. Composite actions
are sequences of moves, so the bound chains; h = 0 at acceptance. The paper's h is the special case of one
piece per label with phi = d_l; this h is never below it (LB(j, k) >= the region-to-region cost). ``h = inf``
proves that no accepting path exists, so the search may drop such states.

**Fixed point.** The fields are uint32 whole units of ``unit_m`` (:data:`UNIT_M` = 2^-22 m, coarser only
where a distance would not fit): 4 bytes per cell and field instead of float64's 8. To keep every step of
the argument above exact, a field is not a rounded metric distance (rounding breaks the 1-Lipschitz
property by an ulp) but the exact shortest path over the same graph with every move's cost rounded *down*
to whole units (:func:`unit_costs`): that ``d_f`` is 1-Lipschitz in the rounded costs, which are <= the
real ones, and 0 on its region, which is all the proofs use. h is computed from sums and maxima of whole
units (exact in float64 below 2^53) and converted to metres by a power of two (exact), so it has no
rounding slack at all; it gives up at most a unit (2.4e-7 m) per move of a path in tightness. A field of
whole units in 4 bytes takes half the memory of a float64 one.

Only automaton states reachable from the start state get a row. The search computes values cell by cell
(:func:`row_value`) and fills a whole row (:func:`fill_row`) only once it has evaluated it often
(``_search.h_ltl``): rows it never fills cost no memory (their pages of the lazily committed ``hmap`` are
never written). An evaluation takes the label groups of a row in order of the paper's term and stops as
soon as no remaining term can be lower, so it usually computes one or two terms in full.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numba import njit

from sgplan.intsets import unique_sorted
from sgplan.planning._memory import sparse_zeros
from sgplan.planning.cells import CellGraph

PIECE_M = 0.2
"""Side of the squares the entry cells of a label region are binned into (metres): the slack of the bound
per region visited is about a piece's diameter. 0.2 m took h(start) of the 9-goal benchmark from 0.52 to
0.96 of the optimum and its A* expansions from 23.0M to 1.0M (0.3 m: 0.95 and 1.5M, 0.6 m: 0.91 and 3.4M;
0.15 m: 0.97 and 0.7M, at more cost per evaluation)."""
UNIT_M = 2.0**-22
"""Metres per unit of the distance fields (a power of two, so unit counts convert to metres exactly): 2^32
units span 1,024 m; a building whose distances do not fit gets the coarser power of two they need. The
unit lost per move is below any real difference of path costs, but it does break exact ties: where
float64 fields made h exact along a bundle of equal-cost optimal paths (f = the optimum on all of them,
so the search stopped without expanding them), those states now sit just below it and are expanded
(Gibson, A*: 0-50 % more expansions on 5 of 20 cases, at a lower cost per expansion; see
benchmarks/results/planning_vs_dijkstra.md)."""
UNREACHED = np.uint32(np.iinfo(np.uint32).max)
"""The field value of a cell that cannot reach the field's region."""
MAX_PIECES = 32
"""At most this many pieces per label region (larger regions get larger squares): the terms of a row, and
so the cost of an evaluation, grow with the pieces."""


@dataclass(eq=False)
class LtlHeuristic:
    """Tabulated h_LTL, rows filled on demand.

    Attributes
    ----------
    q_row:
        ``(Q,)`` int32: the row of ``hmap`` for state q, -1 if q has no map (accepting: h = 0; not
        reachable from the start state or without a way to acceptance: h = inf).
    hmap:
        ``(rows, N)`` float64 metres, lazily committed; row ``r`` is valid once ``ready[r]`` is 1.
    ready:
        ``(rows,)`` uint8.
    dist:
        ``(N, F)`` uint32: each cell's distance to the region of ``leaving_labels[f]`` in whole units of
        ``unit_m`` (the landmarks of the module docstring; :data:`UNREACHED` where it cannot reach it).
    unit_m:
        metres per unit of ``dist`` and of the terms (a power of two).
    term_ptr, term_label, term_add:
        row ``r`` is ``unit_m`` times the min over the terms ``t`` of its label groups ``g in term_ptr[r] ..
        term_ptr[r+1]-1`` of ``phi(x) + term_add[t, 0]``, ``phi`` the bound on the distance to the term's
        piece (in units). Group ``g`` is ``term_label[g] = (field of the label, first term, end)``, its terms
        sorted by cost to go ``term_add[t, 0]``; ``term_add[t, 1:1+F]`` / ``term_add[t, 1+F:]`` are the
        smallest / largest value of each field over the piece (units, as float64).
    accepting:
        ``(Q,)`` bool.
    leaving_labels:
        compact label ids that leave at least one tabulated state and occur on a reachable cell (those
        whose regions were measured).
    piece_label, piece_cells, piece_ptr:
        piece ``k`` is the entry cells ``piece_cells[piece_ptr[k] : piece_ptr[k+1]]`` of field
        ``piece_label[k]``.
    """

    q_row: np.ndarray
    hmap: np.ndarray
    ready: np.ndarray
    dist: np.ndarray
    unit_m: float
    term_ptr: np.ndarray
    term_label: np.ndarray
    term_add: np.ndarray
    accepting: np.ndarray
    leaving_labels: np.ndarray
    piece_label: np.ndarray
    piece_cells: np.ndarray
    piece_ptr: np.ndarray

    def value(self, cell: int, q: int) -> float:
        """h at product state (cell index, q), metres."""
        if self.accepting[q]:
            return 0.0
        row = int(self.q_row[q])
        if row < 0:
            return float("inf")
        if not self.ready[row]:
            return float(row_value(self.dist, self.unit_m, self.term_ptr, self.term_label, self.term_add, row,
                                   cell))
        return float(self.hmap[row, cell])

    def fields_m(self) -> np.ndarray:
        """``(F, N)`` float64: the distance fields in metres (``inf`` where unreached)."""
        return np.where(self.dist.T == UNREACHED, np.inf, self.dist.T * self.unit_m)


@njit(cache=True, inline="always")
def _units(x):
    """A field value as float64 units, ``inf`` for :data:`UNREACHED`."""
    return np.inf if x == UNREACHED else np.float64(x)


@njit(cache=True, inline="always")
def _outside(lo, hi, x):
    """How far field value ``x`` lies outside a piece's values ``[lo, hi]`` (<= 0 inside), all in units,
    ``inf`` for unreached. A cell that cannot reach the field's region cannot reach a piece cell that
    can (``inf`` when ``hi`` is finite); when neither can, the field tells nothing (``-inf``). The fields
    of a run may leave cells out of the graph (execution/fields.py), which is how a cell of the search
    can be unreached by a measured field."""
    if x == np.inf:
        return np.inf if hi < np.inf else -np.inf
    return max(lo - x, x - hi)


@njit(cache=True, inline="always")
def row_value(dist, unit, term_ptr, term_label, term_add, row, c):
    """h at cell ``c`` in the automaton state of row ``row``, metres: ``unit`` times the min over the row's
    terms (see :class:`LtlHeuristic`), computed in full only where it can matter.

    A term's phi is at least its label's distance, so ``key = d_label(c) + cheapest cost to go`` bounds a
    whole label group from below (the paper's term). Groups are taken in order of key (a selection scan:
    a row has a handful), the scan stops once the next key is no better than the best value, and within
    a group (sorted by cost to go) at the first term whose label distance plus cost to go is not. Skipped
    terms cannot be below the result, so the value is the exact minimum."""
    width = dist.shape[1]
    best = np.inf
    last_key = -np.inf
    last = -1
    while True:
        pick = -1
        pick_key = np.inf
        for g in range(term_ptr[row], term_ptr[row + 1]):
            key = _units(dist[c, term_label[g, 0]]) + term_add[term_label[g, 1], 0]
            if key < pick_key and (key > last_key or (key == last_key and g > last)):
                pick = g
                pick_key = key
        if pick < 0 or pick_key >= best:
            return best * unit
        own = _units(dist[c, term_label[pick, 0]])
        for t in range(term_label[pick, 1], term_label[pick, 2]):
            add = term_add[t, 0]
            if own + add >= best:
                break
            phi = own
            for f in range(width):
                phi = max(phi, _outside(term_add[t, 1 + f], term_add[t, 1 + width + f], _units(dist[c, f])))
                if phi + add >= best:  # this term cannot be the minimum
                    break
            best = min(best, phi + add)
        last_key = pick_key
        last = pick


@njit(cache=True, nogil=True)
def fill_row(hmap, ready, dist, unit, term_ptr, term_label, term_add, row):
    """Fill ``hmap[row]`` with :func:`row_value` at every cell (the same bits) and mark it ready."""
    for c in range(hmap.shape[1]):
        hmap[row, c] = row_value(dist, unit, term_ptr, term_label, term_add, row, c)
    ready[row] = 1


def reachable_states(trans: np.ndarray, q_start: int) -> np.ndarray:
    """``(Q,)`` bool: states reachable from ``q_start`` in the (compact-label) transition table."""
    seen = np.zeros(trans.shape[0], dtype=bool)
    seen[q_start] = True
    frontier = [q_start]
    while frontier:
        nxt = np.unique(trans[frontier].ravel())
        nxt = nxt[~seen[nxt]]
        seen[nxt] = True
        frontier = list(nxt)
    return seen


def build_ltl_heuristic(
    graph: CellGraph,
    cell_label: np.ndarray,
    trans: np.ndarray,
    accepting: np.ndarray,
    q_start: int,
    reachable: np.ndarray | None = None,
    fields: Callable[[np.ndarray, float], np.ndarray | float] | None = None,
    start_cell: int = -1,
    piece_m: float = PIECE_M,
    max_pieces: int = MAX_PIECES,
    boundary: np.ndarray | None = None,
) -> LtlHeuristic:
    """Tabulate h_LTL for the states reachable from ``q_start``.

    Parameters
    ----------
    graph:
        the cell graph searched (undirected, as :mod:`sgplan.planning.cells` builds it).
    cell_label:
        ``(N,)`` compact label id of every cell (every id ``0 .. L-1`` occurs).
    trans:
        ``(Q, L)`` next state per compact label.
    accepting:
        ``(Q,)`` bool.
    q_start:
        the automaton state at the start cell.
    reachable:
        optional ``(N,)`` bool, the cells reachable from the start: label regions are restricted to them
        (the search never leaves them), which tightens h and makes it ``inf`` when a needed label occurs
        only elsewhere.
    fields:
        optional ``fields(labels, unit_m)``: the distance fields of the regions of the compact labels
        ``labels`` (ascending), as :func:`label_fields` computes them (the default): an ``(N, len(labels))``
        uint32 matrix, or the largest distance (a float) when some does not fit. A label's field may be
        to its whole region instead of its part in ``reachable``: the two agree on every cell reachable
        from the start, the only cells h reads (e.g. a run's fields, repaired across scene changes).
    start_cell:
        the start's cell index: its neighbours become entry cells of their labels, since the ``authors``
        profile reads the start's label only on the first move. -1: none, which keeps h consistent only
        when ``q_start`` has read the start's label (the ``ltlf`` profile).
    piece_m, max_pieces:
        side of the pieces (metres) and most pieces per label region (:data:`PIECE_M`,
        :data:`MAX_PIECES`); any values keep h consistent, smaller pieces make it tighter and slower.
    boundary:
        optional :func:`label_boundary` of ``graph`` and ``cell_label`` (e.g. kept up to date by a run);
        computed when ``None``.
    """
    accepting = np.asarray(accepting, dtype=bool)
    states = np.flatnonzero(reachable_states(trans, q_start) & ~accepting)
    inside = reachable if reachable is not None else np.ones(graph.num_cells, dtype=bool)
    needed, field_of = _measured_labels(trans, states, cell_label, inside)
    dist, unit_m = _label_fields(graph, cell_label, needed, inside, fields)
    twice = _moves_twice(trans, states)
    if boundary is None:
        boundary = label_boundary(graph, cell_label)
    entry = _entry_cells(graph, cell_label, field_of, inside, twice, start_cell, boundary)
    piece_label, piece_cells, piece_ptr = _pieces(graph, field_of, entry, piece_m, max_pieces)
    lo, hi = _piece_bounds(dist, piece_cells, piece_ptr)
    between = _piece_lower_bounds(dist, piece_cells, piece_ptr, lo, hi)
    q_row, term_ptr, groups, term_piece, term_add = _terms(trans, accepting, states, field_of, piece_label,
                                                           between)
    term_data = _term_data(term_add, lo[term_piece], hi[term_piece])
    rows = len(term_ptr) - 1
    return LtlHeuristic(
        q_row=q_row,
        hmap=sparse_zeros((rows, graph.num_cells), np.float64),
        ready=np.zeros(rows, dtype=np.uint8),
        dist=dist,
        unit_m=unit_m,
        term_ptr=term_ptr,
        term_label=groups,
        term_add=term_data,
        accepting=accepting,
        leaving_labels=needed,
        piece_label=piece_label,
        piece_cells=piece_cells,
        piece_ptr=piece_ptr,
    )


def _measured_labels(trans: np.ndarray, states: np.ndarray, cell_label: np.ndarray, inside: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """``(needed, field_of)``: the compact labels that leave some state of ``states`` and occur on a cell
    ``inside`` (where the search can go), ascending -- one distance field each --, and per compact label
    its field's column (-1: none)."""
    leaves = trans[states] != states[:, None]
    present = np.zeros(trans.shape[1], dtype=bool)
    present[cell_label[inside]] = True
    needed = np.flatnonzero(leaves.any(axis=0) & present)
    field_of = np.full(trans.shape[1], -1, dtype=np.int64)
    field_of[needed] = np.arange(len(needed))
    return needed, field_of


def _term_data(term_add: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """``(T, 1 + 2F)`` per term its added cost, then its piece's smallest and largest value of each field:
    one row per term, as :func:`row_value` reads it."""
    width = lo.shape[1]
    term_data = np.empty((len(term_add), 1 + 2 * width), dtype=np.float64)
    term_data[:, 0] = term_add
    term_data[:, 1 : 1 + width] = lo
    term_data[:, 1 + width :] = hi
    return term_data


def _label_fields(
    graph: CellGraph, cell_label: np.ndarray, needed: np.ndarray, inside: np.ndarray,
    fields: Callable[[np.ndarray, float], np.ndarray | float] | None,
) -> tuple[np.ndarray, float]:
    """``(N, len(needed))`` uint32 distance fields of the regions of the compact labels ``needed`` (by
    ``fields``, :func:`label_fields` over the cells ``inside`` by default), in units of the returned
    ``unit_m``: the finest unit (:func:`finest_unit`) unless some distance does not fit in 32 bits, then
    the coarsest power of two times it that fits."""
    if fields is None:
        def fields(labels: np.ndarray, unit: float) -> np.ndarray | float:
            return label_fields(graph, cell_label, inside, labels, unit)
    unit_m = finest_unit(graph)
    while True:  # a coarser unit only if some distance does not fit in 32 bits
        dist = fields(needed, unit_m)
        if not isinstance(dist, float):
            return dist, unit_m
        unit_m *= 2.0 ** np.ceil(np.log2(dist / (UNREACHED - 1)))


def finest_unit(graph: CellGraph) -> float:
    """:data:`UNIT_M`, or the largest power of two not above the cheapest move if that is finer (every move
    must cost at least one unit)."""
    cheapest = min(graph.step_cost.min(), graph.stairs_cost.min(initial=np.inf))
    return min(UNIT_M, 2.0 ** np.floor(np.log2(cheapest)))


def unit_costs(graph: CellGraph, unit_m: float) -> tuple[np.ndarray, np.ndarray]:
    """``(step, stairs)``: the cost of every move of ``graph`` in whole units of ``unit_m``, rounded down
    (float64 whole numbers, >= 1 when ``unit_m <= finest_unit(graph)``)."""
    return np.floor(graph.step_cost / unit_m), np.floor(graph.stairs_cost / unit_m)


def label_fields(graph: CellGraph, cell_label: np.ndarray, inside: np.ndarray, labels: np.ndarray,
                 unit_m: float, distances: Callable[[np.ndarray, float], np.ndarray | float] | None = None
                 ) -> np.ndarray | float:
    """``(N, F)`` uint32: column ``i`` is the :func:`unit_field` of the cells of ``inside`` whose compact
    label is ``labels[i]``; or, when some distance does not fit, the largest one (units, a float).

    Cell-major, as h reads it: an evaluation reads all the fields of one cell (one cache line).
    ``distances(cells, unit_m)``: :func:`unit_field` of ``graph`` (the default), e.g. kept by a session
    (:mod:`sgplan.planning.shared`); ``cells`` are sorted cell indices."""
    if distances is None:
        def distances(cells: np.ndarray, unit: float) -> np.ndarray | float:
            return unit_field(graph, cells, unit)
    dist = np.empty((graph.num_cells, len(labels)), dtype=np.uint32)
    for i, label in enumerate(labels):
        field = distances(np.flatnonzero((cell_label == label) & inside), unit_m)
        if isinstance(field, float):
            return field
        dist[:, i] = field
    return dist


def unit_field(graph: CellGraph, cells: np.ndarray, unit_m: float) -> np.ndarray | float:
    """``(N,)`` uint32: each cell's distance to ``cells`` in whole units of ``unit_m`` over the moves'
    costs rounded down (:func:`unit_costs`; the module docstring's fixed point), :data:`UNREACHED` where
    none can be reached. If some distance does not fit below :data:`UNREACHED`, the largest one (units, a
    float) instead: a coarser unit is needed."""
    field = graph.distances(cells, costs=unit_costs(graph, unit_m))
    out = np.empty(graph.num_cells, dtype=np.uint32)
    largest = _whole_units(field, out)
    return out if largest < UNREACHED else largest


@njit(cache=True, nogil=True)
def _whole_units(field, out):
    """``out[i]`` = the whole number ``field[i]``, :data:`UNREACHED` for ``inf``, where it fits below
    :data:`UNREACHED`; returns the largest finite value."""
    largest = 0.0
    for i in range(field.shape[0]):
        x = field[i]
        if x == np.inf:
            out[i] = UNREACHED
        else:
            largest = max(largest, x)
            if x < UNREACHED:
                out[i] = np.uint32(x)
    return largest


def _moves_twice(trans: np.ndarray, states: np.ndarray) -> np.ndarray:
    """``(L,)`` bool: labels ``l`` with a state ``q`` among ``states`` where ``T(q, l) != q`` and
    ``T(T(q, l), l) != T(q, l)`` (a robot staying on ``l`` changes state again: every cell of ``l`` is an
    entry cell)."""
    after = trans[states]
    again = trans[after, np.arange(trans.shape[1])[None, :]]
    return ((after != states[:, None]) & (again != after)).any(axis=0)


def _pieces(
    graph: CellGraph,
    field_of: np.ndarray,
    entry: tuple[np.ndarray, np.ndarray],
    piece_m: float,
    max_pieces: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(piece_label, piece_cells, piece_ptr)`` (see :class:`LtlHeuristic`): the entry cells (``entry``:
    the cells, ascending, and their compact labels) of every measured label, binned into squares of
    ``piece_m`` (larger for labels that would get more than ``max_pieces``)."""
    cells, cell_labels = entry
    field = field_of[cell_labels]
    side = max(1, round(piece_m / min(graph.resolution_m)))
    labels, cell_lists = [], []
    for f in range(int(field_of.max(initial=-1)) + 1):
        own = cells[field == f]
        bins = side
        while True:
            key = _bin_key(graph, own, bins)
            order = np.argsort(key, kind="stable")  # by square, each in cell order
            splits = np.flatnonzero(np.diff(key[order])) + 1
            if len(splits) < max_pieces or bins > max(graph.shape[1:]):  # at worst, one piece per floor
                break
            bins = int(np.ceil(bins * 1.5))
        for piece in np.split(own[order], splits):
            labels.append(f)
            cell_lists.append(piece)
    ptr = np.zeros(len(cell_lists) + 1, dtype=np.int64)
    ptr[1:] = np.cumsum([len(c) for c in cell_lists])
    flat = np.concatenate(cell_lists).astype(np.int64) if cell_lists else np.zeros(0, dtype=np.int64)
    return np.array(labels, dtype=np.int64), flat, ptr


def _bin_key(graph: CellGraph, cells: np.ndarray, side: int) -> np.ndarray:
    """The square of ``side`` cells (per floor) holding each cell, as one int64."""
    _, rows, cols = graph.shape
    per_row = cols // side + 1
    per_floor = (rows // side + 1) * per_row
    row, col = graph.row_col(cells)
    return graph.cell_floor[cells].astype(np.int64) * per_floor + row // side * per_row + col // side


def label_boundary(graph: CellGraph, cell_label: np.ndarray) -> np.ndarray:
    """``(N,)`` bool: the cells of ``graph`` that a move (a step or stairs) joins to a cell of the graph
    with another compact label in ``cell_label`` -- where a robot coming from outside a label region
    enters it. A pass over the cells (compiled)."""
    boundary = np.zeros(graph.num_cells, dtype=np.bool_)
    mark_boundary(graph.cell_at, graph.cell_pos, graph.step_offset, graph.stairs_first, graph.stairs_from,
                  graph.stairs_to, cell_label, np.arange(graph.num_cells, dtype=np.int64), False, boundary)
    return boundary


@njit(cache=True, inline="always")
def _on_boundary(cell_at, cell_pos, step_offset, stairs_first, stairs_from, stairs_to, cell_label, x):
    """Whether cell ``x`` is on a label boundary (:func:`label_boundary`); a cell off the graph (masked,
    ``cell_at[cell_pos[x]] != x``) is not."""
    pos = cell_pos[x]
    if cell_at[pos] != x:
        return False
    label = cell_label[x]
    for k in range(8):
        y = cell_at[pos + step_offset[k]]
        if y >= 0 and cell_label[y] != label:
            return True
    j = stairs_first[x]
    while 0 <= j < stairs_from.shape[0] and stairs_from[j] == x:
        y = stairs_to[j]
        if cell_at[cell_pos[y]] == y and cell_label[y] != label:
            return True
        j += 1
    return False


@njit(cache=True, nogil=True)
def mark_boundary(cell_at, cell_pos, step_offset, stairs_first, stairs_from, stairs_to, cell_label, cells,
                  around, boundary):
    """Set ``boundary[x]`` (see :func:`label_boundary`) for every cell ``x`` of ``cells`` and, if
    ``around``, for every cell of the graph a move joins it to (what a change of ``x``'s label or graph
    membership can affect)."""
    n_stairs = stairs_from.shape[0]
    done = np.zeros(boundary.shape[0] if around else 0, dtype=np.bool_)  # each cell once, when around
    for x in cells:
        boundary[x] = _on_boundary(cell_at, cell_pos, step_offset, stairs_first, stairs_from, stairs_to,
                                   cell_label, x)
        if not around:
            continue
        done[x] = True
        pos = cell_pos[x]
        j = stairs_first[x]
        for k in range(8 + n_stairs):
            if k < 8:
                y = cell_at[pos + step_offset[k]]
            elif 0 <= j < n_stairs and stairs_from[j] == x:
                y = stairs_to[j]
                j += 1
            else:
                break
            if y >= 0 and not done[y]:
                done[y] = True
                boundary[y] = _on_boundary(cell_at, cell_pos, step_offset, stairs_first, stairs_from,
                                           stairs_to, cell_label, y)


def _entry_cells(graph: CellGraph, cell_label: np.ndarray, field_of: np.ndarray, inside: np.ndarray,
                 twice: np.ndarray, start_cell: int, boundary: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The measured-label cells (``field_of >= 0``, inside) where the automaton can change state on a move
    (see the module docstring): those on a label ``boundary``, the start's neighbours, every cell of a
    label that moves some state twice in a row; ascending, with their compact labels."""
    cells = np.flatnonzero(boundary)
    if twice.any():
        cells = unique_sorted(np.concatenate([cells, np.flatnonzero(twice[cell_label])]))
    if start_cell >= 0:
        near = graph.neighbours(np.array([start_cell]))[0]
        stairs = graph.stairs_to[graph.stairs_from == start_cell]
        cells = unique_sorted(np.concatenate([cells, near[near >= 0], stairs]).astype(np.int64))
    labels = cell_label[cells]
    keep = inside[cells] & (field_of[labels] >= 0)
    return cells[keep], labels[keep]


@njit(cache=True, nogil=True)
def _piece_bounds(dist, piece_cells, piece_ptr):
    """``(lo, hi)`` ``(K, F)``: smallest and largest value of each field over each piece (float64 units)."""
    num_pieces, num_fields = piece_ptr.shape[0] - 1, dist.shape[1]
    lo = np.full((num_pieces, num_fields), np.inf)
    hi = np.full((num_pieces, num_fields), -np.inf)
    for k in range(num_pieces):
        for i in range(piece_ptr[k], piece_ptr[k + 1]):
            c = piece_cells[i]
            for f in range(num_fields):
                x = _units(dist[c, f])
                lo[k, f] = min(lo[k, f], x)
                hi[k, f] = max(hi[k, f], x)
    return lo, hi


@njit(cache=True, nogil=True)
def _piece_lower_bounds(dist, piece_cells, piece_ptr, lo, hi):
    """``(K, K)``: ``LB[j, k]`` = min over the cells ``y`` of piece ``j`` of ``phi_k(y)`` (the module
    docstring's bound on the distance from ``y`` to piece ``k``, units)."""
    num_pieces, num_fields = lo.shape
    between = np.full((num_pieces, num_pieces), np.inf)
    x = np.empty(num_fields)
    for j in range(num_pieces):
        for i in range(piece_ptr[j], piece_ptr[j + 1]):
            c = piece_cells[i]
            for f in range(num_fields):
                x[f] = _units(dist[c, f])
            for k in range(num_pieces):
                phi = 0.0
                for f in range(num_fields):
                    phi = max(phi, _outside(lo[k, f], hi[k, f], x[f]))
                between[j, k] = min(between[j, k], phi)
    return between


def _terms(
    trans: np.ndarray,
    accepting: np.ndarray,
    states: np.ndarray,
    field_of: np.ndarray,
    piece_label: np.ndarray,
    between: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(q_row, group_ptr, groups, term_piece, term_add)``: the terms (piece, cost to go after it) of
    every state in ``states`` with a finite one, in label groups (see :class:`LtlHeuristic`). ``G`` of the
    module docstring is computed backwards over (piece, state): in one sweep in reverse topological order
    when the automaton's state changes form no cycle, else swept until nothing changes (costs are >= 0,
    so it converges to the least fixed point, as Bellman-Ford)."""
    num_states = trans.shape[0]
    num_pieces = len(piece_label)
    # G[q] (K,): min over the cells of each piece of h(., q); +inf where unknown or unreachable.
    to_go = np.full((num_states, num_pieces), np.inf)
    to_go[accepting] = 0.0
    # Per state: the (piece, successor state) pairs of its terms.
    label_of_field = np.empty(len(np.flatnonzero(field_of >= 0)), dtype=np.int64)
    label_of_field[field_of[field_of >= 0]] = np.flatnonzero(field_of >= 0)
    piece_labels = label_of_field[piece_label]
    piece_next = {}
    for q in states:
        nxt = trans[q, piece_labels]
        keep = nxt != q
        piece_next[int(q)] = (np.flatnonzero(keep), nxt[keep])
    order, acyclic = _reverse_topological(trans, states)
    changed = True
    while changed:
        changed = False
        for q in order:
            pieces, nxt = piece_next[q]
            add = to_go[nxt, pieces]
            finite = np.isfinite(add)
            if not finite.any():
                continue
            best = (between[:, pieces[finite]] + add[finite]).min(axis=1)
            if (best < to_go[q]).any():
                to_go[q] = np.minimum(to_go[q], best)
                changed = True
        changed = changed and not acyclic
    q_row = np.full(num_states, -1, dtype=np.int32)
    group_ptr = [0]
    groups: list[tuple[int, int, int]] = []
    term_piece: list[np.ndarray] = []
    term_add: list[np.ndarray] = []
    num_terms = 0
    for q in states:
        pieces, nxt = piece_next[int(q)]
        add = to_go[nxt, pieces]
        finite = np.isfinite(add)
        if not finite.any():
            continue
        pieces, add = pieces[finite], add[finite]
        # Label groups in order of their cheapest term, each sorted by cost to go.
        by_label = np.lexsort((add, piece_label[pieces]))
        pieces, add = pieces[by_label], add[by_label]
        starts = np.flatnonzero(np.diff(piece_label[pieces], prepend=-1))
        ends = np.append(starts[1:], len(pieces))
        for i in np.argsort(add[starts], kind="stable"):
            groups.append((int(piece_label[pieces[starts[i]]]), num_terms, num_terms + ends[i] - starts[i]))
            term_piece.append(pieces[starts[i] : ends[i]])
            term_add.append(add[starts[i] : ends[i]])
            num_terms += ends[i] - starts[i]
        q_row[q] = len(group_ptr) - 1
        group_ptr.append(len(groups))
    return (
        q_row,
        np.array(group_ptr, dtype=np.int64),
        np.array(groups, dtype=np.int64).reshape(-1, 3),
        np.concatenate(term_piece) if term_piece else np.zeros(0, dtype=np.int64),
        np.concatenate(term_add) if term_add else np.zeros(0, dtype=np.float64),
    )


def _reverse_topological(trans: np.ndarray, states: np.ndarray) -> tuple[list[int], bool]:
    """``(order, acyclic)``: ``states`` with every state after the states it moves to (Kahn's algorithm on
    the state changes among ``states``); if those form a cycle, the states on it follow in index order
    and ``acyclic`` is False."""
    members = set(int(q) for q in states)
    succ = {q: set(int(p) for p in np.unique(trans[q]) if int(p) != q and int(p) in members) for q in members}
    pending = {q: len(s) for q, s in succ.items()}
    pred: dict[int, list[int]] = {q: [] for q in members}
    for q, s in succ.items():
        for p in s:
            pred[p].append(q)
    ready = sorted(q for q, n in pending.items() if n == 0)
    order: list[int] = []
    while ready:
        q = ready.pop()
        order.append(q)
        for p in pred[q]:
            pending[p] -= 1
            if pending[p] == 0:
                ready.append(p)
    acyclic = len(order) == len(members)
    order += sorted(q for q in members if pending[q] > 0)
    return order, acyclic
