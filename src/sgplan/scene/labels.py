"""Atomic propositions over a building and their label rasters (reference-algorithm.md §2.4).

A :class:`Proposition` is ``enter(room_<uuid>)`` -- true on the cells of that room -- or
``reach(object_<uuid>)`` -- true on the cells from which that object is within the reach radius, under
a reach model (:mod:`sgplan.scene.reach`: ``visible`` by default, the authors' ``box`` window). A label
raster holds, for every cell of every floor (obstacles and outside cells included), the bitmask of the
propositions true there: bit ``i`` is ``propositions[i]``.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from sgplan.errors import FormulaError, MissionError, SceneError
from sgplan.scene.model import Building
from sgplan.scene.reach import DEFAULT_REACH_MODEL, object_reach_cells

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


def proposition_cells(
    building: Building, prop: Proposition, reach_radius_m: float | None = None,
    reach_model: str = DEFAULT_REACH_MODEL,
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
        obj = building.object(uuid=prop.uuid)
        for floor in building.floors:
            parts.append(object_reach_cells(floor, obj, radius, reach_model) + floor.index * rows * cols)
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
    reach_model: str = DEFAULT_REACH_MODEL,
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
    reach_model:
        where an object counts as reached (:mod:`sgplan.scene.reach`): ``"visible"`` or ``"box"``.

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
        [proposition_cells(building, prop, reach_radius_m, reach_model) for prop in propositions],
    )
