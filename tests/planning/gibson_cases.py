"""Load one shipped Gibson mission (authors' folder format) as a :class:`PlanningProblem`.

A small test/benchmark helper: scene folder + missions/<k>/{automaton.aut, ap_desc.yaml,
llm_heuristic.yaml} + radius_config.bash + initial_positions.yaml. The product's own mission loader
lives with the CLI; this keeps the planner's tests independent of it.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import yaml

from sgplan.logic.hoa import read_hoa
from sgplan.planning import PlanningProblem
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import Proposition, label_raster
from sgplan.scene.model import Building
from sgplan.scene.grid import OccupancyGrid

# Optimal costs (m) under the authors profile, reference-algorithm.md §11 "stay" column; None = no path.
STAY_COSTS: dict[tuple[str, int], tuple[float | None, ...]] = {
    ("Allensville", 1): (16.5635, 14.3682, None, 11.5359, 16.9138),
    ("Allensville", 2): (14.2741, 11.9368, None, 11.7496, 13.3304),
    ("Allensville", 3): (5.5538, 17.0072, None, 15.8949, 14.2221),
    ("Allensville", 4): (14.1154, 6.1445, None, 5.1813, 12.5838),
    ("Allensville", 5): (0.7513, 2.4904, None, 0.1898, 6.1617),
    ("Benevolence", 1): (18.8181, None, 20.0308, 27.1902, 29.9788),
    ("Benevolence", 2): (20.3680, None, 5.7536, 13.4630, 16.2516),
    ("Benevolence", 3): (38.7465, None, 24.0577, None, 19.8898),
    ("Benevolence", 4): (28.7514, None, 18.7992, 13.6551, 17.1592),
    ("Benevolence", 5): (20.0487, None, 20.1992, 26.8955, 29.6841),
}


@lru_cache(maxsize=4)
def scene(root: Path, name: str) -> tuple[Building, OccupancyGrid]:
    """The building and its occupancy grid at the scene's own robot radius."""
    building = load_authors_scene(root / name)
    return building, build_occupancy_grid(building, building.robot_radius_m or 0.0)


def load_case(root: Path, name: str, mission: int, start_index: int, profile: str = "authors") -> PlanningProblem:
    """The planning problem of ``name`` mission ``mission`` from initial position ``start_index``."""
    building, grid = scene(root, name)
    folder = root / name / "missions" / str(mission)
    automaton = read_hoa(folder / "automaton.aut", profile=profile)
    desc = yaml.safe_load((folder / "ap_desc.yaml").read_text())
    reach = building.reach_radius_m or 0.6
    props = []
    for ap in automaton.aps:
        entry = desc[ap]
        if entry["type"] == "kEnterRoom":
            props.append(Proposition("enter", int(entry["uuid"])))
        else:
            radius = float(entry.get("reach_distance", -1.0))
            props.append(Proposition("reach", int(entry["uuid"]), radius if radius > 0 else None))
    labels = label_raster(building, props, reach)
    guidance = yaml.safe_load((folder / "llm_heuristic.yaml").read_text())
    return PlanningProblem(
        building=building,
        grid=grid,
        labels=labels,
        automaton=automaton,
        start=tuple(building.initial_cells[start_index]),
        profile=profile,
        guidance=guidance,
        reach_radius_m=reach,
        ap_descriptions={ap: p.name for ap, p in zip(automaton.aps, props)},
    )
