"""One cell numbering for a whole run: the cell graph of every cell that could ever be traversable,
masked to the cells that are traversable now.

The planner's parts are per-cell arrays (distance fields, action maps, labels) indexed by cell number.
A scene change that renumbered the cells would void all of them; so a run numbers, once, every cell that
a change could make traversable -- the cells of a room that are free ground or an object's footprint (a
block only covers ground, a removed object's cells take their surroundings' category, walls stay walls)
and the stairs portals -- and a change only *masks* cells: a cell that is not traversable now has -1 in
the graph's padded raster index (``cell_at``), so no move enters it, no look-up finds it and every search
and Dijkstra of :mod:`sgplan.planning` treats it as absent, while its number and every array entry stay.
A newer scene graph that turns a wall into ground needs a new numbering (:func:`remasked` says so).

A masked cell keeps its position (``cell_pos``), label and room; only ``cell_at`` differs between two
masks of the same numbering, and ``cell_at[cell_pos[c]] == c`` says whether cell ``c`` is in the graph.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from sgplan.execution.regrid import GridChange
from sgplan.planning.cells import CellGraph, build_cell_graph
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building, CatCode


class OutsideNumbering(ValueError):
    """A change made traversable a cell that the run's numbering does not hold (a newer scene graph that
    turned a wall into ground): the run numbers its cells anew."""


def candidate_graph(grid: OccupancyGrid, building: Building) -> CellGraph:
    """The unmasked graph of every cell of ``grid`` that lies in a room and is free ground or an object in
    ``building``, or is traversable (a stairs portal): the cells a change could make traversable
    (see the module), numbered as :func:`build_cell_graph` numbers."""
    cat = np.stack([floor.cat_map for floor in building.floors])
    could = (grid.room_map > 0) & ((cat == CatCode.GROUND) | (cat > 0))
    return build_cell_graph(replace(grid, traversable=could | grid.traversable))


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
    if (cells < 0).any():
        raise OutsideNumbering("a change made a cell traversable that the run's numbering does not hold")
    return replace(graph, cell_at=cell_at), np.sort(cells)


def in_graph(graph: CellGraph) -> np.ndarray:
    """``(N,)`` bool: which cells of the numbering are in ``graph`` now."""
    return graph.cell_at[graph.cell_pos] == np.arange(graph.num_cells, dtype=graph.cell_at.dtype)
