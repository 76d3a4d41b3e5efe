"""Analysis of h_LTL on the 9-unordered-goal scaling target (issue 12): slack of the bound, expansions
per automaton state.

Builds the ``scaling.py --target 9goals`` case in this process, runs a plain A* (weights (1, 1), setup
A*) and prints h(start) / C*, and the anchor expansions grouped by the number of goals still to visit.

    .venv/bin/python benchmarks/goals_analysis.py

With the paper's region-level h_LTL (one region per label) it printed h(start) / C* = 0.52 (11.96 of
23.06 m) and 17.7M expansions, most of them in the states with 4-6 of the 9 goals left (at most 6 labels
are needed: some reach regions overlap): the bound lets the robot teleport inside each region it passes.
With the entry pieces of ltl_heuristic.py: 0.96 and 1.0M expansions, the same optimum.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import scaling


def build_case(target_m: float = 2.0, goals: int = 9, seed: int = 0):
    """The scaling benchmark's unordered ``goals`` case: (problem, seconds to build the domain)."""
    from sgplan import mission_from_formula  # the public one: any source tree has it
    from sgplan.assembly import make_problem
    from sgplan.planning.domain import domain_of
    from sgplan.radii import resolve_radii
    from sgplan.scene.grid import build_occupancy_grid

    building = scaling._building(target_m * 1e6, 1, rooms=max(4, goals), seed=seed)
    objects = list(building.objects())
    picks = [objects[i].key for i in np.random.default_rng(seed).choice(len(objects), goals, replace=False)]
    mission = mission_from_formula(" & ".join(f'F "reach({key})"' for key in picks))
    radii = resolve_radii(building)
    grid = build_occupancy_grid(building, radii.robot_m)
    labels = mission.labels(building, radii.reach_m)
    problem = make_problem(building, mission, (0, 0, 0), grid=grid, labels=labels).problem
    free = np.argwhere(problem.grid.traversable[0])
    centre = free[np.argmin(((free - free.mean(axis=0)) ** 2).sum(axis=1))]
    problem.start = (int(centre[0]), int(centre[1]), 0)
    t0 = time.perf_counter()
    _ = domain_of(problem)
    return problem, time.perf_counter() - t0, radii


def goals_left(domain) -> np.ndarray:
    """``(Q,)`` fewest labels still needed to reach acceptance from each automaton state (BFS)."""
    trans, accepting = domain.trans, domain.accepting
    left = np.where(accepting, 0, -1)
    k = 0
    while (left < 0).any():
        k += 1
        grow = (left < 0) & (left[trans] == k - 1).any(axis=1)
        if not grow.any():
            break
        left[grow] = k
    return left


def closed_per_state(state, iteration: int) -> np.ndarray:
    """``(Q,)`` states closed by the anchor in ``iteration``, from the search's page table."""
    from sgplan.planning import _search

    ptab, pool = state.ptab, state.pool
    out = np.zeros(ptab.shape[0], dtype=np.int64)
    for q in range(ptab.shape[0]):
        slots = ptab[q][ptab[q] >= 0].astype(np.int64)
        if slots.size == 0:
            continue
        recs = (slots[:, None] * _search.PAGE + np.arange(_search.PAGE)[None, :]).ravel() * _search.REC
        meta = pool[recs + 2]
        out[q] = int((((meta >> 40) == iteration) & ((meta >> 32) & 1 == 1)).sum())
    return out


def run_astar(problem):
    """Plain A* (weights (1, 1)); returns (result, captured search state)."""
    from sgplan.planning import _search, plan
    from sgplan.planning.schedule import WeightSchedule

    captured = {}
    original = _search.improve_path

    def spy(G, A, M, L, S, *args):
        captured["S"] = S
        return original(G, A, M, L, S, *args)

    _search.improve_path = spy
    try:
        result = plan(problem, "A*", schedule=WeightSchedule((1.0, 1.0)), prebuild_actions=False)
    finally:
        _search.improve_path = original
    return result, captured["S"]


def main() -> None:
    from sgplan.planning.domain import domain_of

    problem, domain_s, radii = build_case()
    domain = domain_of(problem)
    ltl = domain.ltl
    print(f"free cells {domain.graph.num_cells}, Q {domain.num_states}, leaving labels "
          f"{len(ltl.leaving_labels)}, domain {domain_s:.2f} s ({domain.timings}), reach {radii.reach_m} m, "
          f"cell {problem.grid.resolution_m}")
    h0 = ltl.value(domain.start_cell, domain.q_start)
    result, state = run_astar(problem)
    cost = result.cost_m
    print(f"C* {cost:.4f} m, h(start) {h0:.4f} m, ratio {h0 / cost:.4f}, expansions {result.expansions}, "
          f"search {result.search_s:.2f} s")
    closed = closed_per_state(state, 1)
    left = goals_left(domain)
    print("goals left | states Q | Q with expansions | expansions | per expanded Q")
    for k in range(left.max() + 1):
        sel = left == k
        n = closed[sel]
        print(f"{k:10d} | {sel.sum():8d} | {int((n > 0).sum()):17d} | {int(n.sum()):10d} | "
              f"{int(n.sum()) / max(1, int((n > 0).sum())):.0f}")


if __name__ == "__main__":
    main()
