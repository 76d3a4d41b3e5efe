"""Record/replay of chat calls, so that every run that used a language model can be repeated offline.

A cache is a directory with one human-readable JSON file per call, ``<key>.json``, where the key is the
SHA-256 of the canonical JSON of the request: the model name, the messages and the normalised sampling
parameters (:func:`cache_key`). The endpoint is deliberately not part of the key: a call recorded against
one server replays for the same model name anywhere. Each file holds the request and the response
(see ``docs/llm.md``), and is written to a temporary file in the same directory and moved into place with
:func:`os.replace`, so an interrupted run never leaves a half-written entry (at worst a stray
``.*.tmp`` file, which is never read).

Modes (:data:`CacheMode`):

- ``"live"``: no cache, every call goes to the server;
- ``"record"``: a hit is answered from the cache, a miss is sent to the server and recorded;
- ``"replay"``: a hit is answered from the cache, a miss is an :class:`~sgplan.errors.LLMError` naming the
  call; no server (and no API key) is needed.
"""

from __future__ import annotations

import hashlib
import json
import threading
from collections.abc import Sequence
from datetime import datetime, timezone
from pathlib import Path
from typing import Any, Literal, get_args

from sgplan.errors import LLMError
from sgplan.files import write_text_atomically
from sgplan.llm.client import (
    ChatBackend,
    ChatResult,
    Message,
    OpenAIChatClient,
    normalize_messages,
    normalize_params,
    without_reasoning,
)
from sgplan.llm.config import LLMConfig, one_line
from sgplan.safeio import clip, load_json, quote

CacheMode = Literal["live", "record", "replay"]

ENTRY_FORMAT = "sgplan-llm-cache/1"
"""The ``format`` field of every entry; bump it (and the key version) if the layout changes."""

_KEY_VERSION = 1


def cache_request(model: str, messages: Sequence[Message], params: dict[str, Any]) -> dict[str, Any]:
    """The canonical request that is hashed and stored: model, normalised messages and parameters."""
    return {"model": model, "messages": normalize_messages(messages), "params": normalize_params(params)}


def cache_key(model: str, messages: Sequence[Message], params: dict[str, Any] | None = None) -> str:
    """The cache key of a call: 64 hex digits, identical across processes, platforms and Python versions.

    Any difference in the model, a message (role or text) or a parameter gives a different key;
    parameters equal after :func:`~sgplan.llm.client.normalize_params` (``temperature=0`` vs ``0.0``,
    ``seed=None`` vs omitted) give the same key.
    """
    return _hash_request(cache_request(model, messages, params or {}))


def _hash_request(request: dict[str, Any]) -> str:
    canonical = json.dumps(
        {"v": _KEY_VERSION, **request},
        sort_keys=True,
        separators=(",", ":"),
        ensure_ascii=True,
        allow_nan=False,
    )
    return hashlib.sha256(canonical.encode("ascii")).hexdigest()


class ChatCache:
    """The entries of one cache directory (created on first write). Safe for concurrent threads/processes.

    Raises
    ------
    LLMError
        ``directory`` (or the nearest part of it that exists) is not a folder: said before any call is
        made, so a bad ``--cache`` never costs a round trip to the server first.
    """

    def __init__(self, directory: str | Path) -> None:
        self.directory = Path(directory)
        existing = next((p for p in (self.directory, *self.directory.parents) if p.exists()), None)
        if existing is not None and not existing.is_dir():
            what = "is a file" if existing == self.directory else f"lies inside {existing}, a file"
            raise LLMError(f"LLM cache {self.directory} {what}, not a folder: give --cache a folder "
                           "(it is created on the first recorded call)")

    def path(self, key: str) -> Path:
        return self.directory / f"{key}.json"

    def get(self, key: str, request: dict[str, Any]) -> ChatResult | None:
        """The recorded result for ``key`` (with ``from_cache=True``), or ``None`` if there is none.

        Raises :class:`LLMError` if the entry is unreadable or records a different request.
        """
        path = self.path(key)
        if not (path.exists() or path.is_symlink()):
            return None
        try:
            entry = load_json(path, _CacheEntryError, "LLM cache entry", MAX_ENTRY_BYTES)
        except _CacheEntryError as exc:
            raise LLMError(f"{exc}; delete it to record the call again") from None
        if not isinstance(entry, dict) or entry.get("format") != ENTRY_FORMAT:
            raise LLMError(
                f"{path}: not an LLM cache entry of format {ENTRY_FORMAT!r}; "
                "delete it to record the call again"
            )
        if entry.get("key") != key or entry.get("request") != request:
            raise LLMError(
                f"{path}: this LLM cache entry records a different request than its name says "
                "(edited by hand?)"
            )
        try:
            return _result_from_json(entry["response"])
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise LLMError(f"{path}: malformed 'response' in LLM cache entry ({clip(one_line(exc))}); "
                           "delete it to record the call again") from None

    def put(self, key: str, request: dict[str, Any], result: ChatResult, *, endpoint: str) -> Path:
        """Write the entry for ``key`` atomically and return its path; I/O errors raise :class:`LLMError`."""
        entry = {
            "format": ENTRY_FORMAT,
            "key": key,
            "recorded_at": datetime.now(timezone.utc).isoformat(timespec="seconds"),
            "endpoint": endpoint,
            "request": request,
            "response": _result_to_json(result),
        }
        text = json.dumps(entry, indent=2, ensure_ascii=False) + "\n"
        path = self.path(key)
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            write_text_atomically(path, text)
        except OSError as exc:
            raise LLMError(f"{path}: cannot write LLM cache entry ({one_line(exc)})") from None
        return path


MAX_ENTRY_BYTES = 64 * 2**20
"""Cap of one cache entry file (64 MiB); a recorded chat reply is a few kB."""


class _CacheEntryError(LLMError):
    """An unreadable entry (``path`` first, as safeio's readers expect); re-raised as an LLMError."""

    def __init__(self, message: str, path: Path | None = None) -> None:
        super().__init__(f"{path}: unreadable LLM cache entry ({message})")


def _result_to_json(result: ChatResult) -> dict[str, Any]:
    return {
        "content": result.content,
        "choices": list(result.choices),
        "model": result.model,
        "finish_reason": result.finish_reason,
        "usage": dict(result.usage) if result.usage is not None else None,
        "latency_s": result.latency_s,
        "attempts": result.attempts,
    }


def _result_from_json(data: dict[str, Any]) -> ChatResult:
    choices_data = data["choices"]
    if (
        not isinstance(choices_data, list)
        or not choices_data
        or not all(isinstance(c, str) for c in choices_data)
    ):
        raise ValueError(f"'choices' must be a non-empty list of texts, got {quote(choices_data)}")
    if data["usage"] is not None and not isinstance(data["usage"], dict):
        raise ValueError(f"'usage' must be a mapping or null, got {quote(data['usage'])}")
    # Entries recorded before reasoning blocks were removed are answered as a fresh reply would be.
    choices = tuple(without_reasoning(text) for text in choices_data)
    return ChatResult(
        content=choices[0],
        model=data["model"],
        finish_reason=data["finish_reason"],
        usage=data["usage"],
        latency_s=float(data["latency_s"]),
        from_cache=True,
        choices=choices,
        attempts=int(data["attempts"]),
    )


class CachedChatBackend:
    """A :class:`~sgplan.llm.client.ChatBackend` that records and replays another backend's calls.

    Parameters
    ----------
    directory:
        The cache directory.
    mode:
        ``"record"`` (needs ``inner``) or ``"replay"`` (``inner`` is never called and may be ``None``).
    inner:
        The backend that answers misses in record mode.
    model:
        The model name for keys; defaults to ``inner.model``. Required in replay mode without ``inner``.

    Concurrent calls with the same key in one process wait for each other, so a miss is sent once.
    """

    def __init__(
        self,
        directory: str | Path,
        *,
        mode: Literal["record", "replay"],
        inner: ChatBackend | None = None,
        model: str | None = None,
    ) -> None:
        if mode not in ("record", "replay"):
            raise LLMError(f"cache mode must be 'record' or 'replay' here, got {mode!r}")
        if mode == "record" and inner is None:
            raise LLMError("record mode needs a live backend to answer cache misses")
        if model is None and inner is None:
            raise LLMError("replay mode needs the model name the calls were recorded with")
        if model is not None and inner is not None and model != inner.model:
            raise LLMError(f"cache model {model!r} differs from the backend's model {inner.model!r}")
        self.cache = ChatCache(directory)
        self.mode = mode
        self.inner = inner
        self._model = model if model is not None else inner.model  # type: ignore[union-attr]
        self._key_locks: dict[str, threading.Lock] = {}
        self._key_locks_guard = threading.Lock()

    @property
    def model(self) -> str:
        return self._model

    @property
    def label(self) -> str:
        if self.mode == "replay":
            return f"{self._model} replayed from {self.cache.directory}"
        return f"{self.inner.label}, recorded in {self.cache.directory}"  # type: ignore[union-attr]

    def complete(self, messages: Sequence[Message], **params: Any) -> ChatResult:
        """Answer from the cache, else (record mode) from the inner backend and record the answer.

        Raises
        ------
        LLMError
            Replay mode and no entry (the message names the model, the start of the last user message and
            the key); an unreadable entry; the inner backend's error; the entry cannot be written.
        """
        request = cache_request(self._model, messages, params)
        key = _hash_request(request)
        with self._lock_for(key):
            hit = self.cache.get(key, request)
            if hit is not None:
                return hit
            if self.mode == "replay":
                raise LLMError(
                    f"replay: no recorded LLM call for model {self._model!r} asking "
                    f"{_last_user_text(request['messages'])!r} (key {key[:16]}) in {self.cache.directory}; "
                    "run once with recording enabled (a cache without --replay) to record it"
                )
            assert self.inner is not None
            result = self.inner.complete(request["messages"], **request["params"])
            self.cache.put(key, request, result, endpoint=self.inner.label)
            return result

    def _lock_for(self, key: str) -> threading.Lock:
        with self._key_locks_guard:
            return self._key_locks.setdefault(key, threading.Lock())


def open_chat_backend(
    mode: CacheMode,
    *,
    config: LLMConfig | None = None,
    cache_dir: str | Path | None = None,
    model: str | None = None,
) -> ChatBackend:
    """The backend for a run: the live client, the client with a recording cache, or replay only.

    ``live`` and ``record`` need ``config``; ``record`` and ``replay`` need ``cache_dir``; ``replay`` takes
    the model name from ``model`` or ``config`` and never opens a connection (no API key needed).
    """
    if mode not in get_args(CacheMode):
        raise LLMError(f"unknown LLM cache mode {mode!r} (expected one of {', '.join(get_args(CacheMode))})")
    if mode != "live" and cache_dir is None:
        raise LLMError(f"LLM cache mode {mode!r} needs a cache directory (--cache DIR)")
    if mode == "replay":
        name = model or (config.model if config is not None else None)
        if name is None:
            raise LLMError("replay needs the model name the calls were recorded with (--llm openai:MODEL)")
        return CachedChatBackend(cache_dir, mode="replay", model=name)  # type: ignore[arg-type]
    if config is None:
        raise LLMError(f"LLM cache mode {mode!r} needs an endpoint configuration")
    client = OpenAIChatClient(config)
    if mode == "live":
        return client
    return CachedChatBackend(cache_dir, mode="record", inner=client)  # type: ignore[arg-type]


def _last_user_text(messages: list[dict[str, str]], limit: int = 80) -> str:
    return one_line(next((m["content"] for m in reversed(messages) if m["role"] == "user"), ""), limit)
