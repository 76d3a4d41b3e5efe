"""What every translator and guide backend is, for those that use one without choosing it
(:mod:`sgplan.llm.backends` chooses): the language-model ones (:mod:`sgplan.llm.translation`,
:mod:`sgplan.llm.guidance`) and the offline ones (:mod:`sgplan.llm.offline`) satisfy them."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Protocol

from sgplan.logic import Automaton, Formula
from sgplan.scene.model import Building


class TranslationLike(Protocol):
    """What every translator returns (read-only: the translators return frozen dataclasses)."""

    @property
    def backend(self) -> str: ...
    @property
    def text(self) -> str: ...
    @property
    def grounded_text(self) -> str: ...
    @property
    def tokens(self) -> Sequence[str]: ...
    @property
    def formula(self) -> Formula: ...
    @property
    def set_aside(self) -> tuple[str, ...]: ...


class MissionTranslator(Protocol):
    """Text -> grounded, checked formula for a building; raises MissionError when it cannot.

    ``starting_on(floor)``: the same translator for a robot that starts on ``floor`` (``None``: not known),
    for words relative to the start (*upstairs*, *this floor*); a backend that does not read them returns
    itself.
    """

    @property
    def name(self) -> str: ...

    def translate(self, text: str, building: Building) -> TranslationLike: ...

    def starting_on(self, floor: int | None) -> MissionTranslator: ...


class MissionGuide(Protocol):
    """Automaton -> ``{room_uuid: {q: ["move(a, b)" | "reach(r, o)", ...]}}`` for a building."""

    @property
    def name(self) -> str: ...

    def guide(self, building: Building, automaton: Automaton,
              ap_actions: Mapping[str, str] | None = None) -> Mapping[int, Mapping[int, list[str]]]: ...
