"""Planning: the hierarchical domain, heuristics, AMRA*, compiled kernels, the path checker.

Typical use::

    problem = PlanningProblem(building, grid, labels, automaton, start=(row, col, floor), guidance=guide)
    result = plan(problem, setup="ALL")       # PlanResult: status, cost_m, path, iterations, timings
"""

from sgplan.planning.amra import SETUPS, IterationRecord, PlanResult, Setup, get_setup, plan
from sgplan.planning.problem import PROFILES, PlanningProblem

__all__ = [
    "PROFILES",
    "SETUPS",
    "IterationRecord",
    "PlanResult",
    "PlanningProblem",
    "Setup",
    "get_setup",
    "plan",
]
