"""Fixtures for the LLM layer's tests: a scripted OpenAI-compatible server on 127.0.0.1 and clients for it.

- ``fake_llm``: a running :class:`FakeOpenAIServer` (stopped at teardown). Script it with
  ``fake_llm.push_reply("...")``, ``fake_llm.push_status(429)``, ``push_delay``, ``push_truncated_json``,
  ``push_raw``, ``push_disconnect`` or ``respond_with(fn)``; inspect ``fake_llm.requests``.
- ``llm_config``: an :class:`LLMConfig` for it with a 2 s timeout, 2 retries and millisecond backoffs.
- ``llm_client``: an :class:`OpenAIChatClient` on ``llm_config`` (closed at teardown).

Every test in this directory runs under ``_loopback_only``: resolving or connecting to any address that is
not loopback fails the test, so no test here can reach a real service by mistake.
"""

from __future__ import annotations

import ipaddress
import socket
from collections.abc import Iterator

import pytest

from sgplan.llm.client import OpenAIChatClient
from sgplan.llm.config import LLMConfig

from .fake_openai_server import FakeOpenAIServer


def _is_loopback_host(host: object) -> bool:
    if host in ("localhost", None):
        return True
    try:
        return ipaddress.ip_address(str(host).split("%")[0]).is_loopback
    except ValueError:
        return False


@pytest.fixture(autouse=True)
def _loopback_only(monkeypatch: pytest.MonkeyPatch) -> None:
    """Refuse DNS look-ups and connections to anything but loopback addresses."""
    real_getaddrinfo = socket.getaddrinfo
    real_connect = socket.socket.connect
    real_connect_ex = socket.socket.connect_ex

    def getaddrinfo(host, *args, **kwargs):  # type: ignore[no-untyped-def]
        if not _is_loopback_host(host):
            raise AssertionError(f"LLM tests must stay on loopback, but {host!r} was looked up")
        return real_getaddrinfo(host, *args, **kwargs)

    def check(sock: socket.socket, address: object) -> None:
        is_ip = sock.family in (socket.AF_INET, socket.AF_INET6)
        if is_ip and not _is_loopback_host(address[0]):  # type: ignore[index]
            raise AssertionError(f"LLM tests must stay on loopback, but {address!r} was contacted")

    def connect(sock, address):  # type: ignore[no-untyped-def]
        check(sock, address)
        return real_connect(sock, address)

    def connect_ex(sock, address):  # type: ignore[no-untyped-def]
        check(sock, address)
        return real_connect_ex(sock, address)

    monkeypatch.setattr(socket, "getaddrinfo", getaddrinfo)
    monkeypatch.setattr(socket.socket, "connect", connect)
    monkeypatch.setattr(socket.socket, "connect_ex", connect_ex)


@pytest.fixture
def fake_llm() -> Iterator[FakeOpenAIServer]:
    """A scripted chat-completions server on an ephemeral 127.0.0.1 port."""
    with FakeOpenAIServer() as server:
        yield server


@pytest.fixture
def llm_config(fake_llm: FakeOpenAIServer) -> LLMConfig:
    """Settings for ``fake_llm`` that keep failing tests fast (tiny backoffs, 2 retries)."""
    return LLMConfig(
        model="fake-model",
        base_url=fake_llm.base_url,
        api_key="test-key",
        timeout_s=2.0,
        max_retries=2,
        backoff_base_s=0.001,
        backoff_max_s=0.01,
    )


@pytest.fixture
def llm_client(llm_config: LLMConfig) -> Iterator[OpenAIChatClient]:
    """A live client for ``fake_llm``."""
    with OpenAIChatClient(llm_config) as client:
        yield client
