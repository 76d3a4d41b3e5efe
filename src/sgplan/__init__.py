"""sgplan: optimal scene-graph planning of natural-language missions with LLM guidance.

Data flows one way: scene -> mission -> automaton -> domain -> search -> result. The public API is flat::

    import sgplan
    building = sgplan.load_scene("demo")
    mission = sgplan.mission_from_text("Go to the kitchen, then the bedroom with the clock.", building)
    result = sgplan.plan(building, mission, start="kitchen")
    result.draw("out/quick"); result.write_json("out/quick/plan.json")

Its names are loaded on first use (``import sgplan`` stays cheap: no numpy, numba or scipy until then).
See ``docs/`` and the README for the formats and the semantics.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from sgplan.errors import SgplanError
from sgplan.version import __version__

if TYPE_CHECKING:
    from sgplan.api import (
        Session,
        add_guidance,
        load_mission,
        load_scene,
        mission_from_formula,
        mission_from_text,
        plan,
    )
    from sgplan.execution.run import Run
    from sgplan.options import PlanOptions
    from sgplan.result import PlanResult
    from sgplan.scene.builder import BuildingBuilder
    from sgplan.starts import Point


_LAZY = {
    "load_scene": "sgplan.api",
    "load_mission": "sgplan.api",
    "mission_from_formula": "sgplan.api",
    "mission_from_text": "sgplan.api",
    "add_guidance": "sgplan.api",
    "plan": "sgplan.api",
    "Session": "sgplan.api",
    "PlanOptions": "sgplan.options",
    "Run": "sgplan.execution.run",
    "PlanResult": "sgplan.result",
    "Point": "sgplan.starts",
    "BuildingBuilder": "sgplan.scene.builder",
}
__all__ = [
    "BuildingBuilder", "PlanOptions", "PlanResult", "Point", "Run", "Session", "SgplanError", "__version__",
    "add_guidance", "load_mission", "load_scene", "mission_from_formula", "mission_from_text", "plan",
]


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'sgplan' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    """The public API only (not this module's imports or the subpackages loaded so far)."""
    return sorted(__all__)
