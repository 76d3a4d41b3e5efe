"""Say back what will be planned: missions explained in plain English, checked against the scene.

Typical use::

    from sgplan.explain import explain_mission
    print(explain_mission(mission, building).text)

See docs/explain.md.
"""

from sgplan.explain.entities import Entity, entities_of, entity_of
from sgplan.explain.render import Explanation, explain_formula, explain_mission

__all__ = ["Entity", "Explanation", "entities_of", "entity_of", "explain_formula", "explain_mission"]
