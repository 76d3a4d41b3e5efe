"""One cell numbering for a whole run: the cell graph of every cell that could ever be traversable,
masked to the cells that are traversable now.

The planner's parts are per-cell arrays (distance fields, action maps, labels) indexed by cell number.
A scene change that renumbered the cells would void all of them; so a run numbers, once, every cell that
lies in a room or is a stairs portal -- no change can make any other cell traversable, since changes keep
the rooms -- and a change only *masks* cells: a cell that is not traversable now has -1 in the graph's
padded raster index (``cell_at``), so no move enters it, no look-up finds it and every search and
Dijkstra of :mod:`sgplan.planning` treats it as absent, while its number and every array entry stay.

A masked cell keeps its position (``cell_pos``), label and room; only ``cell_at`` differs between two
masks of the same numbering, and ``cell_at[cell_pos[c]] == c`` says whether cell ``c`` is in the graph.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from sgplan.execution.regrid import GridChange
from sgplan.planning.cells import CellGraph, build_cell_graph
from sgplan.scene.grid import OccupancyGrid


def candidate_graph(grid: OccupancyGrid) -> CellGraph:
    """The unmasked graph of every cell of ``grid`` that is in a room or is a stairs portal (the cells any
    change keeping the rooms could make traversable), numbered as :func:`build_cell_graph` numbers."""
    return build_cell_graph(replace(grid, traversable=(grid.room_map > 0) | grid.traversable))


def masked_graph(candidates: CellGraph, traversable: np.ndarray) -> CellGraph:
    """``candidates`` with only the cells traversable in ``traversable`` (``(floors, rows, cols)`` bool, False
    on every non-candidate cell) in the graph. Costs a copy of the padded index and a pass over the
    cells."""
    cell_at = candidates.cell_at.copy()
    blocked = ~traversable.reshape(-1)[candidates.positions()]
    cell_at[candidates.cell_pos[blocked]] = -1
    return replace(candidates, cell_at=cell_at)


def remasked(graph: CellGraph, candidates: CellGraph, change: GridChange) -> tuple[CellGraph, np.ndarray]:
    """``graph`` (a mask of ``candidates``) after ``change``, and the cells (numbers, ascending) that left
    or joined it. Costs a copy of the padded index and work over the changed cells."""
    if change.empty:
        return graph, np.zeros(0, dtype=np.int64)
    cell_at = graph.cell_at.copy()
    blocked, freed = candidates.padded(change.blocked), candidates.padded(change.freed)
    cell_at[blocked] = -1
    cell_at[freed] = candidates.cell_at[freed]
    cells = np.concatenate([candidates.cell_at[blocked], candidates.cell_at[freed]]).astype(np.int64)
    if (cells < 0).any():  # a cell outside every room and portal became traversable: not a candidate
        raise ValueError("a change made a cell outside the rooms traversable")
    return replace(graph, cell_at=cell_at), np.sort(cells)


def in_graph(graph: CellGraph) -> np.ndarray:
    """``(N,)`` bool: which cells of the numbering are in ``graph`` now."""
    return graph.cell_at[graph.cell_pos] == np.arange(graph.num_cells, dtype=graph.cell_at.dtype)
