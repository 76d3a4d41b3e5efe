"""Who gets in and how much they may send: the token check and the request size limit, as pure ASGI
middleware (they run before any route, so a refused request never reaches the planner).

- :class:`TokenGuard`: with a token configured, every request must carry ``Authorization: Bearer
  <token>`` (compared in constant time, :func:`hmac.compare_digest`); the page's own assets and the page
  itself are no exception. A browser gets the page by opening ``/?token=...`` once: the page keeps the
  token and sends it as the header, and the query form is accepted for ``GET`` requests (an event stream
  cannot set headers).
- :class:`BodyLimit`: a body larger than :data:`sgplan.limits.MAX_REQUEST_BYTES` is refused with 413,
  whether it says its length up front or streams it.
"""

from __future__ import annotations

import hmac
import json
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any
from urllib.parse import parse_qs

from sgplan.limits import MAX_REQUEST_BYTES
from sgplan.serve.errors import HTTPProblem, error_body

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


async def _refuse(send: Send, problem: HTTPProblem, headers: list[tuple[bytes, bytes]] | None = None) -> None:
    body = json.dumps(error_body(problem.status, problem)).encode()
    await send(
        {
            "type": "http.response.start",
            "status": problem.status,
            "headers": [
                (b"content-type", b"application/json"),
                (b"content-length", str(len(body)).encode()),
                *(headers or []),
            ],
        }
    )
    await send({"type": "http.response.body", "body": body})


class TokenGuard:
    """Refuse (401) every HTTP request without the right token."""

    def __init__(self, app: ASGIApp, token: str) -> None:
        self.app = app
        self._token = token.encode()

    def _given(self, scope: Scope) -> bytes | None:
        for name, value in scope.get("headers", ()):
            if name == b"authorization" and value[:7].lower() == b"bearer ":
                return bytes(value[7:].strip())
        if scope.get("method") == "GET":
            values = parse_qs(scope.get("query_string", b"").decode("latin-1")).get("token")
            if values:
                return values[0].encode("latin-1", "replace")
        return None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        given = self._given(scope)
        if given is None or not hmac.compare_digest(given, self._token):
            what = "no token" if given is None else "a wrong token"
            problem = HTTPProblem(
                401,
                f"this server needs its token and the request carried {what}: send the "
                "header 'Authorization: Bearer <token>' (a browser: open /?token=<token>)",
            )
            await _refuse(send, problem, [(b"www-authenticate", b"Bearer")])
            return
        await self.app(scope, receive, send)


class BodyLimit:
    """Refuse (413) a request body over ``max_bytes``: the body is read here first (up to the limit), then
    handed to the application whole."""

    def __init__(self, app: ASGIApp, max_bytes: int = MAX_REQUEST_BYTES) -> None:
        self.app = app
        self.max_bytes = max_bytes

    def _problem(self) -> HTTPProblem:
        return HTTPProblem(
            413,
            f"the request body is larger than {self.max_bytes:,} bytes; send fewer poses or changes at a "
            "time",
        )

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        for name, value in scope.get("headers", ()):
            if name == b"content-length" and value.isdigit() and int(value) > self.max_bytes:
                await _refuse(send, self._problem())
                return
        chunks, size = [], 0
        while True:
            message = await receive()
            if message["type"] != "http.request":  # the client left
                return
            chunks.append(message.get("body", b""))
            size += len(chunks[-1])
            if size > self.max_bytes:
                await _refuse(send, self._problem())
                return
            if not message.get("more_body", False):
                break
        whole: list[Message] = [{"type": "http.request", "body": b"".join(chunks), "more_body": False}]

        async def replay() -> Message:
            return whole.pop() if whole else await receive()

        await self.app(scope, replay, send)
