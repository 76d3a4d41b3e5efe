"""Translation (LLM calls 1 and 2): mission text -> grounded text -> checked prefix token list -> DFA.

Pipeline (SYSTEM.md §3 steps 1-5), for one sample:

1. :func:`~sgplan.llm.grounding.ground_mission`: the text with every reference replaced by its ID;
2. the IDs of the grounded text (regex) and the grounded text go to the translation prompt;
3. the reply's list is parsed with :func:`sgplan.logic.parse_tokens` restricted to those IDs, so an
   operator short of operands, a leftover token, a malformed or invented ID are all precise errors;
4. a parsed formula whose automaton is too large, accepts nothing or accepts every path (it asks nothing)
   is an error too;
5. an error is sent back with the repair prompt (the error and the list with the faulty token marked), at
   most ``max_repairs`` times; then the mission is refused with a :class:`RephraseError`.

A wrong formula is never accepted: the only way out of the loop is a formula that parses over the
grounded IDs, is satisfiable and is not a tautology. With ``samples > 1`` translation runs that many times
(with seeds 0..k-1) and the formulas are grouped by language equivalence of their automata (not by string
equality); the largest group wins if it holds more than half of all the samples (a failed sample counts
against every group), otherwise the mission is refused. Warnings (first-cell-only conjuncts, NEXT,
non-co-safe parts, IDs of the grounded text that the formula does not use) are kept, not fatal.

:class:`LLMTranslator` has the same ``translate(text, building)`` contract as the offline
:class:`~sgplan.llm.offline.PatternTranslator`; :func:`translate_to_folder` runs either and saves the
mission folder in the authors' layout plus the run record.
"""

from __future__ import annotations

import contextlib
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from sgplan.errors import AutomatonError, FormulaError, LLMError, MissionError, SgplanError
from sgplan.explain import explain_mission
from sgplan.files import rebuild_folder, write_text_atomically
from sgplan.llm.client import ChatBackend
from sgplan.llm.config import one_line
from sgplan.llm.grounding import (
    DEFAULT_PARAMS,
    Grounding,
    RephraseError,
    environment_text,
    extract_ids,
    ground_mission,
    strip_fences,
)
from sgplan.llm.offline.evaluation import same_language
from sgplan.llm.prompts import load_prompt
from sgplan.llm.records import RunRecord
from sgplan.logic import (
    Formula,
    Not,
    atoms,
    distances_to_accept,
    formula_warnings,
    non_cosafe_parts,
    parse_tokens,
    to_infix,
    to_tokens,
)
from sgplan.logic.tokens import action_entity, as_token_list
from sgplan.mission import Mission, compile_mission, save_mission_folder
from sgplan.scene.model import Building

if TYPE_CHECKING:
    from sgplan.llm.protocols import MissionTranslator, TranslationLike

SAMPLING_TEMPERATURE = 0.7
"""Temperature of the translation calls when several samples are voted on and none is given."""

RECORD_NAME = "llm_record.json"
"""The run record's file name in a mission folder."""

REFUSED_RECORD_NAME = "llm_refused_record.json"
"""The run record of a refused translation: written beside an earlier mission's files, never over them."""

GUIDANCE_RECORD_NAME = "llm_guidance_record.json"
"""The run record of ``sgplan guide``'s LLM calls, beside the guidance it wrote."""

GUIDANCE_FILES = ("llm_heuristic.yaml", GUIDANCE_RECORD_NAME)
"""What ``sgplan guide`` (or ``plan --save-mission``) adds to a mission folder; it fits that mission only."""


@dataclass(frozen=True)
class LLMTranslation:
    """A translation accepted by the checks.

    ``backend`` names what produced it; ``tokens`` is the accepted list (operators upper case, actions
    canonical); ``votes`` the sizes of the equivalence classes of the samples, largest first (``(1,)``
    without voting); ``repairs`` how many repair rounds the winning sample needed.
    """

    backend: str
    text: str
    grounded_text: str
    ids: tuple[str, ...]
    tokens: tuple[str, ...]
    formula: Formula
    warnings: tuple[str, ...]
    votes: tuple[int, ...]
    repairs: int
    set_aside: tuple[str, ...] = ()
    """Words of the text not read (a language model reads all of it: none)."""


def reply_token_list(reply: str) -> list[str]:
    """The token list in a reply: the text from its first ``[`` to its last ``]`` (fences stripped).

    Raises :class:`FormulaError` when there is no bracketed list or it is not a list of strings.
    """
    text = strip_fences(reply)
    start, end = text.find("["), text.rfind("]")
    if start < 0 or end < start:
        raise FormulaError(
            "the reply contains no list [...]; reply with the Python list of quoted tokens only"
        )
    return as_token_list(text[start : end + 1])


def mark_token(tokens: list[str] | None, reply: str, position: int | None) -> str:
    """The bad list for the repair prompt, the faulty token (``position``) followed by ``<-- here``."""
    if tokens is None:
        return one_line(reply, 2000)
    shown = [repr(t) + ("  <-- here" if i == position else "") for i, t in enumerate(tokens)]
    return "[" + ", ".join(shown) + "]"


def _accepts_nothing(formula: Formula) -> bool:
    """Whether no path satisfies ``formula`` (rooms mutually exclusive).

    Raises :class:`FormulaError` when the automaton is too large to build, so that it is repaired too.
    """
    try:
        automaton = compile_mission(formula).automaton
    except AutomatonError as exc:
        raise FormulaError(f"{exc}; write a shorter formula for the same mission") from None
    return not np.isfinite(distances_to_accept(automaton)[automaton.initial])


def check_formula(tokens: list[str], ids: tuple[str, ...]) -> tuple[Formula, list[str]]:
    """Parse ``tokens`` over the grounded ``ids`` and check that the formula asks something possible.

    Returns the formula and its warnings. Raises :class:`FormulaError` (with the token position where
    there is one) for anything that must be repaired: a parse error, an automaton too large to build, a
    formula that no path satisfies and one that every path satisfies (it asks nothing of the robot).
    """
    formula = parse_tokens(tokens, known=ids)
    rooms = [p for p in atoms(formula) if p.startswith("enter(")]
    if _accepts_nothing(formula):
        raise FormulaError(
            f"the formula {to_infix(formula)} can never be satisfied by any path (with one room at a time: "
            f"{', '.join(rooms) or 'no rooms'}); the mission surely means something else"
        )
    if _accepts_nothing(Not(formula)):
        raise FormulaError(
            f"the formula {to_infix(formula)} is satisfied by every path (with one room at a time: "
            f"{', '.join(rooms) or 'no rooms'}), so it asks nothing of the robot; the mission surely means "
            "something else"
        )
    warnings = formula_warnings(formula)
    warnings += [f"'{to_infix(part)}' is not co-safe: it constrains the whole path"
                 for part in non_cosafe_parts(formula)]
    used = {action_entity(a) for a in atoms(formula)}
    unused = [key for key in ids if key not in used]
    if unused:
        warnings.append(f"the grounded mission names {', '.join(unused)}, which the formula does not use")
    return formula, warnings


@dataclass(frozen=True)
class _Sample:
    tokens: tuple[str, ...]
    formula: Formula
    warnings: tuple[str, ...]
    repairs: int


def _translate_once(
    grounding: Grounding,
    backend: ChatBackend,
    record: RunRecord,
    *,
    max_repairs: int,
    params: Mapping[str, Any],
    sample: int,
) -> _Sample:
    """One translation with its repair loop (module docstring, steps 2-5)."""
    prompt, repair = load_prompt("translation"), load_prompt("repair")
    id_list = "[" + ", ".join(grounding.ids) + "]"
    messages = prompt.messages(ids=id_list, grounded=grounding.grounded_text)
    version = prompt.version
    last_error = ""
    for attempt in range(max_repairs + 1):
        step = "translation" if attempt == 0 else "repair"
        index, result = record.complete(backend, messages, params, step=step, prompt_version=version,
                                        context={"sample": sample, "attempt": attempt})
        tokens: list[str] | None = None
        try:
            tokens = reply_token_list(result.content)
            formula, warnings = check_formula(tokens, grounding.ids)
        except FormulaError as exc:
            record.event("formula-rejected", call=index, sample=sample, error=str(exc), position=exc.position)
            last_error = str(exc)
            messages = [
                *messages,
                {"role": "assistant", "content": result.content},
                *repair.messages(
                    error=last_error, marked=mark_token(tokens, result.content, exc.position), ids=id_list
                ),
            ]
            version = repair.version
            continue
        canonical = tuple(to_tokens(formula))
        record.event("formula-accepted", call=index, sample=sample, tokens=list(canonical),
                     formula=to_infix(formula), warnings=warnings, repairs=attempt)
        return _Sample(canonical, formula, tuple(warnings), attempt)
    raise RephraseError(
        f"the model gave no valid formula for {one_line(grounding.text, 120)!r} in {max_repairs + 1} "
        "attempts "
        f"(last error: {last_error}); rephrase the mission in simpler sentences (one goal each) or use "
        "another model"
    )


def _vote(samples: list[_Sample], total: int) -> tuple[_Sample, tuple[int, ...]]:
    """The representative of the largest class of language-equivalent samples, and the class sizes.

    ``total`` is the number of samples asked for, failed ones included: the winning class must hold more
    than half of them, so a few successes among many failures do not decide the mission.

    Raises :class:`RephraseError` when no class holds such a majority.
    """
    classes: list[list[_Sample]] = []
    for s in samples:
        home = next((c for c in classes if same_language(c[0].formula, s.formula)[0]), None)
        if home is None:
            classes.append([s])
        else:
            home.append(s)
    classes.sort(key=len, reverse=True)
    sizes = tuple(len(c) for c in classes)
    if 2 * sizes[0] <= total:
        shown = "; ".join(f"{to_infix(c[0].formula)} ({len(c)}x)" for c in classes[:3])
        failed = total - len(samples)
        raise RephraseError(
            f"the {total} translations have no majority ({shown}{f'; {failed} failed' if failed else ''}); "
            "the mission is read in several ways or is hard to translate: rephrase it more precisely"
        )
    return classes[0][0], sizes


class LLMTranslator:
    """Translate missions with a language model: grounding, translation, checks, repair, optional vote.

    Parameters
    ----------
    backend:
        Any :class:`~sgplan.llm.client.ChatBackend` (live client, record/replay cache, a test double).
    record:
        Where calls and events go; a fresh :class:`RunRecord` by default (see :attr:`record`).
    samples:
        Translations to vote on (grounding is done once); a reading wins with more than half of them,
        failed ones included. With more than one, calls use seeds
        ``0..samples-1`` and, unless ``params`` sets one, temperature :data:`SAMPLING_TEMPERATURE`.
    max_repairs:
        Repair rounds per sample (and unusable grounding replies sent back) before refusing.
    params:
        Sampling parameters of every call (default ``temperature=0``).

    Example
    -------
    >>> text = "Visit the kitchen, then avoid the bathroom."
    >>> t = LLMTranslator(backend).translate(text, building)  # doctest: +SKIP
    >>> t.tokens  # doctest: +SKIP
    ('AND', 'EVENTUALLY', 'enter(room_4)', 'ALWAYS', 'NOT', 'enter(room_5)')
    """

    def __init__(
        self,
        backend: ChatBackend,
        *,
        record: RunRecord | None = None,
        samples: int = 1,
        max_repairs: int = 3,
        params: Mapping[str, Any] | None = None,
    ) -> None:
        if samples < 1 or max_repairs < 0:
            raise ValueError("samples must be >= 1 and max_repairs >= 0")
        self.backend = backend
        self.record = record if record is not None else RunRecord(backend.label)
        self.samples = samples
        self.max_repairs = max_repairs
        self.grounding_params = dict(DEFAULT_PARAMS if params is None else params)
        self.params = dict(self.grounding_params)
        if samples > 1 and params is None:
            self.params["temperature"] = SAMPLING_TEMPERATURE

    @property
    def name(self) -> str:
        return f"llm:{self.backend.model}"

    def starting_on(self, floor: int | None) -> LLMTranslator:
        """This translator: the prompts do not carry the robot's start floor (see
        :class:`~sgplan.llm.protocols.MissionTranslator`)."""
        return self

    def translate(self, text: str, building: Building) -> LLMTranslation:
        """Ground and translate ``text`` for ``building``; see the module docstring.

        Raises
        ------
        RephraseError
            (a :class:`~sgplan.errors.MissionError`) unresolved/ambiguous references, no valid formula
            after the repairs, or no majority in the vote; the message says what to rephrase.
        LLMError
            The backend failed.
        """
        grounding = ground_mission(text, building, self.backend, self.record, max_repairs=self.max_repairs,
                                   params=self.grounding_params)
        results: list[_Sample] = []
        refusal: RephraseError | None = None
        for k in range(self.samples):
            params = {**self.params, "seed": k} if self.samples > 1 else self.params
            try:
                results.append(_translate_once(grounding, self.backend, self.record,
                                               max_repairs=self.max_repairs, params=params, sample=k))
            except RephraseError as exc:
                refusal = exc
        if not results:
            assert refusal is not None
            raise refusal
        winner, sizes = _vote(results, self.samples)
        if self.samples > 1:
            self.record.event(
                "vote", samples=self.samples, failed=self.samples - len(results), classes=list(sizes),
                winner=to_infix(winner.formula),
            )
        return LLMTranslation(
            self.name, grounding.text, grounding.grounded_text, grounding.ids, winner.tokens, winner.formula,
            winner.warnings, sizes, winner.repairs,
        )


def mission_of(translation: TranslationLike) -> Mission:
    """The mission (minimal DFA, propositions) of a translation from any translator backend."""
    return compile_mission(
        translation.formula, text=translation.text, grounded_text=translation.grounded_text,
        set_aside=translation.set_aside,
    )


def _writable_folder(out: str | Path) -> Path:
    """``out`` as a folder that exists (created if needed) and can be written to.

    Raises :class:`MissionError` naming ``out`` when it is a file or the folder cannot be made or written,
    so that callers learn it before any translation is paid for.
    """
    folder = Path(out)
    if folder.exists() and not folder.is_dir():
        raise MissionError("is a file, not a mission folder: choose a folder to write the mission to", folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OSError as exc:
        raise MissionError(f"cannot write a mission folder here ({exc.strerror or exc})", folder) from None
    return folder


def translate_to_folder(
    text: str,
    building: Building,
    translator: MissionTranslator,
    out: str | Path,
    record: RunRecord,
) -> tuple[TranslationLike, Mission]:
    """Translate ``text`` with ``translator`` (LLM or offline) and save every step under ``out``.

    Writes the authors' mission-folder files (:func:`~sgplan.mission.save_mission_folder`, with the
    attribute hierarchy as ``building_desc.yaml`` and the scene record ``scene.yaml``), ``env_elements.txt``
    (the grounded IDs) and the run record ``llm_record.json`` (with an ``explained`` event holding the
    mission's plain-English
    explanation), and removes what an earlier mission left there for its own automaton
    (:data:`GUIDANCE_FILES`) and an earlier refusal's record. Other files in ``out`` are kept. The new
    folder is built beside ``out`` and swapped in whole (:func:`~sgplan.files.rebuild_folder`), so a
    failure or a crash leaves the earlier mission whole, and concurrent translations into one folder
    leave one of them, never a mix.

    On a refusal (or a failed backend) only the record is written, as :data:`REFUSED_RECORD_NAME`, then
    the error is re-raised: the folder never holds a half-made mission, and an earlier mission in it stays
    whole. Returns the translation and its mission.

    Raises
    ------
    MissionError
        ``out`` is a file, or a folder that cannot be created or written; or the translator refused.
    LLMError
        The backend failed, or the run record cannot be written.
    """
    folder = _writable_folder(out)
    try:
        translation = translator.translate(text, building)
    except SgplanError as exc:
        record.event("refused", error=one_line(exc))
        # The refusal is what the user must read: a record that cannot be saved must not replace it.
        with contextlib.suppress(LLMError):
            record.save(folder / REFUSED_RECORD_NAME)
        raise
    mission = mission_of(translation)
    ids = extract_ids(translation.grounded_text)
    hierarchy = environment_text(building)
    record.event("saved", folder=str(folder), backend=translation.backend, tokens=list(translation.tokens),
                 formula=to_infix(translation.formula), states=mission.automaton.num_states)
    record.event("explained", **explain_mission(mission, building).to_dict())

    def build(staging: Path) -> None:
        save_mission_folder(mission, staging, hierarchy_text=hierarchy, building=building)
        write_text_atomically(staging / "env_elements.txt", "[" + ", ".join(ids) + "]\n")
        record.save(staging / RECORD_NAME)

    # The new mission is built beside the folder and swapped in whole; what an earlier mission left for
    # its own automaton (guidance) or an earlier refusal's record is not carried over.
    dropped = {*GUIDANCE_FILES, REFUSED_RECORD_NAME}
    try:
        rebuild_folder(folder, build, carry_over=lambda name: name not in dropped)
    except OSError as exc:
        raise MissionError(f"cannot write the mission ({exc.strerror or exc}); the folder is unchanged",
                           folder) from None
    return translation, mission
