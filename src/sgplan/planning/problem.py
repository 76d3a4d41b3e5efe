"""A planning problem: scene, grid, labels, automaton, start, semantics profile, optional LLM guidance."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from sgplan.errors import PlanningError
from sgplan.logic.automaton import Automaton
from sgplan.planning.setups import check_profile, reach_model_for
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building

if TYPE_CHECKING:
    from sgplan.planning.shared import SharedParts



@dataclass(eq=False)
class PlanningProblem:
    """Everything one planning query needs.

    Attributes
    ----------
    building:
        the scene graph (rooms, objects, door cells); used by the object/room levels and h_LLM.
    grid:
        the occupancy grid the path moves on.
    labels:
        ``(floors, rows, cols)`` integer bitmasks; bit ``i`` = ``automaton.aps[i]`` holds at the cell.
    automaton:
        the mission DFA (complete table).
    start:
        ``(row, col, floor)`` start cell.
    profile:
        ``"ltlf"`` (default) or ``"authors"``, see :data:`sgplan.planning.setups.PROFILES`.
    guidance:
        optional LLM guidance ``{room_uuid: {q: [call strings]}}`` (llm_heuristic.yaml content).
    reach_radius_m:
        radius (metres) defining the object level's "object reached" regions.
    reach_model:
        where an object counts as reached (:mod:`sgplan.scene.reach`: ``"visible"`` or ``"box"``), for the
        object level's regions as for the labels; ``None`` (default): the profile's
        (:data:`~sgplan.planning.setups.PROFILE_REACH_MODELS`). The labels must be made with the same model.
    ap_descriptions:
        optional names for messages, e.g. ``{"p1": "enter(room_2)"}``.
    shared:
        parts that depend only on the building, shared with the other problems of a
        :class:`sgplan.Session` (:mod:`sgplan.planning.shared`); ``None``: built for this problem alone.
        Parts that are also :class:`~sgplan.planning.domain.KeptParts` (a run's) serve the per-cell parts
        they keep up to date across changes of the building.
    start_state:
        resume a mission part-way: the automaton state at the start cell, its label already read (e.g. a
        plan's state at one of its path cells, or a monitor's). ``None`` (default): the automaton's
        initial state, the start's label read or not as ``profile`` says. Either way the search reads the
        label of every cell it enters.
    """

    building: Building
    grid: OccupancyGrid
    labels: np.ndarray
    automaton: Automaton
    start: tuple[int, int, int]
    profile: str = "ltlf"
    guidance: Mapping | None = None
    reach_radius_m: float = 0.6
    reach_model: str | None = None
    ap_descriptions: Mapping[str, str] = field(default_factory=dict)
    shared: SharedParts | None = None
    start_state: int | None = None
    built_domain: Any = field(default=None, init=False, repr=False)
    """The planning domain :func:`sgplan.planning.domain.domain_of` built for this problem, shared by
    every plan of it (``None`` until then). Typed loosely: the domain sits above the problem."""

    def __post_init__(self) -> None:
        check_profile(self.profile)
        if self.start_state is not None and not 0 <= int(self.start_state) < self.automaton.num_states:
            raise PlanningError(f"start state {self.start_state} does not exist (automaton states 0.."
                                f"{self.automaton.num_states - 1})")
        if tuple(self.labels.shape) != tuple(self.grid.shape):
            raise PlanningError(
                f"label raster has shape {tuple(self.labels.shape)}, the grid {tuple(self.grid.shape)} "
                "(floors, rows, cols); build both from the same building"
            )
        if not np.issubdtype(self.labels.dtype, np.integer):
            raise PlanningError(f"label raster must hold integer bitmasks, got dtype {self.labels.dtype}")
        if not (np.isfinite(self.reach_radius_m) and self.reach_radius_m > 0):
            raise PlanningError(
                f"reach radius must be a positive number of metres, got {self.reach_radius_m}"
            )
        self.reach_model = reach_model_for(self.profile, self.reach_model)
        self.start = tuple(int(v) for v in self.start)  # type: ignore[assignment]

    def ap_name(self, index: int) -> str:
        """Readable name of the automaton's proposition ``index``."""
        ap = self.automaton.aps[index]
        described = self.ap_descriptions.get(ap)
        return f"{ap} ({described})" if described and described != ap else ap
