"""Where an object is within reach: the two reach models, the one place that decides it.

A reach model turns an object, a floor's rasters and a reach radius ``d`` (metres) into the cells from
which the object counts as reached (``reach(object_<uuid>)`` holds there). Cells are compared by their
centres; ``res_r`` / ``res_c`` are the metres per row / column.

``box`` -- the authors' model (reference-algorithm.md §2.4), kept so that their numbers stay
    reproducible (the default of the ``authors`` profile). A cell reaches the object when an object cell
    lies in the axis-aligned window of ``int(d / res_r)`` rows and ``int(d / res_c)`` columns (each at
    least 1) around it. The window's corners lie up to ``d * sqrt(2)`` away, and walls do not stop it:
    an object is "reached" from the next room.

``visible`` -- sgplan's model (the default of the ``ltlf`` profile). A cell reaches the object when it
    is one of the object's cells, or when it is a floor cell (category ``GROUND``) and some object cell
    ``t`` satisfies both:

    - *within the radius*: ``sqrt((dr * res_r) ** 2 + (dc * res_c) ** 2) <= d`` in float64, ``(dr, dc)``
      the row and column offsets between the two cells (:func:`sgplan.scene.dilate.radius_widths`);
    - *in sight*: the straight segment between the two centres crosses no opaque cell. A segment crosses
      a cell when it meets the cell's open square, so a segment through a cell corner crosses only the
      diagonal cell, as the planner's diagonal step and the simplified waypoints' line-of-sight test do.

    Opaque are the raw category map's non-floor cells (walls, other objects, stairs, outside) -- not the
    obstacles inflated by the robot's radius: one reaches over the margin the robot keeps -- except the
    object's own cells and the non-floor cells of the object's own room. Those stay see-through because
    the category maps draw unlabelled furniture as wall: a sink sits inside a counter, a vase on a
    sideboard, and counting them as walls would put half the Gibson objects out of every robot's reach.
    A wall or a piece of furniture of another room, or the outside, blocks the line. Cells other than
    floor (walls, furniture) never reach an object they are not part of: a robot stands on floor.

Both give the cells of every floor (the object's footprint is looked up on each, as the C++ does) as flat
indices into a ``(rows, cols)`` floor raster, ascending.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from sgplan.scene.dilate import box_dilate, radius_widths, within_distance
from sgplan.scene.model import Building, CatCode, Floor, SceneObject

DEFAULT_REACH_MODEL = "visible"
"""sgplan's model, the one of its default ``ltlf`` profile. The models' names, and which one each semantics
profile uses, are in :mod:`sgplan.planning.setups` (``REACH_MODELS``, ``PROFILE_REACH_MODELS``)."""


def reach_half_widths(resolution_m: tuple[float, float], reach_radius_m: float) -> tuple[int, int]:
    """Half-widths ``(rows, cols)`` in cells of the ``box`` model's window: ``int(d / res)``, at least 1
    each (truncated as the authors' C++ does: ``int(0.6 / 0.05)`` is 11)."""
    return (
        max(1, int(reach_radius_m / resolution_m[0])),
        max(1, int(reach_radius_m / resolution_m[1])),
    )


def object_reach_cells(floor: Floor, obj: SceneObject, reach_radius_m: float, model: str,
                       among: np.ndarray | None = None) -> np.ndarray:
    """Flat indices (into ``floor``'s ``(rows, cols)`` rasters) of the cells from which ``obj`` is within
    ``reach_radius_m`` metres under ``model`` (``"box"`` or ``"visible"``); int64, ascending; empty when
    the object has no cell on this floor's category map.

    ``among``: a ``(rows, cols)`` bool raster; only its cells are decided (the others are left out), e.g.
    the free cells of a room. The cells kept are those of the whole region that lie in it, found for
    less work: a cell's line of sight never depends on the other cells' answers.

    Raises
    ------
    ValueError
        for another model (user input is checked before, :func:`sgplan.planning.setups.reach_model_for`).
    """
    footprint = floor.cat_map == obj.id
    bounds = reach_window(floor, obj, reach_radius_m, model, footprint)
    if bounds is None:
        return np.zeros(0, dtype=np.int64)
    (r0, r1), (c0, c1) = bounds
    cat_map = floor.cat_map
    window = (slice(r0, r1), slice(c0, c1))
    decide = None if among is None else among[window]
    if model == "box":
        reached = box_dilate(footprint[window], reach_half_widths(floor.resolution_m, reach_radius_m))
    else:
        reached = _visible(cat_map[window], floor.room_map[window], obj, floor.resolution_m, reach_radius_m,
                           decide)
    if decide is not None:
        reached &= decide
    rr, cc = np.nonzero(reached)
    return (rr + r0).astype(np.int64) * cat_map.shape[1] + (cc + c0)


def reach_window(floor: Floor, obj: SceneObject, reach_radius_m: float, model: str = DEFAULT_REACH_MODEL,
                 footprint: np.ndarray | None = None
                 ) -> tuple[tuple[int, int], tuple[int, int]] | None:
    """``((row0, row1), (col0, col1))``, half-open: the part of ``floor`` that ``model`` looks at for
    ``obj`` -- its footprint's bounding box grown by the reach (``int(d / res)`` cells per axis for the box,
    one more for ``visible``, whose float test decides at the edge), clipped to the floor. Every cell
    that reaches the object lies in it, and so does every line of sight (between two of its cells).
    ``None`` when the object has no cell on the floor. ``footprint``: ``floor.cat_map == obj.id``, if
    already made.

    Raises
    ------
    ValueError
        for another model (user input is checked before, :func:`sgplan.planning.setups.reach_model_for`).
    """
    if model not in ("box", "visible"):
        raise ValueError(f"unknown reach model {model!r}")
    footprint = floor.cat_map == obj.id if footprint is None else footprint
    rows, cols = np.nonzero(footprint.any(axis=1))[0], np.nonzero(footprint.any(axis=0))[0]
    if len(rows) == 0:
        return None
    res_r, res_c = floor.resolution_m
    pad = (reach_half_widths(floor.resolution_m, reach_radius_m) if model == "box"
           else (int(reach_radius_m / res_r) + 1, int(reach_radius_m / res_c) + 1))
    height, width = floor.shape
    return ((max(0, int(rows[0]) - pad[0]), min(height, int(rows[-1]) + pad[0] + 1)),
            (max(0, int(cols[0]) - pad[1]), min(width, int(cols[-1]) + pad[1] + 1)))


def sight_may_change(building: Building, obj: SceneObject, changed: Mapping[int, np.ndarray],
                     reach_radius_m: float, model: str) -> bool:
    """Whether cells that changed category (``changed``: floor -> flat positions ``row * cols + col``) can
    change where ``obj`` is reached from without it moving: under ``visible``, one of them lies in its
    :func:`reach_window` (it may block or open a line of sight); under ``box``, never."""
    if model != "visible":
        return False
    floor = building.room(uuid=obj.room_uuid).floor
    cells = changed.get(floor)
    if cells is None or not cells.size:
        return False
    rows, cols = np.divmod(cells, building.grid_shape[1])
    # The bounding box the scene records, grown by the reach, holds the window: most objects stop here,
    # before their footprint is looked up on the floor's map.
    pad = [int(reach_radius_m / res) + 2 for res in building.floors[floor].resolution_m]
    (r0, c0), (r1, c1) = obj.grid_min, obj.grid_max
    near = (rows >= r0 - pad[0]) & (rows <= r1 + pad[0]) & (cols >= c0 - pad[1]) & (cols <= c1 + pad[1])
    if not near.any():
        return False
    window = reach_window(building.floors[floor], obj, reach_radius_m, model)
    if window is None:
        return False
    (r0, r1), (c0, c1) = window
    return bool(((rows >= r0) & (rows < r1) & (cols >= c0) & (cols < c1)).any())


def _visible(cat: np.ndarray, room: np.ndarray, obj: SceneObject, resolution_m: tuple[float, float],
             reach_radius_m: float, decide: np.ndarray | None) -> np.ndarray:
    """The ``visible`` model on one window of the rasters (bool, the window's shape); only the floor cells
    of ``decide`` are looked from when it is given."""
    from sgplan.scene._sight import visible_cells  # numba loads when a visible region is first made

    target = cat == obj.id
    floor = cat == CatCode.GROUND
    opaque = ~floor & ~target & (room != obj.room_id)
    viewers = floor & within_distance(target, resolution_m, reach_radius_m)
    if decide is not None:
        viewers &= decide
    widest = radius_widths(resolution_m, reach_radius_m, *cat.shape)
    return target | visible_cells(opaque, target, viewers, widest)
