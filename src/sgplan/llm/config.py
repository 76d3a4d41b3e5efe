"""Where the chat client connects and how patiently: endpoint, model, API key, timeouts, retries.

A configuration comes from, in order of precedence (the more specific source wins):

1. explicit values (e.g. the CLI's ``--llm openai:MODEL`` and ``--base-url URL``),
2. a YAML config file (:func:`load_llm_config`'s ``path``, else the file named by ``$SGPLAN_LLM_CONFIG``),
3. the environment: the key from ``$SGPLAN_LLM_API_KEY`` then ``$OPENAI_API_KEY``, the endpoint from
   ``$OPENAI_BASE_URL`` (the OpenAI SDK's own variable),
4. the defaults of :class:`LLMConfig`.

Local servers (vLLM, Ollama, llama.cpp) ignore the key, so when no key is found and the endpoint is not
OpenAI's own, a placeholder key is used. OpenAI's endpoint without a key is an error, raised before any
request is sent.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from sgplan.errors import LLMError
from sgplan.safeio import load_yaml

OPENAI_BASE_URL = "https://api.openai.com/v1"
"""The endpoint used when none is configured."""

PLACEHOLDER_API_KEY = "sgplan-no-key"
"""Sent to endpoints other than OpenAI's when no key is configured; local servers ignore keys."""

KEY_ENV_VARS = ("SGPLAN_LLM_API_KEY", "OPENAI_API_KEY")
"""Environment variables searched for the API key, first match wins."""

CONFIG_ENV_VAR = "SGPLAN_LLM_CONFIG"
"""Environment variable naming a config file to read when none is passed explicitly."""


@dataclass(frozen=True)
class LLMConfig:
    """Everything the live chat client needs. Times are seconds.

    Attributes
    ----------
    model:
        The model name the server knows, e.g. ``gpt-4o`` or ``qwen2.5:7b-instruct`` (Ollama).
    base_url:
        The OpenAI-compatible API root, ending in ``/v1`` for most servers
        (vLLM ``http://host:8000/v1``, Ollama ``http://host:11434/v1``, llama.cpp ``http://host:8080/v1``).
    api_key:
        Sent as a bearer token. Never printed (excluded from ``repr``).
    timeout_s:
        Limit for each network phase of one attempt (connect, send, each read), not for the whole call.
    deadline_s:
        Limit for the whole call: every attempt, backoff wait and stalled reply included. A server that
        accepts and never answers, or trickles its reply, fails the call after this long.
    max_retries:
        Retries after the first attempt on HTTP 429, HTTP 5xx, connection errors and timeouts; other
        HTTP 4xx statuses are never retried. ``0`` means a single attempt.
    backoff_base_s, backoff_max_s:
        The wait before retry ``k`` (1-based) is ``min(backoff_max_s, backoff_base_s * 2**(k-1))``, scaled
        by a random factor in [0.5, 1) so that parallel clients do not retry in lockstep.
    requests_per_minute:
        If set, request starts (retries included) are spaced at least ``60 / requests_per_minute`` s
        apart across all threads using the client; for hosted APIs with rate limits.
    """

    model: str
    base_url: str = OPENAI_BASE_URL
    api_key: str = field(default=PLACEHOLDER_API_KEY, repr=False)
    timeout_s: float = 60.0
    deadline_s: float = 120.0
    max_retries: int = 4
    backoff_base_s: float = 1.0
    backoff_max_s: float = 30.0
    requests_per_minute: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.model, str) or not self.model.strip():
            raise LLMError("LLM config: 'model' must be a non-empty model name, e.g. gpt-4o")
        parts = urlsplit(self.base_url) if isinstance(self.base_url, str) else None
        if parts is None or parts.scheme not in ("http", "https") or not parts.hostname:
            raise LLMError(
                f"LLM config: base_url {self.base_url!r} is not an http(s) URL; "
                "expected e.g. http://127.0.0.1:8000/v1"
            )
        if not isinstance(self.api_key, str) or not self.api_key:
            raise LLMError("LLM config: 'api_key' must be a non-empty string")
        _check_number("timeout_s", self.timeout_s, minimum=0.0, strict=True)
        _check_number("deadline_s", self.deadline_s, minimum=0.0, strict=True)
        _check_number("backoff_base_s", self.backoff_base_s, minimum=0.0)
        _check_number("backoff_max_s", self.backoff_max_s, minimum=0.0)
        if self.requests_per_minute is not None:
            _check_number("requests_per_minute", self.requests_per_minute, minimum=0.0, strict=True)
        retries = self.max_retries
        if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
            raise LLMError(f"LLM config: 'max_retries' must be an integer >= 0, got {self.max_retries!r}")

    @property
    def endpoint(self) -> str:
        """The chat-completions URL requests go to, for messages and run records."""
        return f"{self.base_url.rstrip('/')}/chat/completions"

    @property
    def is_openai(self) -> bool:
        """Whether the endpoint is OpenAI's own (which needs a real key)."""
        return urlsplit(self.base_url).hostname == urlsplit(OPENAI_BASE_URL).hostname


def _check_number(name: str, value: object, *, minimum: float, strict: bool = False) -> None:
    ok = (
        isinstance(value, (int, float))
        and not isinstance(value, bool)
        and math.isfinite(value)
        and (value > minimum if strict else value >= minimum)
    )
    if not ok:
        relation = ">" if strict else ">="
        raise LLMError(f"LLM config: {name!r} must be a finite number {relation} {minimum:g}, got {value!r}")


_FILE_ONLY_KEYS = ("api_key_env",)
"""Config-file keys that are not :class:`LLMConfig` fields (``api_key_env``: the variable holding the key)."""


def load_llm_config(
    path: str | Path | None = None,
    *,
    environ: Mapping[str, str] | None = None,
    **overrides: Any,
) -> LLMConfig:
    """Resolve an :class:`LLMConfig` from explicit values, a config file and the environment.

    Parameters
    ----------
    path:
        A YAML file whose top level maps :class:`LLMConfig` field names (and ``api_key_env``, the name of
        an environment variable holding the key) to values. ``None`` reads ``$SGPLAN_LLM_CONFIG`` if set.
    environ:
        The environment to read (default ``os.environ``); tests pass a dict.
    **overrides:
        Explicit field values; ``None`` values are ignored, so CLI options can be passed through as is.

    Returns
    -------
    LLMConfig

    Raises
    ------
    LLMError
        The file is missing, not YAML, has an unknown key or a bad value; no model is given; or the
        endpoint is OpenAI's and no API key was found.

    Example
    -------
    >>> load_llm_config(model="qwen2.5:7b", base_url="http://127.0.0.1:11434/v1", environ={}).api_key
    'sgplan-no-key'
    """
    env = os.environ if environ is None else environ
    fields = {f.name for f in dataclasses.fields(LLMConfig)}
    unknown = sorted(set(overrides) - fields)
    if unknown:
        known = ", ".join(sorted(fields))
        raise LLMError(f"LLM config: unknown option(s) {', '.join(unknown)} (known: {known})")
    if path is None and env.get(CONFIG_ENV_VAR):
        path = env[CONFIG_ENV_VAR]
    from_file = _read_config_file(Path(path), fields) if path is not None else {}

    values: dict[str, Any] = {}
    if env.get("OPENAI_BASE_URL"):
        values["base_url"] = env["OPENAI_BASE_URL"]
    env_key = next((env[name] for name in KEY_ENV_VARS if env.get(name)), None)
    key_var = from_file.pop("api_key_env", None)
    if key_var is not None:
        env_key = env.get(key_var) or None
        if env_key is None:
            raise LLMError(
                f"{path}: api_key_env names ${key_var}, which is not set; export it or remove the key"
            )
    if env_key is not None:
        values["api_key"] = env_key
    values.update(from_file)
    values.update({name: value for name, value in overrides.items() if value is not None})

    if "model" not in values:
        where = f" or set 'model' in {path}" if path is not None else ""
        raise LLMError(f"no LLM model given: pass one (e.g. --llm openai:gpt-4o){where}")
    config = LLMConfig(**values)
    if config.is_openai and "api_key" not in values:
        raise LLMError(
            f"no API key for {config.base_url}: set {' or '.join('$' + v for v in KEY_ENV_VARS)}, "
            "or 'api_key' / 'api_key_env' in the LLM config file"
        )
    return config


def _read_config_file(path: Path, fields: set[str]) -> dict[str, Any]:
    """The top-level mapping of a YAML config file, restricted to known keys."""
    if not (path.exists() or path.is_symlink()):
        raise LLMError(f"{path}: LLM config file not found")
    data = load_yaml(path, _ConfigFileError, "LLM config file", 2**20)
    if data is None:
        return {}
    if not isinstance(data, dict):
        kind = type(data).__name__
        raise LLMError(f"{path}: an LLM config file must be a mapping of option: value, got {kind}")
    known = fields | set(_FILE_ONLY_KEYS)
    unknown = sorted(str(k) for k in data if k not in known)
    if unknown:
        listed = ", ".join(sorted(known))
        raise LLMError(f"{path}: unknown LLM option(s) {', '.join(unknown)} (known: {listed})")
    try:
        LLMConfig(**{"model": "probe", **{k: v for k, v in data.items() if k in fields}})
    except LLMError as exc:
        raise LLMError(f"{path}: {exc}") from None
    return dict(data)


class _ConfigFileError(LLMError):
    """An unreadable config file (``path`` first, as safeio's readers expect)."""

    def __init__(self, message: str, path: Path | None = None) -> None:
        super().__init__(f"{path}: cannot read the LLM config file ({message})")


def one_line(value: object, limit: int | None = None) -> str:
    """``str(value)`` with all whitespace runs collapsed to one space, cut to ``limit`` characters.

    Error messages quote server replies and file contents through this, so they stay on one line.
    """
    flat = " ".join(str(value).split())
    return flat if limit is None or len(flat) <= limit else flat[: limit - 3] + "..."
