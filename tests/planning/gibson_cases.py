"""The shipped Gibson missions as planning problems, and their reference optima.

Built with the product's own loaders (:func:`sgplan.mission.load_mission_folder`,
:func:`sgplan.assembly.make_problem`); used by the tests and benchmarks/planning_gibson.py.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from sgplan.assembly import make_problem
from sgplan.mission import load_mission_folder
from sgplan.options import PlanOptions
from sgplan.planning import PlanningProblem
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.model import Building

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
def scene(root: Path, name: str) -> Building:
    return load_authors_scene(root / name)


def load_case(
    root: Path, name: str, mission: int, start_index: int, profile: str = "authors"
) -> PlanningProblem:
    """The planning problem of ``name`` mission ``mission`` from initial position ``start_index``."""
    building = scene(root, name)
    loaded = load_mission_folder(root / name / "missions" / str(mission), profile=profile)
    start = building.initial_cells[start_index]
    return make_problem(building, loaded, start, PlanOptions(profile=profile)).problem
