"""Grounding: which rooms and objects of the scene each phrase of the syntax tree denotes, given what was
said before it (:class:`.discourse.Discourse`); the refusals of what matches nothing, or several where one
is meant."""

from sgplan.llm.offline.grounding import described as _described  # noqa: F401  (registers its grounder)
from sgplan.llm.offline.grounding.discourse import Discourse, Grounded, Where
from sgplan.llm.offline.grounding.phrases import ground_list, ground_phrase

__all__ = ["Discourse", "Grounded", "Where", "ground_list", "ground_phrase"]
