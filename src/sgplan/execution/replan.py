"""One plan of a run: from the robot's (cell, automaton state) in the run's current building, over the
run's carried parts (:mod:`sgplan.execution.parts`), as the same :class:`~sgplan.result.PlanResult` that
:func:`sgplan.plan` returns (checked by the independent checker from that state)."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from sgplan.planning.problem import PlanningProblem

if TYPE_CHECKING:
    from sgplan.api import Explained
    from sgplan.execution.view import RunView
    from sgplan.result import PlanResult


def plan_from(run: RunView, cell: tuple[int, int, int], state: int, explained: Explained) -> PlanResult:
    """The optimal plan of ``run``'s mission from ``cell`` ``(row, col, floor)`` in automaton ``state``
    (the state after reading ``cell``'s label) in the run's current building; ``explained``: the
    mission's explanation, made once per mission by the run.

    Raises
    ------
    PlanningError
        ``status="infeasible"`` when no path satisfies the rest of the mission from there.
    """
    from sgplan.api import StagedPlan, finish_plan
    from sgplan.planning.amra import plan as amra_plan
    from sgplan.planning.setups import get_setup
    from sgplan.planning.termination import any_of

    t0 = time.perf_counter()
    options, mission = run.options, run.mission
    uses_guidance = get_setup(options.setup).uses_llm  # a setup without LLM queues never reads it
    problem = PlanningProblem(
        building=run.building, grid=run.grid, labels=run.labels.raster, automaton=mission.automaton,
        start=cell, start_state=state, profile=options.profile,
        guidance=mission.guidance if uses_guidance else None,
        reach_radius_m=run.radii.reach_m, reach_model=options.effective_reach_model,
        ap_descriptions=mission.descriptions, shared=run.parts,
    )
    guidance = "mission" if mission.guidance is not None else None
    staged = StagedPlan(mission, guidance, problem, run.radii, "the run's position", [])
    prepare_s = time.perf_counter() - t0
    found = amra_plan(problem, options.setup, termination=any_of(options.termination(), run.stop_when),
                      prebuild_actions=options.prebuild_actions)
    return finish_plan(found, staged, options, explained, started=t0, prepare_s=prepare_s)
