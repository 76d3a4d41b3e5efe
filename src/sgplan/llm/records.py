"""The JSON run record: every LLM call of a pipeline run and every check made on its replies.

A :class:`RunRecord` is filled while grounding, translation and guidance run and saved next to their
output (``llm_record.json`` in a mission folder). It holds, in order:

- ``calls``: one entry per chat call -- the step (``grounding``, ``translation``, ``repair``,
  ``guidance``), the prompt version, the model and backend label, the sampling parameters, the messages,
  the reply (first choice) or the error, ``latency_s`` (retries included; for a cached reply, the latency of
  the recorded call), ``from_cache``, ``attempts``, ``finish_reason`` and token ``usage``, plus a
  ``context`` (e.g. ``{"room": 5, "state": 2}``);
- ``events``: what the pipeline concluded, e.g. a parse error sent for repair, the accepted formula,
  a vote, counts of dropped guidance calls; an event may name the ``call`` index it is about.

Both lists are appended to from several threads (batch guidance), so appends are locked. The format is
documented in docs/llm-pipeline.md; ``format`` names its version.
"""

from __future__ import annotations

import json
import threading
from collections.abc import Mapping, Sequence
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

from sgplan.errors import LLMError
from sgplan.files import write_text_atomically
from sgplan.llm.client import ChatBackend, ChatResult, Message, normalize_messages, normalize_params
from sgplan.llm.config import one_line

RECORD_FORMAT = "sgplan-llm-run/1"


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="seconds")


class RunRecord:
    """The calls and events of one run; see the module docstring.

    Parameters
    ----------
    backend:
        A label for what answered (``"gpt-4o at https://..."``, ``"offline-pattern (not an LLM)"``).
    """

    def __init__(self, backend: str) -> None:
        self.backend = backend
        self.started_at = _now()
        self.calls: list[dict[str, Any]] = []
        self.events: list[dict[str, Any]] = []
        self._lock = threading.Lock()

    def complete(
        self,
        backend: ChatBackend,
        messages: Sequence[Message],
        params: Mapping[str, Any],
        *,
        step: str,
        prompt_version: str,
        context: Mapping[str, Any] | None = None,
    ) -> tuple[int, ChatResult]:
        """Ask ``backend`` and record the call; returns ``(call index, result)``.

        An :class:`LLMError` is recorded, then re-raised.
        """
        try:
            result = backend.complete(messages, **params)
        except LLMError as error:
            self.add_call(
                backend, messages, params, error, step=step, prompt_version=prompt_version, context=context
            )
            raise
        index = self.add_call(backend, messages, params, result, step=step, prompt_version=prompt_version,
                              context=context)
        return index, result

    def add_call(
        self,
        backend: ChatBackend,
        messages: Sequence[Message],
        params: Mapping[str, Any],
        outcome: ChatResult | LLMError,
        *,
        step: str,
        prompt_version: str,
        context: Mapping[str, Any] | None = None,
    ) -> int:
        """Record a call made elsewhere (e.g. by :func:`~sgplan.llm.client.complete_many`); returns its
        index."""
        entry: dict[str, Any] = {
            "step": step,
            "prompt_version": prompt_version,
            "model": backend.model,
            "backend": backend.label,
            "params": normalize_params(params),
            "context": dict(context or {}),
            "messages": normalize_messages(messages),
            "recorded_at": _now(),
        }
        if isinstance(outcome, ChatResult):
            entry.update(
                reply=outcome.content,
                choices=list(outcome.choices) if len(outcome.choices) > 1 else None,
                reply_model=outcome.model,
                finish_reason=outcome.finish_reason,
                usage=dict(outcome.usage) if outcome.usage is not None else None,
                latency_s=outcome.latency_s,
                from_cache=outcome.from_cache,
                attempts=outcome.attempts,
                error=None,
            )
        else:
            entry.update(reply=None, latency_s=None, from_cache=False, error=one_line(outcome))
        with self._lock:
            entry["index"] = len(self.calls)
            self.calls.append(entry)
            return entry["index"]

    def event(self, kind: str, *, call: int | None = None, **data: Any) -> None:
        """Record a pipeline event (``kind`` such as ``"parse-error"``, ``"accepted"``) with JSON-ready
        data."""
        with self._lock:
            self.events.append({"kind": kind, **({"call": call} if call is not None else {}), **data})

    def to_json(self) -> dict[str, Any]:
        """The record as a JSON-ready mapping."""
        with self._lock:
            calls = list(self.calls)
            events = list(self.events)
        from_cache = sum(1 for c in calls if c.get("from_cache"))
        return {
            "format": RECORD_FORMAT,
            "backend": self.backend,
            "started_at": self.started_at,
            "summary": {
                "calls": len(calls),
                "failed_calls": sum(1 for c in calls if c["error"] is not None),
                "from_cache": from_cache,
                "latency_s": sum(c["latency_s"] or 0.0 for c in calls if not c.get("from_cache")),
            },
            "calls": calls,
            "events": events,
        }

    def save(self, path: str | Path) -> Path:
        """Write the record atomically (indented UTF-8 JSON); I/O errors raise :class:`LLMError`."""
        path = Path(path)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            write_text_atomically(path, json.dumps(self.to_json(), indent=1, ensure_ascii=False) + "\n")
        except OSError as exc:
            raise LLMError(f"{path}: cannot write the LLM run record ({one_line(exc)})") from None
        return path
