"""One cell numbering for a whole run: the cell graph of every cell that could ever be traversable,
masked to the cells that are traversable now.

The planner's parts are per-cell arrays (distance fields, action maps, labels) indexed by cell number.
A scene change that renumbered the cells would void all of them; so a run numbers, once, every cell that
a change could make traversable, and no other -- the cells of a room whose robot footprint holds only free
ground and objects (a block or a closed door only covers ground, a removed object's cells take their
surroundings' category: walls, stairs and the outside stay where they are, so do the cells within the
robot's radius of them) and the stairs portals -- and a change only *masks* cells: a cell that is not
traversable now has -1 in
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
from sgplan.scene.grid import OccupancyGrid, free_cells, grid_kernel
from sgplan.scene.model import Building, CatCode


class OutsideNumbering(ValueError):
    """A change made traversable a cell that the run's numbering does not hold (a newer scene graph that
    turned a wall into ground): the run numbers its cells anew."""


def candidate_graph(grid: OccupancyGrid, scene: Building) -> CellGraph:
    """The unmasked graph of every cell of ``grid`` that would be traversable if every object of ``scene``
    were gone (a cell of a room clear, by the robot radius, of the walls, stairs and outside cells), or is
    traversable (a stairs portal): the cells a change could make traversable (see the module), numbered as
    :func:`build_cell_graph` numbers. ``scene``: the building without its blocks and closed doors (a
    :class:`~sgplan.execution.world.SceneState`'s ``scene()``). Costs the inflation of every floor."""
    kernel = grid_kernel(scene, grid.robot_radius_m)
    could = np.stack([free_cells(np.where(floor.cat_map > 0, CatCode.GROUND, floor.cat_map), floor.room_map,
                                 kernel) for floor in scene.floors])
    return build_cell_graph(replace(grid, traversable=could | grid.traversable))


def masked_graph(candidates: CellGraph, traversable: np.ndarray) -> CellGraph:
    """``candidates`` with only the cells traversable in ``traversable`` (``(floors, rows, cols)`` bool, False
    on every non-candidate cell) in the graph. Costs a copy of the padded index and a pass over the
    cells."""
    cell_at = candidates.cell_at.copy()
    blocked = ~traversable.reshape(-1)[candidates.positions()]
    cell_at[candidates.cell_pos[blocked]] = -1
    return replace(candidates, cell_at=cell_at)


def remasked(graph: CellGraph, candidates: CellGraph, change: GridChange, in_place: bool = False
             ) -> tuple[CellGraph, np.ndarray]:
    """``graph`` (a mask of ``candidates``) after ``change``, and the cells (numbers, ascending) that left
    or joined it. Costs work over the changed cells, and a copy of the padded index unless ``in_place``
    (``graph`` itself is changed then: for a caller that holds the only graph still read)."""
    if change.empty:
        return graph, np.zeros(0, dtype=np.int64)
    blocked, freed = candidates.padded(change.blocked), candidates.padded(change.freed)
    cells = np.concatenate([candidates.cell_at[blocked], candidates.cell_at[freed]]).astype(np.int64)
    if (cells < 0).any():
        raise OutsideNumbering("a change made a cell traversable that the run's numbering does not hold")
    cell_at = graph.cell_at if in_place else graph.cell_at.copy()
    cell_at[blocked] = -1
    cell_at[freed] = candidates.cell_at[freed]
    return replace(graph, cell_at=cell_at), np.sort(cells)


def in_graph(graph: CellGraph) -> np.ndarray:
    """``(N,)`` bool: which cells of the numbering are in ``graph`` now."""
    return graph.cell_at[graph.cell_pos] == np.arange(graph.num_cells, dtype=graph.cell_at.dtype)


def in_graph_cells(graph: CellGraph, cells: np.ndarray) -> np.ndarray:
    """Bool per cell of ``cells`` (numbers): whether it is in ``graph`` now."""
    cells = np.asarray(cells, dtype=np.int64)
    return graph.cell_at[graph.cell_pos[cells]] == cells


class LabelMask:
    """The run's graph without the cells of some label bitmasks -- those every move onto which ends the
    mission (a room it forbids): a search never stands there, so the robot's component and the h_LTL
    fields are taken over the rest, where they say what the search can do (a goal the robot can reach
    only through such a room is out of its reach). Kept as a padded index of its own, made once and
    updated at the cells that change (:meth:`update`).
    """

    def __init__(self) -> None:
        self.flags = np.zeros(0, dtype=bool)  # per bitmask: whether its cells are left out
        self._cell_at: np.ndarray | None = None

    def avoided(self, masks: np.ndarray) -> np.ndarray:
        """Bool per bitmask of ``masks``: whether its cells are left out."""
        out = np.zeros(np.shape(masks), dtype=bool)
        listed = masks < self.flags.size
        out[listed] = self.flags[masks[listed]]
        return out

    def set(self, graph: CellGraph, masks: np.ndarray, avoid: np.ndarray) -> bool:
        """Leave out the cells of the bitmasks ``avoid`` (``masks``: every cell's); whether that changed
        which are left out (a pass over the cells when it did)."""
        flags = np.zeros(int(np.max(avoid, initial=-1)) + 1, dtype=bool)
        flags[np.asarray(avoid, dtype=np.int64)] = True
        if np.array_equal(flags, self.flags):
            return False
        self.flags = flags
        self._cell_at = None
        if flags.any():
            self._cell_at = graph.cell_at.copy()
            off = np.flatnonzero(self.avoided(masks))
            self._cell_at[graph.cell_pos[off]] = -1
        return True

    def update(self, graph: CellGraph, cells: np.ndarray, masks: np.ndarray) -> None:
        """Follow a change of ``graph`` or of the labels at ``cells`` (numbers; ``masks`` the bitmask of
        every cell now)."""
        if self._cell_at is None or not cells.size:
            return
        positions = graph.cell_pos[cells]
        keep = (graph.cell_at[positions] == cells) & ~self.avoided(masks[cells])
        self._cell_at[positions] = np.where(keep, cells, -1)

    def of(self, graph: CellGraph) -> CellGraph:
        """``graph`` without the cells left out (``graph`` itself when none are)."""
        return graph if self._cell_at is None else replace(graph, cell_at=self._cell_at)
