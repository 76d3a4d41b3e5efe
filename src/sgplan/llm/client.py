"""The chat backend contract and the live client for any OpenAI-compatible chat-completions server.

Everything in sgplan that asks a language model something (grounding, translation, guidance) takes a
:class:`ChatBackend`: an object with a ``model`` name, a human-readable ``label`` and
``complete(messages, **params) -> ChatResult``. Implementations:

- :class:`OpenAIChatClient` (here): a live server, e.g. OpenAI, vLLM, Ollama, llama.cpp;
- :class:`sgplan.llm.cache.CachedChatBackend`: record/replay around another backend;
- scripted or rule-based backends written for tests and offline use.

Chat parameters are limited to :data:`CHAT_PARAMS` and normalised by :func:`normalize_params` so that the
same request always has the same cache key. The live client retries HTTP 429, HTTP 5xx, connection
errors and timeouts with exponential backoff and jitter (the SDK's own retries are disabled), and turns
every failure into a one-line :class:`~sgplan.errors.LLMError` naming the endpoint, the status and the
number of attempts. Both the client and the cache are safe to call from several threads;
:func:`complete_many` runs a batch with a concurrency limit.
"""

from __future__ import annotations

import functools
import ipaddress
import json
import random
import re
import sys
import threading
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, TypeVar, runtime_checkable
from urllib.parse import urlsplit

from sgplan.errors import LLMError
from sgplan.llm.config import KEY_ENV_VARS, LLMConfig, one_line

if TYPE_CHECKING:
    import openai

ROLES = ("system", "user", "assistant")
"""Message roles a request may contain."""

_FLOAT_PARAMS = ("temperature", "top_p", "presence_penalty", "frequency_penalty")
_INT_PARAMS = ("max_tokens", "n", "seed")
CHAT_PARAMS = (*_FLOAT_PARAMS, *_INT_PARAMS, "stop")
"""The sampling parameters a backend accepts; each is part of the cache key."""


@dataclass(frozen=True)
class ChatResult:
    """The answer to one chat call.

    Attributes
    ----------
    content:
        The text of the first choice, never empty.
    model:
        The model that answered, as the server reported it (may be more specific than the name asked for).
    finish_reason:
        Why generation stopped for the first choice (``"stop"``, ``"length"``, ...), if reported.
    usage:
        Token counts (``prompt_tokens``, ``completion_tokens``, ``total_tokens``) if reported.
    latency_s:
        Wall time of the call in seconds, retries and backoff included. A cached result keeps the
        latency of the call that was recorded.
    from_cache:
        True when the result was read from a record/replay cache rather than produced by this call.
    choices:
        The texts of all choices (more than one only when ``n > 1`` was asked); ``choices[0] == content``.
    attempts:
        HTTP attempts the live call took (1 without retries).
    """

    content: str
    model: str
    finish_reason: str | None = None
    usage: Mapping[str, int] | None = None
    latency_s: float = 0.0
    from_cache: bool = False
    choices: tuple[str, ...] = field(default=())
    attempts: int = 1

    def __post_init__(self) -> None:
        if not self.choices:
            object.__setattr__(self, "choices", (self.content,))
        elif self.choices[0] != self.content:
            raise ValueError("ChatResult.choices[0] must equal ChatResult.content")


Message = Mapping[str, str]
"""A chat message: ``{"role": "system" | "user" | "assistant", "content": text}``."""


@runtime_checkable
class ChatBackend(Protocol):
    """Anything that answers chat requests; see the module docstring."""

    @property
    def model(self) -> str:
        """The model name; part of every cache key and run record."""
        ...

    @property
    def label(self) -> str:
        """A short description for reports, e.g. ``"gpt-4o at https://api.openai.com/v1"``."""
        ...

    def complete(self, messages: Sequence[Message], **params: Any) -> ChatResult:
        """Answer ``messages`` with the sampling ``params`` (see :data:`CHAT_PARAMS`).

        Raises :class:`~sgplan.errors.LLMError` when no usable answer can be produced.
        """
        ...


def normalize_messages(messages: Sequence[Message]) -> list[dict[str, str]]:
    """Messages as plain ``{"role", "content"}`` dicts, checked; raises :class:`LLMError` if malformed."""
    if isinstance(messages, (str, bytes)) or not isinstance(messages, Sequence) or not messages:
        raise LLMError("chat request: messages must be a non-empty list of {'role', 'content'} mappings")
    normalized = []
    for i, message in enumerate(messages):
        if not isinstance(message, Mapping) or set(message) != {"role", "content"}:
            raise LLMError(f"chat request: message {i} must have exactly the keys 'role' and 'content'")
        role, content = message["role"], message["content"]
        if role not in ROLES or not isinstance(content, str):
            raise LLMError(
                f"chat request: message {i} needs a role in {ROLES} and text content, got role {role!r}"
            )
        normalized.append({"role": role, "content": content})
    return normalized


def normalize_params(params: Mapping[str, Any]) -> dict[str, Any]:
    """Sampling parameters in canonical form: ``None`` dropped, numbers typed, ``stop`` a list, keys sorted.

    ``temperature=0`` and ``temperature=0.0`` normalise alike, so they share a cache entry.
    Raises :class:`LLMError` for unknown names or values of the wrong type.
    """
    normalized: dict[str, Any] = {}
    for name in sorted(params):
        value = params[name]
        if name not in CHAT_PARAMS:
            raise LLMError(f"chat request: unknown parameter {name!r} (supported: {', '.join(CHAT_PARAMS)})")
        if value is None:
            continue
        if name in _FLOAT_PARAMS and isinstance(value, (int, float)) and not isinstance(value, bool):
            normalized[name] = float(value)
        elif name in _INT_PARAMS and isinstance(value, int) and not isinstance(value, bool):
            normalized[name] = value
        elif name == "stop" and isinstance(value, str):
            normalized[name] = [value]
        elif name == "stop" and isinstance(value, Sequence) and all(isinstance(s, str) for s in value):
            normalized[name] = list(value)
        else:
            raise LLMError(f"chat request: parameter {name}={value!r} has the wrong type")
    for name in ("n", "max_tokens"):
        if normalized.get(name, 1) < 1:
            raise LLMError(f"chat request: parameter {name} must be at least 1, got {normalized[name]}")
    return normalized


class RateLimiter:
    """Spaces events at least ``60 / requests_per_minute`` seconds apart, across threads.

    ``clock`` and ``sleep`` are injectable so that tests need not wait.
    """

    def __init__(
        self,
        requests_per_minute: float,
        *,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
    ) -> None:
        self.interval_s = 60.0 / requests_per_minute
        self._clock = clock
        self._sleep = sleep
        self._lock = threading.Lock()
        self._next_s = float("-inf")

    def acquire(self) -> float:
        """Wait for the next free slot; returns the seconds waited."""
        with self._lock:
            now = self._clock()
            start = max(now, self._next_s)
            self._next_s = start + self.interval_s
        # Sleep outside the lock: the slot is reserved, later callers queue behind it.
        wait = start - now
        if wait > 0:
            self._sleep(wait)
        return wait


class OpenAIChatClient:
    """A :class:`ChatBackend` over an OpenAI-compatible ``/chat/completions`` endpoint.

    Parameters
    ----------
    config:
        Endpoint, model, key, timeout, retry and rate-limit settings (see :class:`LLMConfig`).
    sleep:
        Called with the backoff delay in seconds between attempts (tests pass a recorder).
    rng:
        Source of the backoff jitter.
    notify:
        Called with one line before each retry (default: print it to stderr), so a slow server is
        never silent.

    Notes
    -----
    A loopback endpoint is contacted directly even when ``HTTP(S)_PROXY`` is set: a local model server
    is never behind the user's proxy. Use as a context manager, or call :meth:`close`, to release the
    connection pool.

    Example
    -------
    >>> client = OpenAIChatClient(LLMConfig(model="qwen2.5:7b", base_url="http://127.0.0.1:11434/v1"))
    >>> client.complete([{"role": "user", "content": "Say hi"}], temperature=0).content  # doctest: +SKIP
    'Hi!'
    """

    def __init__(
        self,
        config: LLMConfig,
        *,
        sleep: Callable[[float], None] = time.sleep,
        rng: random.Random | None = None,
        notify: Callable[[str], None] | None = None,
    ) -> None:
        # Imported here, not at module level: the SDK is slow to import, and offline runs (replay,
        # rule-based backends) never need it.
        import openai

        self.config = config
        self._sleep = sleep
        self._notify = notify if notify is not None else _to_stderr
        self._rng = rng or random.Random()
        self._rate_limiter = (
            RateLimiter(config.requests_per_minute, sleep=sleep) if config.requests_per_minute else None
        )
        http_client = openai.DefaultHttpxClient(trust_env=False) if _is_loopback(config.base_url) else None
        self._sdk = openai.OpenAI(
            base_url=config.base_url,
            api_key=config.api_key,
            timeout=config.timeout_s,
            max_retries=0,  # retries are ours: one policy, one attempt count in every message
            http_client=http_client,
        )

    @property
    def model(self) -> str:
        return self.config.model

    @property
    def label(self) -> str:
        return f"{self.config.model} at {self.config.base_url}"

    def close(self) -> None:
        self._sdk.close()

    def __enter__(self) -> OpenAIChatClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def complete(self, messages: Sequence[Message], **params: Any) -> ChatResult:
        """Send one chat request, retrying transient failures; see :class:`ChatBackend`.

        Raises
        ------
        LLMError
            The server failed, refused (HTTP 4xx), timed out or could not be reached on every attempt,
            or its answer is malformed, truncated, or empty.
        """
        import openai  # already loaded by __init__; see there

        request_messages = normalize_messages(messages)
        request_params = normalize_params(params)
        max_attempts = 1 + self.config.max_retries
        started = time.monotonic()
        deadline = started + self.config.deadline_s
        for attempt in range(1, max_attempts + 1):
            if self._rate_limiter is not None:
                self._rate_limiter.acquire()
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise LLMError(f"{self._failed(attempt - 1)}: {self._past_deadline()}")
            retry_after_s: float | None = None
            try:
                send = functools.partial(
                    self._sdk.chat.completions.with_raw_response.create, model=self.config.model,
                    messages=request_messages, timeout=min(self.config.timeout_s, remaining),
                    **request_params,
                )
                raw = _within(remaining, send)
                if raw is None:
                    raise LLMError(f"{self._failed(attempt)}: {self._past_deadline()}")
            except openai.APIStatusError as exc:
                status = exc.status_code
                problem = f"HTTP {status}: {_server_message(exc)}"
                if status != 429 and status < 500:
                    refused = f"{problem} (HTTP {status} is not retried){_status_hint(status)}"
                    raise LLMError(f"{self._failed(attempt)}: {refused}") from None
                retry_after_s = _retry_after_s(exc.response.headers.get("retry-after"))
            except openai.APITimeoutError:
                problem = f"no answer within the {self.config.timeout_s:g} s timeout"
            except openai.APIConnectionError as exc:
                problem = (f"connection failed ({one_line(exc.__cause__ or exc)}); is a server running at "
                           f"{self.config.endpoint}? (--base-url, or base_url in the LLM config)")
            else:
                body = _parse_body(raw.text, raw.headers.get("content-type", ""), self._where(attempt))
                return _result_from_body(
                    body,
                    requested_model=self.config.model,
                    n=request_params.get("n", 1),
                    where=self._where(attempt),
                    latency_s=time.monotonic() - started,
                    attempts=attempt,
                )
            if attempt == max_attempts:
                raise LLMError(f"{self._failed(attempt)}: {problem}")
            delay = self._backoff_s(attempt, retry_after_s)
            if time.monotonic() + delay >= deadline:
                raise LLMError(f"{self._failed(attempt)}: {problem}; no time left for a retry "
                               f"within the {self.config.deadline_s:g} s deadline")
            self._notify(f"sgplan: LLM attempt {attempt} of {max_attempts} to {self.config.endpoint} failed "
                         f"({one_line(problem, 160)}); retrying in {delay:.1f} s")
            self._sleep(delay)
        raise AssertionError("unreachable: the loop returns or raises")

    def _past_deadline(self) -> str:
        return (f"no complete answer within the {self.config.deadline_s:g} s deadline of the whole call "
                "(deadline_s in the LLM config, or --llm-deadline)")

    def _backoff_s(self, retry: int, retry_after_s: float | None) -> float:
        """Seconds to wait before retry number ``retry`` (1-based); honours a server's Retry-After."""
        ceiling = min(self.config.backoff_max_s, self.config.backoff_base_s * 2 ** (retry - 1))
        delay = ceiling * (0.5 + 0.5 * self._rng.random())
        if retry_after_s is not None:
            delay = max(delay, min(retry_after_s, self.config.backoff_max_s))
        return delay

    def _failed(self, attempts: int) -> str:
        plural = "s" if attempts != 1 else ""
        return (
            f"LLM call to {self.config.endpoint} (model {self.config.model!r}) "
            f"failed after {attempts} attempt{plural}"
        )

    def _where(self, attempt: int) -> str:
        return f"LLM reply from {self.config.endpoint} (model {self.config.model!r}, attempt {attempt})"


def _to_stderr(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


_T = TypeVar("_T")


def _within(seconds: float, call: Callable[[], _T]) -> _T | None:
    """``call()``, or ``None`` if it has not returned after ``seconds``.

    The per-read timeout of the HTTP client does not bound a reply that trickles in a byte at a time,
    so the request runs in a daemon thread that is abandoned at the deadline (it ends by itself at
    the server's next stall longer than ``timeout_s``). Exceptions of ``call`` propagate.
    """
    outcome: list[Any] = []

    def run() -> None:
        try:
            outcome.append((True, call()))
        except BaseException as exc:  # noqa: BLE001 - handed to the caller's thread, which re-raises it
            outcome.append((False, exc))

    worker = threading.Thread(target=run, name="sgplan-llm-request", daemon=True)
    worker.start()
    worker.join(seconds)
    if not outcome:
        return None
    ok, value = outcome[0]
    if not ok:
        raise value
    return value


def complete_many(
    backend: ChatBackend,
    requests: Iterable[tuple[Sequence[Message], Mapping[str, Any]]],
    *,
    max_concurrency: int = 4,
) -> list[ChatResult | LLMError]:
    """Run many ``(messages, params)`` requests on ``backend`` with at most ``max_concurrency`` in flight.

    Returns one entry per request, in request order: the :class:`ChatResult`, or the :class:`LLMError`
    that request ended with (so one bad call does not lose the others). Rate limiting, if configured,
    is done by the live client, so cache hits are never throttled.
    """
    if max_concurrency < 1:
        raise LLMError(f"max_concurrency must be at least 1, got {max_concurrency}")

    def run(request: tuple[Sequence[Message], Mapping[str, Any]]) -> ChatResult | LLMError:
        messages, params = request
        try:
            return backend.complete(messages, **params)
        except LLMError as exc:
            return exc

    with ThreadPoolExecutor(max_workers=max_concurrency, thread_name_prefix="sgplan-llm") as pool:
        return list(pool.map(run, requests))


# -- response parsing -------------------------------------------------------------------------------------


def _parse_body(text: str, content_type: str, where: str) -> Mapping[str, Any]:
    """The JSON object of a 200 response. Some servers mislabel JSON, so the content type is only reported."""
    try:
        body = json.loads(text)
    except ValueError:
        raise LLMError(
            f"{where} is not valid JSON (truncated or malformed body of {len(text)} characters, "
            f"content-type {content_type or 'missing'!r}, starting {one_line(text, 80)!r})"
        ) from None
    if not isinstance(body, dict):
        raise LLMError(f"{where} is JSON but not an object: starts {one_line(text, 80)!r}")
    return body


def _result_from_body(
    body: Mapping[str, Any], *, requested_model: str, n: int, where: str, latency_s: float, attempts: int
) -> ChatResult:
    """Check a chat-completion object and extract the result; every defect is an :class:`LLMError`."""
    choices = body.get("choices")
    if not isinstance(choices, list) or not choices:
        error = body.get("error")
        said = one_line(error.get("message", error), 200) if isinstance(error, dict) else None
        detail = f"; the server says: {said}" if said else ""
        raise LLMError(f"{where} has no 'choices' (not a chat completion){detail}")
    if len(choices) < n:
        raise LLMError(
            f"{where} has {len(choices)} choice(s) but n={n} were asked; this server may ignore n, "
            "so make separate calls with different seeds instead"
        )
    texts = []
    for i, choice in enumerate(choices):
        message = choice.get("message") if isinstance(choice, dict) else None
        if not isinstance(message, dict):
            raise LLMError(f"{where}: choice {i} has no 'message' object")
        content = message.get("content")
        answer = without_reasoning(content) if isinstance(content, str) else ""
        if answer.strip():
            texts.append(answer)
            continue
        finish = choice.get("finish_reason")
        if isinstance(content, str) and content.strip():
            reason = "only a <think> reasoning block, no answer" + (
                "; raise max_tokens" if finish == "length" else ""
            )
        elif message.get("refusal"):
            reason = f"the model refused: {one_line(message['refusal'])}"
        elif message.get("tool_calls"):
            reason = "the model returned tool calls instead of text"
        elif finish == "length":
            reason = "generation hit the token limit before any text; raise max_tokens"
        else:
            reason = f"finish_reason {finish!r}"
        raise LLMError(f"{where}: choice {i} has empty content ({reason})")
    first = choices[0]
    usage = body.get("usage")
    return ChatResult(
        content=texts[0],
        model=str(body.get("model") or requested_model),
        finish_reason=first.get("finish_reason"),
        usage={k: v for k, v in usage.items() if isinstance(v, int)} if isinstance(usage, dict) else None,
        latency_s=latency_s,
        choices=tuple(texts),
        attempts=attempts,
    )


# -- small helpers --------------------------------------------------------------------------------------

_REASONING = re.compile(r"^\s*<think>.*?(?:</think>|\Z)", re.DOTALL)
_REASONING_TAIL = re.compile(r"^.*?</think>", re.DOTALL)


def without_reasoning(content: str) -> str:
    """``content`` without the reasoning that models served without a reasoning parser (Ollama,
    llama.cpp, vLLM) put before the answer: a leading ``<think>...</think>`` block (an unclosed one is all
    reasoning), or everything up to a ``</think>`` whose ``<think>`` was in the prompt template."""
    if _REASONING.match(content):
        return _REASONING.sub("", content, count=1)
    end = content.find("</think>")
    if end >= 0 and "<think>" not in content[:end]:
        return _REASONING_TAIL.sub("", content, count=1)
    return content



def _is_loopback(base_url: str) -> bool:
    host = urlsplit(base_url).hostname or ""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def _server_message(exc: openai.APIStatusError) -> str:
    """The server's own explanation of an error status, from the OpenAI error schema or the raw body."""
    body = exc.body
    if isinstance(body, dict):
        error = body.get("error", body)
        message = error.get("message") if isinstance(error, dict) else error
        if message:
            return one_line(message, 200)
    return one_line(exc.response.text, 200) or exc.response.reason_phrase or "no details"


def _status_hint(status: int) -> str:
    if status in (401, 403):
        return f"; check the API key (${' or $'.join(KEY_ENV_VARS)}, or the LLM config file)"
    if status == 404:
        return "; check the model name and the base URL (most servers expect it to end in /v1)"
    return ""


def _retry_after_s(value: str | None) -> float | None:
    """A Retry-After header given in seconds; the HTTP-date form is ignored (the backoff applies)."""
    try:
        seconds = float(value) if value is not None else None
    except ValueError:
        return None
    return seconds if seconds is not None and seconds >= 0 else None


