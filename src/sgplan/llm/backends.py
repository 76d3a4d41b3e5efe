"""Choosing the translator and guide backends from a CLI-style spec: ``"openai:MODEL"`` or ``"offline"``.

Both kinds satisfy two small protocols (:mod:`sgplan.llm.protocols`), so front ends never care which one
runs:

- :class:`~sgplan.llm.protocols.MissionTranslator`: ``name``, ``translate(text, building)`` returning a
  :class:`~sgplan.llm.protocols.TranslationLike` (``backend``, ``text``, ``grounded_text``, ``tokens``,
  ``formula``, and ``set_aside``: the words of the text not read because they ask nothing), and
  ``starting_on(floor)`` (the translator for a robot starting on that floor: words such as *upstairs* are
  read from there by a backend that can, the others return themselves); implemented by
  :class:`~sgplan.llm.translation.LLMTranslator` and the offline
  :class:`~sgplan.llm.offline.PatternTranslator`, and scored by :mod:`sgplan.llm.evaluate`;
- :class:`~sgplan.llm.protocols.MissionGuide`: ``name`` and ``guide(building, automaton, ap_actions)``
  returning ``{room_uuid: {q: [calls]}}``; implemented by :class:`~sgplan.llm.guidance.LLMGuide` and the
  offline :class:`~sgplan.llm.offline.SymbolicGuide`.

``openai:MODEL`` talks to any OpenAI-compatible server (``base_url``; key and other settings from the
environment or an LLM config file, see docs/llm.md). With a cache directory every call is recorded there
and answered from it when already recorded; ``replay`` answers only from the cache (no network, no key).
``offline`` uses the rule-based backends, which are not language models.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from sgplan.errors import LLMError
from sgplan.llm.client import ChatBackend
from sgplan.llm.protocols import MissionGuide, MissionTranslator
from sgplan.llm.records import RunRecord

OFFLINE = "offline"
OPENAI_PREFIX = "openai:"


@dataclass
class Backends:
    """The backends of one run and the record their calls go to.

    ``chat`` is the chat backend (``None`` offline); ``description`` says in one line what answers, and
    whether it is a language model.
    """

    translator: MissionTranslator
    guide: MissionGuide
    record: RunRecord
    chat: ChatBackend | None
    description: str


def open_backends(
    spec: str = OFFLINE,
    *,
    base_url: str | None = None,
    cache_dir: str | Path | None = None,
    replay: bool = False,
    config_path: str | Path | None = None,
    requests_per_minute: float | None = None,
    deadline_s: float | None = None,
    samples: int = 1,
    max_repairs: int = 3,
    max_concurrency: int = 4,
    mission_text: str | None = None,
    params: Mapping[str, Any] | None = None,
) -> Backends:
    """The translator and guide named by ``spec`` (``"offline"`` or ``"openai:MODEL"``).

    Parameters
    ----------
    base_url, config_path, requests_per_minute, deadline_s:
        Endpoint settings for ``openai:MODEL`` (see :func:`~sgplan.llm.config.load_llm_config`).
    cache_dir, replay:
        Record calls in ``cache_dir`` (answering recorded ones from it); with ``replay``, only answer from it.
    samples, max_repairs, params:
        For the LLM translator (see :class:`~sgplan.llm.translation.LLMTranslator`).
    max_concurrency, mission_text:
        For the LLM guide (see :class:`~sgplan.llm.guidance.LLMGuide`).

    Raises
    ------
    LLMError
        An unknown spec; LLM-only options given with ``offline``; ``replay`` without ``cache_dir``; or an
        endpoint configuration problem (no model, no key for OpenAI's endpoint, a bad config file).
    """
    if spec == OFFLINE:
        given = [
            name
            for name, value in (
                ("--base-url", base_url), ("--cache", cache_dir), ("--replay", replay),
                ("--llm-config", config_path), ("--rpm", requests_per_minute), ("--llm-deadline", deadline_s),
                ("--samples", samples != 1),
            )
            if value
        ]
        if given:
            raise LLMError(
                f"{', '.join(given)} only apply to a language model; with --llm offline leave them out"
            )
        from sgplan.llm.offline import PatternTranslator, SymbolicGuide

        pattern, symbolic = PatternTranslator(), SymbolicGuide()
        description = f"{pattern.name} translator and {symbolic.name} guide (offline, not language models)"
        return Backends(pattern, symbolic, RunRecord(description), None, description)
    if not spec.startswith(OPENAI_PREFIX) or not spec[len(OPENAI_PREFIX):].strip():
        raise LLMError(f"unknown --llm {spec!r}: use 'offline' or 'openai:MODEL' (e.g. openai:gpt-4o)")
    model = spec[len(OPENAI_PREFIX):].strip()
    if replay and cache_dir is None:
        raise LLMError("--replay needs the cache to replay from (--cache DIR)")
    from sgplan.llm.cache import open_chat_backend
    from sgplan.llm.config import load_llm_config
    from sgplan.llm.guidance import LLMGuide
    from sgplan.llm.translation import LLMTranslator

    mode: Literal["live", "record", "replay"] = (
        "replay" if replay else ("record" if cache_dir is not None else "live")
    )
    config = (
        None
        if replay
        else load_llm_config(
            config_path, model=model, base_url=base_url, requests_per_minute=requests_per_minute,
            deadline_s=deadline_s,
        )
    )
    chat = open_chat_backend(mode, config=config, cache_dir=cache_dir, model=model)
    record = RunRecord(chat.label)
    translator = LLMTranslator(chat, record=record, samples=samples, max_repairs=max_repairs, params=params)
    guide = LLMGuide(chat, record=record, mission_text=mission_text, max_concurrency=max_concurrency)
    return Backends(translator, guide, record, chat, f"language model {chat.label}")
