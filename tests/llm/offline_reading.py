"""Assertions shared by the offline translator's tests: a text means a gold formula (the same language
under the scene's facts, :func:`sgplan.llm.offline.evaluation.same_language`), or it is refused with a
message that contains a given fragment. Gold formulas use the shorthand ``r5`` / ``o23`` for
``enter(room_5)`` / ``reach(object_23)``."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.evaluation import expand_shorthand, same_language
from sgplan.logic import parse_infix
from sgplan.scene.model import Building


def means(text: str, gold: str, building: Building, start_floor: int | None = None) -> None:
    """``text`` translates (robot on ``start_floor`` when given) to a formula meaning ``gold``."""
    formula = PatternTranslator(start_floor).translate(text, building).formula
    same, why = same_language(formula, parse_infix(expand_shorthand(gold)), building)
    assert same, f"{text!r} -> {formula}, expected {gold}: {why}"


def refused(text: str, fragment: str, building: Building, start_floor: int | None = None) -> str:
    """``text`` is refused with a message containing ``fragment``; returns the message."""
    with pytest.raises(MissionError) as info:
        PatternTranslator(start_floor).translate(text, building)
    assert fragment in str(info.value)
    return str(info.value)
