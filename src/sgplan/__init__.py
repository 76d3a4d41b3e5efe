"""sgplan: optimal scene-graph planning of natural-language missions with LLM guidance.

Data flows one way: scene -> mission -> automaton -> domain -> search -> result. See ``docs/`` and the
README for the formats and the semantics.
"""

from sgplan.errors import SgplanError

__all__ = ["SgplanError", "__version__"]
__version__ = "0.1.0"
