"""The offline pattern translator: controlled English -> grounded text + LLM-style token list. Not an LLM.

It produces what the LLM translation pipeline produces (the prefix token list over ``enter(room_<uuid>)``
/ ``reach(object_<uuid>)``, the grounded text with references replaced by IDs, and the references with
their resolution), but by a fixed grammar (:mod:`.grammar`), deterministically and without any network.
Results carry ``backend = "offline-pattern"`` so every saved mission says what produced it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from sgplan.errors import MissionError
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.discourse import Discourse, Grounded
from sgplan.llm.offline.grounding.floors import ordinal_read_either_way
from sgplan.llm.offline.lexicon import PRONOUNS
from sgplan.llm.offline.meaning.feasible import check_can_be_done
from sgplan.llm.offline.meaning.mission import mission_formula
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.llm.offline.spelling import Spelling
from sgplan.llm.offline.syntax import split_mission
from sgplan.llm.offline.text import tokenize
from sgplan.logic.formula import Formula
from sgplan.logic.tokens import parse_tokens, to_tokens
from sgplan.scene.model import Building

PATTERN_BACKEND = "offline-pattern"


@dataclass(frozen=True)
class Reference:
    """One noun phrase of the mission and what it was grounded to.

    ``start``/``end`` are character offsets into the mission text; ``keys`` the entity IDs
    (``room_2``, ``object_27``) in scene order; ``mode`` whether the mission needs ``the`` one, ``any``
    one or ``all`` of them; ``role`` where the phrase occurs (a goal, something to avoid, a condition, or
    a qualifier inside another phrase such as "the kitchen" in "the sink in the kitchen").
    """

    phrase: str
    start: int
    end: int
    keys: tuple[str, ...]
    mode: Literal["the", "any", "all"]
    role: Literal["goal", "avoid", "condition", "qualifier"]
    descriptions: tuple[str, ...]


@dataclass(frozen=True)
class Translation:
    """The outcome of translating one mission text.

    ``tokens`` is the LLM prefix token list (e.g. ``['AND', 'EVENTUALLY', 'enter(room_2)', ...]``),
    ``formula`` the same as a formula tree, ``grounded_text`` the text with every reference replaced by
    its IDs, ``backend`` the name of what produced it, ``set_aside`` the words not read (context).
    """

    backend: str
    text: str
    grounded_text: str
    tokens: tuple[str, ...]
    formula: Formula
    references: tuple[Reference, ...]
    set_aside: tuple[str, ...] = ()
    """Words of the text set aside unread because they ask nothing (context: *We're hosting dinner tonight.*;
    a list's heading), as typed; the explanation says them back."""


class PatternTranslator:
    """Translate controlled-English missions against a scene without any language model.

    Example
    -------
    >>> t = PatternTranslator().translate("Visit the kitchen, then always avoid the bathroom.", building)
    >>> t.backend, t.tokens  # doctest: +SKIP
    ('offline-pattern', ('AND', 'EVENTUALLY', 'enter(room_11)', 'ALWAYS', 'NOT', 'enter(room_2)'))
    """

    name = PATTERN_BACKEND

    def __init__(self, start_floor: int | None = None) -> None:
        """``start_floor``: the floor the robot starts on, when known; *upstairs* / *downstairs* are relative
        to it (without it they are understood only in a two-floor building)."""
        self.start_floor = start_floor

    def starting_on(self, floor: int | None) -> PatternTranslator:
        """The same translator for a robot starting on ``floor`` (``None``: not known), which *upstairs*,
        *this floor*, *the floor above* are read from (:class:`~sgplan.llm.protocols.MissionTranslator`)."""
        return PatternTranslator(floor)

    def translate(self, text: str, building: Building) -> Translation:
        """Parse, ground and translate ``text``.

        *The first floor* is the lowest floor to some and the one above the ground floor to others: a text
        that counts floors so without naming the ground floor
        (:func:`.grounding.floors.ordinal_read_either_way`) is read both ways; the scene decides when one
        way names nothing it holds, and it is refused when both ways read, differently.

        Raises
        ------
        MissionError
            a phrase the grammar does not understand, a reference matching no room/object, or a
            definite reference ("the bathroom") matching several; the message names the phrase, lists
            the candidates as ``room_<uuid> (floor k)`` and says how to disambiguate.
        """
        ordinal = ordinal_read_either_way(text)
        if ordinal is None:
            return self._translate(text, building, None)
        readings: list[Translation | MissionError] = []
        for counted_from in (0, 1):
            try:
                readings.append(self._translate(text, building, counted_from))
            except MissionError as refusal:
                readings.append(refusal)
        us, british = readings
        if isinstance(us, MissionError):
            if isinstance(british, MissionError):
                raise us
            return british
        if isinstance(british, Translation) and british.tokens != us.tokens:
            raise MissionError(rf.ordinal_floor_either_way(ordinal))
        return us

    def _translate(self, text: str, building: Building, ordinals_from: int | None) -> Translation:
        """:meth:`translate`, with *the first floor* counted from ``ordinals_from`` (0, 1, or ``None``: from
        the text)."""
        vocabulary = SceneVocabulary(building)
        disc = Discourse(vocabulary, text, self.start_floor, ordinals_from=ordinals_from)
        spelling = Spelling(vocabulary.nouns)
        try:
            formula = mission_formula(split_mission(text, vocabulary.nouns, spelling), disc)
        except MissionError as refusal:  # name every unknown word at once, with what it looks like
            raise MissionError(rf.with_suggestions(str(refusal), spelling.did_you_mean(
                t.text for t in tokenize(text)))) from None
        check_can_be_done(formula, building, self.start_floor)
        nps = sorted(disc.references, key=lambda np: np.start)
        tokens = to_tokens(formula)
        # The token list must be exactly what the shared parser reads back; a failure here is a bug.
        parse_tokens(tokens, known=vocabulary.by_key.keys())
        references = tuple(
            Reference(np.phrase, np.start, np.end, tuple(e.key for e in np.entities), np.mode, np.role,
                      tuple(e.describe() for e in np.entities))
            for np in nps
        )
        return Translation(self.name, text, grounded_text(text, nps, vocabulary), tuple(tokens), formula,
                           references, tuple(disc.set_aside))


def grounded_text(text: str, nps: list[Grounded], vocabulary: SceneVocabulary) -> str:
    """``text`` with each outermost noun phrase replaced by its IDs (``room_2 or room_4``, ...).

    Objects located through a room keep it: "the vases in the dining room" -> "object_21, object_22 and
    object_23 in room_10", as in the authors' NL_instructions_uuid.txt.
    """
    out: list[str] = []
    cursor = 0
    for np in sorted(nps, key=lambda n: (n.start, -n.end)):
        if np.start < cursor:
            continue  # a qualifier inside a phrase already replaced
        keys = list(dict.fromkeys(e.key for e in np.entities))
        joiner = "or" if np.mode == "any" else "and"
        joined = keys[0] if len(keys) == 1 else f"{', '.join(keys[:-1])} {joiner} {keys[-1]}"
        if np.room_scoped and np.phrase.lower() not in PRONOUNS:
            rooms = list(dict.fromkeys(e.room_key for e in np.entities if e.kind == "object"))
            joined += " in " + " or ".join(rooms) if len(rooms) > 1 else f" in {rooms[0]}"
        out += [text[cursor : np.start], joined]
        cursor = np.end
    out.append(text[cursor:])
    return "".join(out)
