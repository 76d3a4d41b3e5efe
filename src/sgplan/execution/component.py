"""The cells a robot can reach (its connected component of a run's cell graph), kept up to date across
scene changes from the cells that changed, not flooded anew.

The planner needs them on every plan: h_LTL measures only the label regions the robot can reach (and
proves a goal cut off at once), the infeasibility messages name what it cannot reach, the composite
action maps stop once they have settled the reachable cells of their room. A flood fill from the robot
costs a pass over its component; after a change, :meth:`Component.update` costs what the change touched:

- **Cells joined the graph** (a door opened, a block lifted): the component can only grow, through them.
  A flood from the joined cells next to it marks what they connect to it, and nothing it had already.
- **Cells left the graph** (a door closed, an area blocked): the component may split. *Competing floods*
  start from every reachable neighbour of the cells that left, breadth first and in step, each flood
  claiming the cells it reaches first; two floods that meet are one region from then on (union-find). The
  run stops as soon as at most one region can still grow: every other region has been flooded to its end,
  so it is a whole connected component of the new graph, known cell by cell. If the robot is in one of
  them, that region is its component; otherwise its component is the old one without the cells that left
  and without those finished regions. A block that the way goes around ends once the floods meet around
  it (a few rings of cells); a door that cuts a wing off costs the smaller side, whichever side the robot
  is on.

Both are exact: :func:`tests.execution.test_component` compares the result with a flood fill after
random sequences of changes.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from sgplan.execution.graph import in_graph_cells
from sgplan.intsets import members, unique_sorted
from sgplan.planning._dijkstra import flood
from sgplan.planning.cells import CellGraph


@njit(cache=True, inline="always")
def _root(parent, i):
    """The representative of seed ``i``'s region (path halving)."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@njit(cache=True)
def _competing_floods(cell_at, cell_pos, step_offset, stairs_first, stairs_from, stairs_to, seeds, owner,
                      order):
    """Competing breadth-first floods from ``seeds`` (cells of the graph; see the module docstring), until
    at most one region can still grow.

    ``owner`` (``(N,)`` int32, zeros) receives ``1 +`` the representative seed of every cell reached, and
    ``order`` (``(N,)`` int32) the cells reached, in order. Returns ``(reached, finished)``: how many cells
    ``order`` holds, and per seed whether its region was flooded to its end (a whole component of the
    graph). Stairs are followed from a cell to a portal in the graph."""
    num_seeds = seeds.shape[0]
    parent = np.arange(num_seeds)
    frontier = np.zeros(num_seeds, dtype=np.int64)  # per representative: cells reached, not yet expanded
    tail = 0
    growing = 0
    for i in range(num_seeds):
        x = seeds[i]
        if owner[x] != 0:  # a seed given twice
            parent[i] = _root(parent, owner[x] - 1)
            continue
        owner[x] = i + 1
        order[tail] = x
        tail += 1
        frontier[i] = 1
        growing += 1
    n_stairs = stairs_from.shape[0]
    head = 0
    while head < tail and growing > 1:
        x = order[head]
        head += 1
        r = _root(parent, owner[x] - 1)
        pos = cell_pos[x]
        j = stairs_first[x]
        for k in range(8 + n_stairs):
            if k < 8:
                y = cell_at[pos + step_offset[k]]
            else:  # the stairs moves leaving x
                if not (0 <= j < n_stairs and stairs_from[j] == x):
                    break
                y = stairs_to[j]
                j += 1
                if cell_at[cell_pos[y]] != y:
                    continue
            if y < 0 or owner[y] == r + 1:  # most neighbours: claimed by this region already
                continue
            if owner[y] == 0:
                owner[y] = r + 1
                order[tail] = y
                tail += 1
                frontier[r] += 1
            else:
                other = _root(parent, owner[y] - 1)
                if other != r:  # two regions meet: one from now on
                    if frontier[other] > 0:
                        growing -= 1
                    frontier[r] += frontier[other]
                    parent[other] = r
        frontier[r] -= 1
        if frontier[r] == 0:
            growing -= 1
    finished = np.zeros(num_seeds, dtype=np.bool_)
    for i in range(num_seeds):
        finished[i] = frontier[_root(parent, i)] == 0
    for i in range(tail):
        owner[order[i]] = _root(parent, owner[order[i]] - 1) + 1
    return tail, finished


class Component:
    """The connected component of a run's cell graph that holds a cell (the robot's), as ``(N,)`` bool over
    the run's numbering, kept up to date across changes (see the module). ``floods`` counts the full
    flood fills, ``updates`` the changes followed without one (for tests and benchmarks)."""

    def __init__(self) -> None:
        self.cells: np.ndarray | None = None
        self.anchor = -1
        self.floods = 0
        self.updates = 0

    def of(self, graph: CellGraph, cell: int) -> np.ndarray:
        """The cells reachable from ``cell`` in ``graph`` (the run's current graph): the component kept,
        if it holds ``cell``, else a flood fill from it. The array is the component's: read it, do not
        change it."""
        if self.cells is None or not self.cells[cell]:
            self.cells = graph.reachable(cell)
            self.floods += 1
        self.anchor = cell
        return self.cells

    def update(self, graph: CellGraph, moved: np.ndarray, anchor: int | None = None) -> None:
        """Follow a change of the graph: ``graph`` is the new one, ``moved`` the cells (numbers) that left
        or joined it. ``anchor``: a cell of the robot's component now, if known (default: the cell last
        asked for). The component is forgotten (flooded anew when next asked for) if the anchor left the
        graph."""
        if anchor is not None and anchor >= 0:
            self.anchor = anchor
        if self.cells is None or moved.size == 0:
            return
        inside = in_graph_cells(graph, moved)
        left, joined = moved[~inside], moved[inside]
        if not in_graph_cells(graph, np.array([self.anchor]))[0]:
            self.cells = None
            return
        cells = self.cells.copy()
        if left.size and cells[left].any():
            self._split(graph, cells, left)
        if joined.size:
            _grow(graph, cells, joined)
        self.cells = cells
        self.updates += 1

    def _split(self, graph: CellGraph, cells: np.ndarray, left: np.ndarray) -> None:
        """``cells`` (the component before ``left`` left the graph) made the anchor's component of
        ``graph`` as far as those cells go: competing floods from their reachable neighbours."""
        near = graph.neighbours(left)
        seeds = near[near >= 0]
        seeds = unique_sorted(seeds[cells[seeds]]).astype(np.int64)
        cells[left] = False
        if seeds.size == 0:
            return
        owner = np.zeros(graph.num_cells, dtype=np.int32)
        order = np.empty(graph.num_cells, dtype=np.int32)
        reached, finished = _competing_floods(graph.cell_at, graph.cell_pos, graph.step_offset,
                                              graph.stairs_first, graph.stairs_from, graph.stairs_to, seeds,
                                              owner, order)
        visited = order[:reached]
        region = owner[visited] - 1
        mine = owner[self.anchor] - 1
        if mine >= 0 and finished[mine]:
            cells[:] = False
            cells[visited[region == mine]] = True
        else:
            cells[visited[finished[region]]] = False


def _grow(graph: CellGraph, cells: np.ndarray, joined: np.ndarray) -> None:
    """Add to ``cells`` (a component of ``graph`` but for ``joined``, cells that joined the graph) what
    the joined cells next to it connect to it."""
    near = graph.neighbours(joined)
    touching = (cells[np.where(near >= 0, near, 0)] & (near >= 0)).any(axis=1)
    partners = members(graph.stairs_from, joined)
    if partners.any():
        across = graph.stairs_from[partners][cells[graph.stairs_to[partners]]]  # portals beside it
        touching |= members(joined, unique_sorted(across))
    starts = joined[touching]
    if starts.size:
        flood(graph.cell_at, graph.cell_pos, graph.step_offset, graph.stairs_first, graph.stairs_from,
              graph.stairs_to, starts.astype(np.int64), cells)
