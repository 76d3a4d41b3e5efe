"""Why the rest of a mission became impossible, in words: which goal the building now keeps the robot from,
or which forbidden room the only remaining way crosses, and the change that did it."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from sgplan.logic.automaton import Automaton
from sgplan.logic.paths import remaining_mission

if TYPE_CHECKING:
    from sgplan.execution.view import RunView


def _unreachable_goals(run: RunView) -> list[str]:
    """The places the rest of the mission must visit that no cell reachable from the robot offers."""
    from sgplan.explain.referents import referent_of

    automaton = run.mission.automaton
    rest = remaining_mission(automaton, run.state)
    if rest is None:
        return []
    graph = run.parts.graph
    reachable = graph.reachable(graph.cell_id(*run.position))  # through any room: the words say which
    offered = np.bitwise_or.reduce(run.parts.masks[reachable]) if reachable.any() else 0
    needed = sorted({name for step in rest.to_make_true for name in step})
    names = []
    for name in needed:
        bit = automaton.aps.index(name)
        if not int(offered) >> bit & 1:
            names.append(referent_of(name, run.mission.propositions.get(name), run.building).phrase())
    return names


def _scene_findings(run: RunView) -> list[str]:
    """The errors the scene checks find in the rest of the mission from the robot's cell."""
    from sgplan.explain.checks import check_mission_in_scene
    from sgplan.mission import Mission

    a = run.mission.automaton
    formula = run.monitor.words.residual(run.state).formula
    rest = Mission(Automaton(a.aps, a.table, run.state, a.accepting), run.mission.propositions, formula)
    check = check_mission_in_scene(rest, run.building, run.position, grid=run.grid,
                                   labels=run.labels.raster, profile="authors",
                                   reach_model=run.options.effective_reach_model)
    return [finding.message for finding in check.of("error")]


def why_impossible(run: RunView, planner_says: str) -> str:
    """Why no path satisfies the rest of ``run``'s mission from the robot's cell, in a sentence or two;
    ``planner_says``: the planner's own reason, used when nothing more specific is found.

    Cost: a flood fill from the robot's cell and the scene checks of the rest (a few passes over the
    grid)."""
    cut_off = _unreachable_goals(run)
    if cut_off:
        what = f"{', '.join(cut_off)} can no longer be reached from the robot's position"
    else:
        findings = _scene_findings(run)
        what = findings[0] if findings else planner_says
    since = [event.message for event in run.history if event.kind == "changed"]
    return f"{what} (since: {since[-1]})" if since else what
