"""The words a plan is configured with: the paper's planner setups, the semantics profiles and the reach
models.

Plain data, no numpy or numba: the options (:class:`sgplan.PlanOptions`) and the CLI's parser check setup and
profile names with it without loading the search.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from sgplan.errors import PlanningError

PROFILES = ("ltlf", "authors")
"""``ltlf``: the start cell's label is read (q_start = T(initial, label(start))); ``authors``: it is not
(q_start = initial), as in the authors' planner. Missing-edge behaviour is the automaton table's."""

REACH_MODELS = ("box", "visible")
"""Where an object counts as reached (:mod:`sgplan.scene.reach`): ``box``, the authors' square window;
``visible``, within the radius and in sight (walls block)."""
PROFILE_REACH_MODELS = {"ltlf": "visible", "authors": "box"}
"""The reach model of each profile when none is chosen: ``authors`` keeps the paper's window, so that its
numbers stay reproducible."""

LEVEL_NAMES = ("anchor", "occupancy", "object", "room", "floor")
"""The hierarchy levels by number: 0 the anchor (the union of the others), 1 occupancy .. 4 floor; also the
order of the bench's ``exp_<level>`` result columns."""
LTL, LLM = 0, 1
"""Heuristic kinds of a queue: h_LTL (consistent) and h_LLM (guidance, inadmissible)."""
_HEURISTIC_NAMES = ("LTL", "LLM")


def queue_name(level: int, heuristic: int) -> str:
    """The name of the queue of ``level`` under ``heuristic``, e.g. ``"LLM/room"`` (``PlanResult.queues``,
    the bench's result files); :func:`queue_level_name` reads the level back."""
    return f"{_HEURISTIC_NAMES[heuristic]}/{LEVEL_NAMES[level]}"


def queue_level_name(name: str) -> str:
    """The level of a queue named by :func:`queue_name` (``"LLM/room"`` -> ``"room"``), for result files
    read back, whose queues may be those of an earlier version's setups."""
    return name.rsplit("/", 1)[-1]


@dataclass(frozen=True)
class Setup:
    """A planner configuration: the highest level used and the (level, heuristic) queues, anchor first."""

    name: str
    max_level: int
    queues: tuple[tuple[int, int], ...]

    @property
    def uses_llm(self) -> bool:
        return any(h == LLM for _, h in self.queues)

    @property
    def queue_names(self) -> tuple[str, ...]:
        return tuple(queue_name(level, h) for level, h in self.queues)

    def expansions_by_level(self, expansions: Sequence[int]) -> dict[str, int]:
        """Expansions per queue (in :attr:`queues` order) summed by level, every level of
        :data:`LEVEL_NAMES` present (0 where no queue has it)."""
        by_level = dict.fromkeys(LEVEL_NAMES, 0)
        for (level, _), n in zip(self.queues, expansions):
            by_level[LEVEL_NAMES[level]] += int(n)
        return by_level


# Queue layouts (reference-algorithm.md §7.2), with every (level, LTL) queue merged into the anchor: such a
# queue has the anchor's heuristic, so it holds the anchor's states under the anchor's keys, and since the
# anchor expansion generates every level's successors (and closes the state at every level), expanding a
# state there again only repeats work -- in NO-LLM each state was expanded by up to five queues. What
# remains is the anchor (level 0 = union of levels 1..max_level, h_LTL) and the LLM-guided level queues.
_LLM_LEVELS = tuple((level, LLM) for level in range(1, 5))
SETUPS: dict[str, Setup] = {
    "ALL": Setup("ALL", 4, ((0, LTL),) + _LLM_LEVELS),
    "NO-LLM": Setup("NO-LLM", 4, ((0, LTL),)),
    "A*": Setup("A*", 1, ((0, LTL),)),
    "OCC": Setup("OCC", 4, ((0, LTL), (1, LLM))),
    "OBJ": Setup("OBJ", 4, ((0, LTL), (2, LLM))),
    "ROOM": Setup("ROOM", 4, ((0, LTL), (3, LLM))),
    "FLR": Setup("FLR", 4, ((0, LTL), (4, LLM))),
}
"""The paper's setups (reference-algorithm.md §7.2), (level, LTL) queues merged into the anchor (above)."""
_ALIASES = {"NO_LLM": "NO-LLM", "NOLLM": "NO-LLM", "ASTAR": "A*", "A_STAR": "A*", "A-STAR": "A*"}


def get_setup(name: str) -> Setup:
    """The setup called ``name`` (case-insensitive; ``NO_LLM`` / ``A_STAR`` also accepted).

    Raises
    ------
    PlanningError
        for any other name, listing the setups.
    """
    key = str(name).strip().upper()
    key = _ALIASES.get(key, key)
    if key not in SETUPS:
        raise PlanningError(f"unknown setup {name!r}; use one of {', '.join(SETUPS)}")
    return SETUPS[key]


def check_profile(profile: str) -> str:
    """``profile`` if it is one of :data:`PROFILES` (exactly, lower case).

    Raises
    ------
    PlanningError
        for any other value, listing the profiles.
    """
    if profile not in PROFILES:
        raise PlanningError(f"unknown semantics profile {profile!r}; use one of {', '.join(PROFILES)}")
    return profile


def reach_model_for(profile: str, name: str | None = None) -> str:
    """The reach model ``name`` (any case) if given, else the one of ``profile``
    (:data:`PROFILE_REACH_MODELS`).

    Raises
    ------
    PlanningError
        for an unknown model or profile, listing the known ones.
    """
    if name is None:
        return PROFILE_REACH_MODELS[check_profile(profile)]
    model = str(name).strip().lower()
    if model not in REACH_MODELS:
        raise PlanningError(f"unknown reach model {name!r}; use one of {', '.join(REACH_MODELS)}")
    return model
