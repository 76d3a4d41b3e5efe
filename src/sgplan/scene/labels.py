"""Atomic propositions over a building and their label rasters (reference-algorithm.md §2.4).

A :class:`Proposition` is ``enter(room_<uuid>)`` -- true on the cells of that room -- or
``reach(object_<uuid>)`` -- true on the cells within the reach radius of that object. A label raster
holds, for every cell of every floor (obstacles and outside cells included), the bitmask of the
propositions true there: bit ``i`` is ``propositions[i]``.

The reach region is the authors' one: an axis-aligned square (Chebyshev) window of ``int(d / res_x)``
rows and ``int(d / res_y)`` columns (each at least 1) around every cell of the object's footprint on the
category map. It ignores walls and rooms: the robot "reaches" an object seen through a wall.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from sgplan.errors import FormulaError, MissionError, SceneError
from sgplan.scene.dilate import box_dilate
from sgplan.scene.model import Building

PropositionKind = Literal["enter", "reach"]
MAX_PROPOSITIONS = 32
"""Label rasters are unsigned bitmasks of at most 32 bits: one bit per proposition."""

_TOKEN = re.compile(r"^\s*(enter|reach)\s*\(\s*(room|object)_(\d+)\s*\)\s*$")
_ENTITY = {"enter": "room", "reach": "object"}


@dataclass(frozen=True)
class Proposition:
    """An atomic proposition: enter a room or reach an object, named by uuid.

    ``reach_radius_m`` applies to ``reach`` only: ``None`` means the mission's global reach radius.
    """

    kind: PropositionKind
    uuid: int
    reach_radius_m: float | None = None

    def __post_init__(self) -> None:
        if self.kind not in _ENTITY:
            raise FormulaError(f"unknown proposition kind {self.kind!r} (use 'enter' or 'reach')")
        if self.kind == "enter" and self.reach_radius_m is not None:
            raise FormulaError(f"{self.name}: a reach radius only applies to reach(object_...) propositions")
        radius = self.reach_radius_m
        if radius is not None and not (np.isfinite(radius) and radius > 0):
            raise FormulaError(f"{self.name}: reach radius must be a positive number of metres")

    @property
    def name(self) -> str:
        """The token used in formulas and prompts, e.g. ``enter(room_2)`` or ``reach(object_27)``."""
        return f"{self.kind}({_ENTITY[self.kind]}_{self.uuid})"

    @classmethod
    def parse(cls, token: str, reach_radius_m: float | None = None) -> Proposition:
        """Parse ``enter(room_<uuid>)`` or ``reach(object_<uuid>)``.

        Raises
        ------
        FormulaError
            if the token has another shape, or pairs ``enter`` with an object (or ``reach`` with a room).
        """
        match = _TOKEN.match(token)
        if match is None:
            raise FormulaError(
                f"{token!r} is not a proposition: expected enter(room_<uuid>) or reach(object_<uuid>)"
            )
        kind, entity, uuid = match.groups()
        if _ENTITY[kind] != entity:
            raise FormulaError(f"{token!r}: {kind} takes a {_ENTITY[kind]}_<uuid>, not a {entity}")
        return cls(kind, int(uuid), reach_radius_m if kind == "reach" else None)  # type: ignore[arg-type]

    def __str__(self) -> str:
        return self.name


def _check_known(building: Building, propositions: Sequence[Proposition]) -> None:
    unknown = [
        p.name
        for p in propositions
        if not (building.has_room(p.uuid) if p.kind == "enter" else building.has_object(p.uuid))
    ]
    if unknown:
        raise SceneError(
            f"building {building.name!r} has no entity for proposition(s) {', '.join(unknown)}; "
            "check the uuids against the scene (e.g. `sgplan inspect`)"
        )


def reach_half_widths(resolution_m: tuple[float, float], reach_radius_m: float) -> tuple[int, int]:
    """Half-widths ``(rows, cols)`` in cells of the reach window: ``int(d / res)``, at least 1 each."""
    return (
        max(1, int(reach_radius_m / resolution_m[0])),
        max(1, int(reach_radius_m / resolution_m[1])),
    )


def _reach_cells(cat_map: np.ndarray, object_id: int, half: tuple[int, int]) -> np.ndarray:
    """Flat indices (into ``cat_map``) of the cells whose square window of ``half`` cells holds a cell of
    ``object_id``; int64, ascending."""
    footprint = cat_map == object_id
    rows, cols = np.nonzero(footprint.any(axis=1))[0], np.nonzero(footprint.any(axis=0))[0]
    if len(rows) == 0:
        return np.zeros(0, dtype=np.int64)
    # Work in the object's bounding box grown by the window: the rest of the floor is outside.
    r0, r1 = max(0, rows[0] - half[0]), min(cat_map.shape[0], rows[-1] + half[0] + 1)
    c0, c1 = max(0, cols[0] - half[1]), min(cat_map.shape[1], cols[-1] + half[1] + 1)
    rr, cc = np.nonzero(box_dilate(footprint[r0:r1, c0:c1], half))
    return (rr + r0).astype(np.int64) * cat_map.shape[1] + (cc + c0)


def proposition_cells(
    building: Building, prop: Proposition, reach_radius_m: float | None = None
) -> np.ndarray:
    """Flat indices into a ``(floors, rows, cols)`` raster of the cells where ``prop`` holds, ascending;
    int32 when the raster has fewer than 2**31 cells (4 bytes a cell: a session keeps them), else int64.
    The sparse form of one bit of :func:`label_raster` (same arguments, same cells): a reach region is a
    few thousand cells of a raster of millions.

    Raises
    ------
    SceneError, MissionError
        as :func:`label_raster`.
    """
    _check_known(building, [prop])
    rows, cols = building.grid_shape
    parts = []
    if prop.kind == "enter":
        room_id = building.room(uuid=prop.uuid).id
        for floor in building.floors:
            parts.append(np.flatnonzero(floor.room_map == room_id) + floor.index * rows * cols)
    else:
        default_reach = building.reach_radius_m if reach_radius_m is None else reach_radius_m
        radius = prop.reach_radius_m if prop.reach_radius_m is not None else default_reach
        if radius is None or not (np.isfinite(radius) and radius > 0):
            raise MissionError(
                f"{prop.name}: no reach radius (give the proposition one or pass a positive reach_radius_m)"
            )
        object_id = building.object(uuid=prop.uuid).id
        half = reach_half_widths(building.resolution_m, radius)
        for floor in building.floors:
            parts.append(_reach_cells(floor.cat_map, object_id, half) + floor.index * rows * cols)
    dtype = np.int32 if building.num_floors * rows * cols < 2**31 else np.int64
    return np.concatenate(parts).astype(dtype) if parts else np.zeros(0, dtype=dtype)


def label_dtype(count: int) -> type[np.unsignedinteger]:
    """The smallest unsigned dtype with a bit for each of ``count`` propositions (at most
    :data:`MAX_PROPOSITIONS`): uint8 up to 8, uint16 up to 16, else uint32."""
    return np.uint8 if count <= 8 else np.uint16 if count <= 16 else np.uint32


def raster_from_cells(shape: tuple[int, ...], cells: Sequence[np.ndarray]) -> np.ndarray:
    """A label raster of ``shape`` (:func:`label_dtype` of ``len(cells)``) with bit ``i`` set at the flat
    indices ``cells[i]`` (e.g. :func:`proposition_cells` of proposition ``i``)."""
    dtype = label_dtype(len(cells))
    labels = np.zeros(shape, dtype=dtype)
    flat = labels.reshape(-1)
    for bit, where in enumerate(cells):
        flat[where] |= dtype(1 << bit)
    return labels


def label_raster(
    building: Building,
    propositions: Sequence[Proposition],
    reach_radius_m: float | None = None,
) -> np.ndarray:
    """The label of every cell: ``(floors, rows, cols)``, bit ``i`` = ``propositions[i]`` holds; the
    smallest unsigned dtype with a bit per proposition (:func:`label_dtype`: a raster is a byte a cell
    for most missions instead of four).

    Parameters
    ----------
    building:
        the scene; its rasters store Gibson ids, the propositions name uuids.
    propositions:
        at most 32, in bit order.
    reach_radius_m:
        the global reach radius (metres) for ``reach`` propositions without their own; defaults to the
        building's ``reach_radius_m``.

    Raises
    ------
    SceneError
        naming every proposition whose uuid is not a room (enter) / object (reach) of the building.
    MissionError
        for more than 32 propositions, or a reach proposition with no radius at all.
    """
    if len(propositions) > MAX_PROPOSITIONS:
        raise MissionError(
            f"{len(propositions)} propositions given; label rasters hold at most {MAX_PROPOSITIONS}"
        )
    _check_known(building, propositions)
    return raster_from_cells(
        (building.num_floors, *building.grid_shape),
        [proposition_cells(building, prop, reach_radius_m) for prop in propositions],
    )
