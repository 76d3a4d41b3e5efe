"""A real OpenAI-compatible chat-completions server on 127.0.0.1 with scripted replies, for tests.

The server listens on an ephemeral loopback port in a background thread and answers
``POST /v1/chat/completions``. Each request consumes the next scripted step, in order:

>>> with FakeOpenAIServer() as server:                      # doctest: +SKIP
...     server.push_status(429)                              # first request: rate limited
...     server.push_reply("['enter(room_3)']")               # second request: a normal answer
...     ...  # point a client at server.base_url
...     assert len(server.requests) == 2

When the queue is empty, the responder set by :meth:`FakeOpenAIServer.respond_with` answers (useful for
concurrent callers, whose order is not fixed); without one the server answers HTTP 400 with the message
"fake OpenAI server: no scripted reply left for request #N", which a client reports without retrying.

Every request is recorded (:attr:`FakeOpenAIServer.requests`) so tests can assert on what was sent.
Delayed steps wait on an event that :meth:`FakeOpenAIServer.stop` sets, so shutdown is always prompt.
"""

from __future__ import annotations

import json
import threading
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

CHAT_PATH = "/v1/chat/completions"


@dataclass(frozen=True)
class RecordedRequest:
    """One HTTP request the server received."""

    method: str
    path: str
    headers: Mapping[str, str]
    body: bytes

    @property
    def json(self) -> Any:
        """The parsed JSON body (``None`` if it is not JSON)."""
        try:
            return json.loads(self.body)
        except ValueError:
            return None

    @property
    def messages(self) -> list[dict[str, str]]:
        return list((self.json or {}).get("messages", []))

    @property
    def last_user_message(self) -> str:
        return next((m["content"] for m in reversed(self.messages) if m.get("role") == "user"), "")


@dataclass(frozen=True)
class Step:
    """One scripted answer: a status, headers and body, sent after ``delay_s`` seconds.

    ``disconnect`` closes the connection without answering (a connection error for the client).
    ``trickle_s`` > 0 sends the headers at once, then the body one byte every ``trickle_s`` seconds (a
    reply that stalls mid-body without ever tripping a per-read timeout).
    """

    status: int = 200
    body: bytes = b""
    content_type: str = "application/json"
    headers: Mapping[str, str] = field(default_factory=dict)
    delay_s: float = 0.0
    disconnect: bool = False
    trickle_s: float = 0.0


def completion_body(
    content: str | Sequence[str | None] | None,
    *,
    model: str = "fake-model",
    finish_reason: str = "stop",
    usage: Mapping[str, int] | None = None,
) -> dict[str, Any]:
    """A chat-completion response in the OpenAI schema; a sequence of contents gives one choice each."""
    contents = [content] if content is None or isinstance(content, str) else list(content)
    return {
        "id": "chatcmpl-fake",
        "object": "chat.completion",
        "created": 1700000000,
        "model": model,
        "choices": [
            {"index": i, "message": {"role": "assistant", "content": text}, "finish_reason": finish_reason}
            for i, text in enumerate(contents)
        ],
        "usage": dict(usage or {"prompt_tokens": 11, "completion_tokens": 7, "total_tokens": 18}),
    }


def error_body(message: str, *, type_: str = "server_error", code: str | None = None) -> dict[str, Any]:
    """An error response in the OpenAI schema."""
    return {"error": {"message": message, "type": type_, "param": None, "code": code}}


Responder = Callable[[RecordedRequest], "str | Step"]
"""Answers a request when the queue is empty: a content string (a normal reply) or a :class:`Step`."""


class FakeOpenAIServer:
    """A scripted chat-completions server on ``127.0.0.1`` (see the module docstring)."""

    def __init__(self, *, default_model: str | None = None) -> None:
        self._steps: deque[Step | Callable[[RecordedRequest], Step]] = deque()
        self._requests: list[RecordedRequest] = []
        self._lock = threading.Lock()
        self._stopping = threading.Event()
        self._responder: Responder | None = None
        self._default_model = default_model
        self._server: ThreadingHTTPServer | None = None
        self._thread: threading.Thread | None = None

    # -- lifecycle -------------------------------------------------------------------------------------

    def start(self) -> FakeOpenAIServer:
        handler = type("Handler", (_Handler,), {"fake": self})
        self._server = ThreadingHTTPServer(("127.0.0.1", 0), handler)
        self._server.daemon_threads = True
        self._thread = threading.Thread(
            target=self._server.serve_forever, kwargs={"poll_interval": 0.05}, name="fake-openai", daemon=True
        )
        self._thread.start()
        return self

    def stop(self) -> None:
        """Stop serving; delayed replies in flight are abandoned. Idempotent and bounded in time."""
        self._stopping.set()
        if self._server is not None:
            self._server.shutdown()
            self._server.server_close()
            self._server = None
        if self._thread is not None:
            self._thread.join(timeout=5)
            self._thread = None

    def __enter__(self) -> FakeOpenAIServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    @property
    def port(self) -> int:
        if self._server is None:
            raise RuntimeError("the fake OpenAI server is not running")
        return self._server.server_address[1]

    @property
    def base_url(self) -> str:
        """The API root to give a client, e.g. ``http://127.0.0.1:40123/v1``."""
        return f"http://127.0.0.1:{self.port}/v1"

    # -- scripting -------------------------------------------------------------------------------------

    def push(self, step: Step, *, times: int = 1) -> None:
        """Queue ``step`` to answer the next ``times`` requests."""
        with self._lock:
            self._steps.extend([step] * times)

    def push_reply(
        self,
        content: str | Sequence[str | None] | None,
        *,
        finish_reason: str = "stop",
        model: str | None = None,
        usage: Mapping[str, int] | None = None,
        delay_s: float = 0.0,
        times: int = 1,
    ) -> None:
        """Queue a normal HTTP 200 completion; ``model`` defaults to the model the request named."""

        def build(request: RecordedRequest) -> Step:
            name = model or self._default_model or (request.json or {}).get("model", "fake-model")
            body = completion_body(content, model=name, finish_reason=finish_reason, usage=usage)
            return Step(body=json.dumps(body).encode(), delay_s=delay_s)

        with self._lock:
            self._steps.extend([build] * times)

    def push_status(
        self,
        status: int,
        message: str | None = None,
        *,
        headers: Mapping[str, str] | None = None,
        times: int = 1,
    ) -> None:
        """Queue an HTTP error status with an OpenAI-style error body (e.g. 429, 500, 401)."""
        text = message or f"fake OpenAI server: scripted HTTP {status}"
        body = json.dumps(error_body(text, code=str(status))).encode()
        self.push(Step(status=status, body=body, headers=dict(headers or {})), times=times)

    def push_raw(
        self,
        body: bytes | str,
        *,
        status: int = 200,
        content_type: str = "application/json",
        delay_s: float = 0.0,
    ) -> None:
        """Queue an arbitrary body, e.g. an HTML page or a JSON document missing ``choices``."""
        data = body.encode() if isinstance(body, str) else body
        self.push(Step(status=status, body=data, content_type=content_type, delay_s=delay_s))

    def push_truncated_json(self, content: str = "a reply cut short") -> None:
        """Queue a completion whose JSON text is cut in half (sent with a matching Content-Length)."""
        text = json.dumps(completion_body(content))
        self.push_raw(text[: len(text) // 2])

    def push_delay(self, delay_s: float, content: str = "too late") -> None:
        """Queue a normal reply sent only after ``delay_s`` seconds (to exceed a client timeout)."""
        self.push_reply(content, delay_s=delay_s)

    def push_trickle(self, content: str = "a reply that never ends", interval_s: float = 0.2) -> None:
        """Queue a normal reply whose body arrives one byte every ``interval_s`` seconds."""
        body = json.dumps(completion_body(content, model=self._default_model or "fake-model")).encode()
        self.push(Step(body=body + b" " * 10_000, trickle_s=interval_s))

    def push_disconnect(self, *, times: int = 1) -> None:
        """Queue a connection closed without any answer (a connection error for the client)."""
        self.push(Step(disconnect=True), times=times)

    def respond_with(self, responder: Responder | None) -> None:
        """Answer requests that find the queue empty with ``responder(request)`` (``None`` to unset)."""
        with self._lock:
            self._responder = responder

    # -- inspection ------------------------------------------------------------------------------------

    @property
    def requests(self) -> list[RecordedRequest]:
        """The requests received so far, in arrival order (a copy)."""
        with self._lock:
            return list(self._requests)

    @property
    def pending(self) -> int:
        """How many scripted steps have not been used yet."""
        with self._lock:
            return len(self._steps)

    # -- serving (called from handler threads) ---------------------------------------------------------

    def _next_step(self, request: RecordedRequest) -> Step:
        with self._lock:
            self._requests.append(request)
            number = len(self._requests)
            scripted = self._steps.popleft() if self._steps else None
            responder = self._responder
        if scripted is not None:
            return scripted(request) if callable(scripted) else scripted
        if responder is not None:
            answer = responder(request)
            if isinstance(answer, Step):
                return answer
            name = self._default_model or (request.json or {}).get("model", "fake-model")
            return Step(body=json.dumps(completion_body(answer, model=name)).encode())
        message = f"fake OpenAI server: no scripted reply left for request #{number}"
        return Step(status=400, body=json.dumps(error_body(message, type_="invalid_request_error")).encode())


class _Handler(BaseHTTPRequestHandler):
    fake: FakeOpenAIServer  # set on the per-server subclass

    def log_message(self, format: str, *args: Any) -> None:
        pass

    def do_POST(self) -> None:
        length = int(self.headers.get("Content-Length") or 0)
        body = self.rfile.read(length) if length else b""
        request = RecordedRequest("POST", self.path, dict(self.headers.items()), body)
        if self.path != CHAT_PATH:
            self._send(Step(status=404, body=json.dumps(error_body(f"no route {self.path}")).encode()))
            return
        step = self.fake._next_step(request)
        if step.delay_s and self.fake._stopping.wait(step.delay_s):
            return  # shutting down: abandon the reply
        if step.disconnect:
            self.close_connection = True
            return
        self._send(step)

    def do_GET(self) -> None:
        self._send(Step(status=404, body=json.dumps(error_body(f"no route {self.path}")).encode()))

    def _send(self, step: Step) -> None:
        try:
            self.send_response(step.status)
            self.send_header("Content-Type", step.content_type)
            self.send_header("Content-Length", str(len(step.body)))
            for name, value in step.headers.items():
                self.send_header(name, value)
            self.end_headers()
            if not step.trickle_s:
                self.wfile.write(step.body)
                return
            self.wfile.flush()
            for k in range(len(step.body)):
                if self.fake._stopping.wait(step.trickle_s):
                    return
                self.wfile.write(step.body[k : k + 1])
                self.wfile.flush()
        except (BrokenPipeError, ConnectionResetError):
            pass  # the client gave up (e.g. it timed out); nothing to answer
