"""Planning: the hierarchical domain, heuristics, AMRA*, compiled kernels, the path checker.

Typical use::

    problem = PlanningProblem(building, grid, labels, automaton, start=(row, col, floor), guidance=guide)
    result = plan(problem, setup="ALL")       # SearchResult: status, cost_m, path, iterations, timings
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from sgplan.planning.amra import IterationRecord, SearchResult, plan
    from sgplan.planning.problem import PlanningProblem
    from sgplan.planning.schedule import WeightSchedule
    from sgplan.planning.setups import PROFILES, SETUPS, Setup, get_setup
    from sgplan.planning.termination import CancelFlag, Deadline, ExpansionLimit, TimeLimit

# Loaded on first use, as in ``sgplan/__init__.py``: importing one module of this package (the checker,
# the problem) must not load the search and its compiled kernels (numba is slow to load).
_LAZY = {
    "IterationRecord": "sgplan.planning.amra", "SearchResult": "sgplan.planning.amra",
    "plan": "sgplan.planning.amra", "PlanningProblem": "sgplan.planning.problem",
    "WeightSchedule": "sgplan.planning.schedule",
    "CancelFlag": "sgplan.planning.termination", "Deadline": "sgplan.planning.termination",
    "ExpansionLimit": "sgplan.planning.termination", "TimeLimit": "sgplan.planning.termination",
    "PROFILES": "sgplan.planning.setups", "SETUPS": "sgplan.planning.setups",
    "Setup": "sgplan.planning.setups", "get_setup": "sgplan.planning.setups",
}

__all__ = [
    "PROFILES",
    "SETUPS",
    "CancelFlag",
    "Deadline",
    "ExpansionLimit",
    "IterationRecord",
    "PlanningProblem",
    "SearchResult",
    "Setup",
    "TimeLimit",
    "WeightSchedule",
    "get_setup",
    "plan",
]


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'sgplan.planning' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
