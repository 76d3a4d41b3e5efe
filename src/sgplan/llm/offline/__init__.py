"""Offline backends, clearly not language models: they make sgplan work with no LLM at all.

- :class:`PatternTranslator` (``"offline-pattern"``): a fixed grammar of controlled English, grounded
  against the scene graph, producing the LLM's prefix token list, the grounded text and the references;
  ambiguous or unknown references are errors that list the candidates (docs/offline.md).
- :class:`SymbolicGuide` (``"offline-symbolic"``): move / reach guidance per (room, automaton state),
  from shortest paths over the room graph and the automaton.
"""

from sgplan.llm.offline.guide import SYMBOLIC_BACKEND, Call, Guidance, SymbolicGuide
from sgplan.llm.offline.translator import PATTERN_BACKEND, PatternTranslator, Reference, Translation

__all__ = [
    "PATTERN_BACKEND", "SYMBOLIC_BACKEND", "PatternTranslator", "SymbolicGuide", "Translation", "Reference",
    "Call", "Guidance",
]
