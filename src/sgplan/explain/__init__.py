"""Say back what will be planned: missions explained in plain English, checked against the scene.

Typical use::

    from sgplan.explain import explain_mission
    print(explain_mission(mission, building).text)

See docs/explain.md.
"""

from sgplan.explain.referents import Referent, referent_of, referents_of
from sgplan.explain.render import Explanation, explain_formula, explain_mission

__all__ = ["Referent", "Explanation", "referents_of", "referent_of", "explain_formula", "explain_mission"]
