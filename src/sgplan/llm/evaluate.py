"""Scoring any translation backend on a user's own mission set (JSON Lines), for ``sgplan eval-translation``.

The set is a JSONL file, one mission per line::

    {"id": "m1", "scene": "demo", "text": "Go to the kitchen.", "formula": "F \\"enter(room_4)\\""}

``scene`` is ``demo``, a Gibson scene name or a scene folder; ``formula`` is the gold formula in Spot-like
infix over ``"enter(room_N)"`` / ``"reach(object_N)"`` (the shorthand ``r4`` / ``o19`` is accepted too).
A line with ``"formula": null`` and an optional ``"expect_error": "fragment"`` is a mission the backend
must refuse. An optional ``"start_floor"`` (0 = the lowest) says where the robot starts, for words such as
"upstairs" (the offline translator reads them relative to it; a language model gets the text only).
Optional booleans ``"must_pass"`` and ``"paper"`` mark missions a test requires right and the paper's own
texts (:class:`~sgplan.llm.offline.evaluation.EvalMission`). Other fields are kept as they are and ignored.
Blank lines and lines starting with ``#`` are skipped.

A translation is **right** when its automaton accepts exactly the gold's words among those the scene
allows (one room at a time; an object only from its room:
:func:`~sgplan.llm.offline.evaluation.same_language`),
**refused** when the backend raised a :class:`~sgplan.errors.MissionError` (it said it could not), and
**wrong** otherwise: the dangerous case, a formula that does not mean the mission.
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from sgplan.errors import MissionError, SgplanError
from sgplan.llm.offline.evaluation import (
    EvalMission,
    EvalResult,
    evaluate,
    expand_shorthand,
    scene_facts,
)
from sgplan.llm.protocols import MissionTranslator
from sgplan.logic import atoms, parse_infix, to_infix
from sgplan.logic.formula import Formula
from sgplan.scene.model import Building

Explainer = Callable[[Formula, Building], str]
"""Plain words for a formula over a scene's IDs."""


def load_jsonl_set(path: str | Path) -> list[EvalMission]:
    """Read a JSONL mission set (see the module docstring).

    Raises
    ------
    MissionError
        naming the file and the line: not JSON, not an object, a missing ``id`` / ``scene`` / ``text``,
        a missing ``formula`` key, a gold formula that does not parse, or a repeated id.
    """
    path = Path(path)
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except OSError as exc:
        raise MissionError(f"cannot read the mission set: {exc.strerror or exc}", path) from None
    missions: list[EvalMission] = []
    seen: set[str] = set()
    for number, line in enumerate(lines, start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        where = f"line {number}"
        try:
            entry = json.loads(line)
        except ValueError as exc:
            raise MissionError(f"{where}: not JSON ({exc})", path) from None
        if not isinstance(entry, dict) or not {"id", "scene", "text", "formula"} <= entry.keys():
            raise MissionError(f"{where}: expected an object with id, scene, text and formula "
                               f"(formula null for a mission that must be refused)", path)
        mission_id = str(entry["id"])
        if mission_id in seen:
            raise MissionError(f"{where}: the id {mission_id!r} is used twice", path)
        seen.add(mission_id)
        gold = None
        if entry["formula"] is not None:
            try:
                gold = parse_infix(expand_shorthand(str(entry["formula"])))
            except SgplanError as exc:
                raise MissionError(
                    f"{where} (mission {mission_id!r}): the gold formula does not parse: {exc}", path
                ) from None
        expect_error = None if gold is not None else str(entry.get("expect_error") or "")
        start_floor = entry.get("start_floor")
        if start_floor is not None and (not isinstance(start_floor, int) or start_floor < 0):
            raise MissionError(
                f"{where} (mission {mission_id!r}): start_floor must be a floor number (0 = the "
                f"lowest), got {start_floor!r}",
                path,
            )
        missions.append(EvalMission(mission_id, str(entry["scene"]), str(entry["text"]), gold, expect_error,
                                    must_pass=bool(entry.get("must_pass", False)),
                                    paper=bool(entry.get("paper", False)), note=str(entry.get("note", "")),
                                    start_floor=start_floor))
    if not missions:
        raise MissionError("the mission set holds no mission", path)
    return missions


@dataclass(frozen=True)
class TranslationScore:
    """The outcome of scoring one backend on one set: per-mission results and the explanations of the
    wrong ones (gold and translation, in plain words, keyed by mission id)."""

    backend: str
    set_path: str
    results: tuple[EvalResult, ...]
    explanations: dict[str, tuple[str, str]]

    @property
    def counts(self) -> Counter[str]:
        """``right`` / ``wrong`` / ``refused`` -> number of missions."""
        return Counter({"right": 0, "wrong": 0, "refused": 0}) + Counter(r.outcome for r in self.results)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready report: backend, set, counts, and every mission with its outcome."""
        missions = []
        for r in self.results:
            entry: dict[str, Any] = {
                "id": r.mission.id, "scene": r.mission.scene, "text": r.mission.text, "outcome": r.outcome,
                "gold": to_infix(r.mission.gold) if r.mission.gold is not None else None,
                "translation": to_infix(r.formula) if r.formula is not None else None, "detail": r.detail,
            }
            if r.mission.id in self.explanations:
                entry["gold_explanation"], entry["translation_explanation"] = self.explanations[r.mission.id]
            missions.append(entry)
        return {"backend": self.backend, "set": self.set_path, "total": len(self.results),
                "counts": dict(self.counts), "missions": missions}


def infix_explainer(formula: Formula, building: Building) -> str:
    """The formula itself in infix, for when no plain-words explanation is at hand."""
    return to_infix(formula)


def score_translator(
    translator: MissionTranslator,
    missions: Iterable[EvalMission],
    building_of: Callable[[str], Building],
    *,
    set_path: str = "",
    explain: Explainer = infix_explainer,
    progress: Callable[[EvalResult], None] | None = None,
) -> TranslationScore:
    """Translate every mission with ``translator`` and score it (see the module docstring).

    ``building_of`` maps a mission's ``scene`` to its building (it is called once per mission; cache it);
    ``explain`` renders the gold and the translation of each wrong mission; ``progress`` is called after
    each mission.

    Raises
    ------
    MissionError
        a gold formula naming a room or object the mission's scene does not have.
    SgplanError
        whatever the backend raises other than a refusal (a server that cannot be reached, a replay cache
        without the call): the score would be meaningless, so it is not hidden.
    """
    results: list[EvalResult] = []
    explanations: dict[str, tuple[str, str]] = {}
    for mission in missions:
        if mission.gold is not None:
            try:
                scene_facts(atoms(mission.gold), building_of(mission.scene))
            except MissionError as exc:
                raise MissionError(
                    f"mission {mission.id!r}: the gold formula: {exc}", set_path or None
                ) from None
        (result,) = evaluate(translator, [mission], building_of)
        results.append(result)
        if result.outcome == "wrong" and result.formula is not None and mission.gold is not None:
            building = building_of(mission.scene)
            explanations[mission.id] = (explain(mission.gold, building), explain(result.formula, building))
        if progress is not None:
            progress(result)
    return TranslationScore(translator.name, set_path, tuple(results), explanations)
