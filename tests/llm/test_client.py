"""The live chat client against a real HTTP server on 127.0.0.1, plus its configuration and helpers."""

from __future__ import annotations

import dataclasses
import json
import random
import re
import socket
import threading
import time

import pytest

from sgplan.errors import LLMError
from sgplan.llm.client import (
    ChatBackend,
    ChatResult,
    OpenAIChatClient,
    RateLimiter,
    complete_many,
    normalize_messages,
    normalize_params,
)
from sgplan.llm.config import PLACEHOLDER_API_KEY, LLMConfig, load_llm_config

from .fake_openai_server import FakeOpenAIServer, Step, completion_body

ASK = [
    {"role": "system", "content": "You translate missions."},
    {"role": "user", "content": "Go to the kitchen."},
]


def make_client(config: LLMConfig, **changes: object) -> tuple[OpenAIChatClient, list[float]]:
    """A client whose backoff sleeps are recorded instead of slept."""
    slept: list[float] = []
    changed = dataclasses.replace(config, **changes)
    client = OpenAIChatClient(changed, sleep=slept.append, rng=random.Random(0))
    return client, slept


# -- successful calls -----------------------------------------------------------------------------------


def test_correct_reply_and_request_contents(fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient) -> None:
    usage = {"prompt_tokens": 5, "completion_tokens": 3, "total_tokens": 8}
    fake_llm.push_reply("['enter(room_3)']", usage=usage)
    result = llm_client.complete(ASK, temperature=0, max_tokens=50, seed=7)

    assert result.content == "['enter(room_3)']"
    assert result.choices == ("['enter(room_3)']",)
    assert result.model == "fake-model"
    assert result.finish_reason == "stop"
    assert result.usage == usage
    assert result.attempts == 1 and not result.from_cache and result.latency_s > 0

    (request,) = fake_llm.requests
    assert request.path == "/v1/chat/completions"
    assert request.headers["authorization"] == "Bearer test-key"
    sent = {"model": "fake-model", "messages": ASK, "temperature": 0.0, "max_tokens": 50, "seed": 7}
    assert request.json == sent


def test_backends_satisfy_the_protocol(llm_client: OpenAIChatClient) -> None:
    assert isinstance(llm_client, ChatBackend)
    assert llm_client.model == "fake-model" and "127.0.0.1" in llm_client.label


def test_n_choices_are_all_returned(fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient) -> None:
    fake_llm.push_reply(["first", "second", "third"])
    result = llm_client.complete(ASK, n=3)
    assert result.content == "first" and result.choices == ("first", "second", "third")


def test_fewer_choices_than_asked_is_an_error(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient,
) -> None:
    fake_llm.push_reply("only one")
    with pytest.raises(LLMError, match=r"has 1 choice\(s\) but n=3 were asked"):
        llm_client.complete(ASK, n=3)


def test_json_with_a_wrong_content_type_is_still_read(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient,
) -> None:
    fake_llm.push_raw(json.dumps(completion_body("fine")), content_type="text/plain")
    assert llm_client.complete(ASK).content == "fine"


def test_loopback_endpoint_ignores_proxy_settings(
    fake_llm: FakeOpenAIServer, llm_config: LLMConfig, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A dead loopback port as proxy: the call only succeeds if the proxy is bypassed.
    for name in ("HTTP_PROXY", "HTTPS_PROXY", "ALL_PROXY", "http_proxy", "all_proxy"):
        monkeypatch.setenv(name, "http://127.0.0.1:9")
    monkeypatch.delenv("NO_PROXY", raising=False)
    monkeypatch.delenv("no_proxy", raising=False)
    fake_llm.push_reply("direct")
    with OpenAIChatClient(llm_config) as client:
        assert client.complete(ASK).content == "direct"


# -- retries --------------------------------------------------------------------------------------------


def test_429_then_success_is_retried(fake_llm: FakeOpenAIServer, llm_config: LLMConfig) -> None:
    client, slept = make_client(llm_config)
    fake_llm.push_status(429, "Rate limit reached")
    fake_llm.push_reply("ok")
    result = client.complete(ASK)
    assert result.content == "ok" and result.attempts == 2
    assert len(fake_llm.requests) == 2 and len(slept) == 1
    assert fake_llm.requests[0].body == fake_llm.requests[1].body


def test_retry_after_header_is_honoured_up_to_the_backoff_cap(
    fake_llm: FakeOpenAIServer, llm_config: LLMConfig,
) -> None:
    client, slept = make_client(llm_config, backoff_max_s=0.05)
    fake_llm.push_status(429, headers={"Retry-After": "0.03"})
    fake_llm.push_status(429, headers={"Retry-After": "100"})
    fake_llm.push_reply("ok")
    assert client.complete(ASK).attempts == 3
    assert slept[0] >= 0.03 and slept[1] == pytest.approx(0.05)


def test_5xx_until_the_budget_ends(fake_llm: FakeOpenAIServer, llm_config: LLMConfig) -> None:
    client, slept = make_client(llm_config, max_retries=3)
    fake_llm.push_status(500, "The server had an error", times=2)
    fake_llm.push_status(503, "Overloaded", times=2)
    with pytest.raises(LLMError) as info:
        client.complete(ASK)
    message = str(info.value)
    assert message == (
        f"LLM call to {fake_llm.base_url}/chat/completions (model 'fake-model') failed after 4 attempts: "
        "HTTP 503: Overloaded"
    )
    assert len(fake_llm.requests) == 4 and len(slept) == 3 and fake_llm.pending == 0


def test_backoff_grows_exponentially_with_jitter(fake_llm: FakeOpenAIServer, llm_config: LLMConfig) -> None:
    client, slept = make_client(llm_config, max_retries=5, backoff_base_s=0.001, backoff_max_s=0.01)
    fake_llm.push_status(502, times=6)
    with pytest.raises(LLMError, match="after 6 attempts"):
        client.complete(ASK)
    ceilings = [0.001, 0.002, 0.004, 0.008, 0.01]
    assert len(slept) == len(ceilings)
    for delay, ceiling in zip(slept, ceilings):
        assert 0.5 * ceiling <= delay < ceiling


@pytest.mark.parametrize(
    ("status", "hint"),
    [
        (400, "not retried"),
        (401, "check the API key"),
        (403, "check the API key"),
        (404, "check the model name"),
    ],
)
def test_other_4xx_are_not_retried(
    fake_llm: FakeOpenAIServer, llm_config: LLMConfig, status: int, hint: str,
) -> None:
    client, slept = make_client(llm_config)
    fake_llm.push_status(status, "nope")
    fake_llm.push_reply("never sent")
    with pytest.raises(LLMError) as info:
        client.complete(ASK)
    assert f"failed after 1 attempt: HTTP {status}: nope (HTTP {status} is not retried)" in str(info.value)
    assert hint in str(info.value)
    assert len(fake_llm.requests) == 1 and slept == [] and fake_llm.pending == 1


def test_timeout_is_retried_then_reported(fake_llm: FakeOpenAIServer, llm_config: LLMConfig) -> None:
    client, _ = make_client(llm_config, timeout_s=0.2, max_retries=1)
    fake_llm.push_delay(5.0)
    fake_llm.push_delay(5.0)
    started = time.monotonic()
    with pytest.raises(LLMError, match=r"failed after 2 attempts: no answer within the 0.2 s timeout"):
        client.complete(ASK)
    assert time.monotonic() - started < 2.0
    assert len(fake_llm.requests) == 2


def test_timeout_then_success(fake_llm: FakeOpenAIServer, llm_config: LLMConfig) -> None:
    client, _ = make_client(llm_config, timeout_s=0.2)
    fake_llm.push_delay(5.0)
    fake_llm.push_reply("in time")
    assert client.complete(ASK).attempts == 2


def test_dropped_connection_is_retried(fake_llm: FakeOpenAIServer, llm_config: LLMConfig) -> None:
    client, _ = make_client(llm_config)
    fake_llm.push_disconnect()
    fake_llm.push_reply("ok")
    result = client.complete(ASK)
    assert result.content == "ok" and result.attempts == 2


def test_unreachable_server(llm_config: LLMConfig, fake_llm: FakeOpenAIServer) -> None:
    client, slept = make_client(llm_config)
    fake_llm.stop()
    with pytest.raises(LLMError, match=r"127\.0\.0\.1.*failed after 3 attempts: connection failed") as error:
        client.complete(ASK)
    assert len(slept) == 2
    hint = f"is a server running at {llm_config.endpoint}? (--base-url, or base_url in the LLM config)"
    assert str(error.value).endswith(hint)


# -- malformed replies ----------------------------------------------------------------------------------


def test_truncated_json_is_an_error_and_not_retried(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient,
) -> None:
    fake_llm.push_truncated_json()
    with pytest.raises(LLMError) as info:
        llm_client.complete(ASK)
    message = str(info.value)
    assert "(model 'fake-model', attempt 1) is not valid JSON (truncated or malformed body" in message
    assert "content-type 'application/json'" in message and "\n" not in message
    assert len(fake_llm.requests) == 1


def test_html_instead_of_json(fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient) -> None:
    fake_llm.push_raw("<html><body>Proxy login</body></html>", content_type="text/html")
    expected = r"not valid JSON .*content-type 'text/html', starting '<html><body>Proxy"
    with pytest.raises(LLMError, match=expected):
        llm_client.complete(ASK)


@pytest.mark.parametrize(
    ("content", "finish_reason", "expected"),
    [
        ("", "stop", "choice 0 has empty content (finish_reason 'stop')"),
        ("  \n ", "stop", "choice 0 has empty content"),
        (None, "length", "hit the token limit before any text; raise max_tokens)"),
        (
            "<think>Let me see... the kitchen is", "length",
            "only a <think> reasoning block, no answer; raise max_tokens",
        ),
        ("<think>done</think>\n ", "stop", "only a <think> reasoning block, no answer)"),
    ],
)
def test_empty_content(
    fake_llm: FakeOpenAIServer,
    llm_client: OpenAIChatClient,
    content: str | None,
    finish_reason: str,
    expected: str,
) -> None:
    fake_llm.push_reply(content, finish_reason=finish_reason)
    with pytest.raises(LLMError, match=re.escape(expected)):
        llm_client.complete(ASK)
    assert len(fake_llm.requests) == 1


def test_a_leading_reasoning_block_is_not_part_of_the_answer(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient,
) -> None:
    fake_llm.push_reply(
        "<think>\nThe user wants <command>move(1, 2)</command>? No.\n</think>\n<command>move(2, 3)</command>"
    )
    assert llm_client.complete(ASK).content == "\n<command>move(2, 3)</command>"
    fake_llm.push_reply("The answer mentions <think> later, and stays whole.")
    assert llm_client.complete(ASK).content == "The answer mentions <think> later, and stays whole."
    # the template opened the block in the prompt: the reply starts inside it
    fake_llm.push_reply("the kitchen is room_4\n</think>\n['EVENTUALLY', 'enter(room_4)']")
    assert llm_client.complete(ASK).content == "\n['EVENTUALLY', 'enter(room_4)']"


def test_refusal_is_reported(fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient) -> None:
    body = completion_body(None)
    body["choices"][0]["message"]["refusal"] = "I can't help with that."
    fake_llm.push_raw(json.dumps(body))
    with pytest.raises(LLMError, match=r"the model refused: I can't help with that."):
        llm_client.complete(ASK)


@pytest.mark.parametrize(
    ("body", "expected"),
    [
        ({"id": "x", "object": "chat.completion"}, r"has no 'choices' \(not a chat completion\)"),
        ({"choices": []}, "has no 'choices'"),
        ({"error": {"message": "model overloaded"}}, "has no 'choices' .*the server says: model overloaded"),
        ({"choices": [{"index": 0}]}, "choice 0 has no 'message' object"),
        (["not", "an", "object"], "is JSON but not an object"),
    ],
)
def test_malformed_completion(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient, body: object, expected: str,
) -> None:
    fake_llm.push_raw(json.dumps(body))
    with pytest.raises(LLMError, match=expected):
        llm_client.complete(ASK)


# -- request validation ---------------------------------------------------------------------------------


def test_normalize_params() -> None:
    normalized = normalize_params({"temperature": 0, "seed": None, "stop": "END"})
    assert normalized == {"stop": ["END"], "temperature": 0.0}
    assert list(normalize_params({"seed": 1, "max_tokens": 9, "n": 2})) == ["max_tokens", "n", "seed"]
    with pytest.raises(LLMError, match="unknown parameter 'temprature'"):
        normalize_params({"temprature": 0})
    with pytest.raises(LLMError, match="seed=True has the wrong type"):
        normalize_params({"seed": True})
    with pytest.raises(LLMError, match="n must be at least 1"):
        normalize_params({"n": 0})


def test_normalize_messages() -> None:
    assert normalize_messages(ASK) == ASK
    bad_requests = (
        [],
        "hello",
        [{"role": "user"}],
        [{"role": "robot", "content": "x"}],
        [{"role": "user", "content": 3}],
    )
    for bad in bad_requests:
        with pytest.raises(LLMError, match="chat request"):
            normalize_messages(bad)  # type: ignore[arg-type]


def test_bad_request_fails_before_any_traffic(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient,
) -> None:
    with pytest.raises(LLMError, match="unknown parameter"):
        llm_client.complete(ASK, top_k=3)
    assert fake_llm.requests == []


def test_chat_result_choices_must_start_with_content() -> None:
    assert ChatResult(content="a", model="m").choices == ("a",)
    with pytest.raises(ValueError, match="choices"):
        ChatResult(content="a", model="m", choices=("b",))


# -- concurrency and rate limiting ----------------------------------------------------------------------


def test_rate_limiter_spaces_requests() -> None:
    now = [100.0]
    slept: list[float] = []

    def sleep(seconds: float) -> None:
        slept.append(seconds)
        now[0] += seconds

    limiter = RateLimiter(120, clock=lambda: now[0], sleep=sleep)  # one start every 0.5 s
    waits = [limiter.acquire() for _ in range(4)]
    assert waits == [0.0, 0.5, 0.5, 0.5] and slept == [0.5, 0.5, 0.5]
    now[0] += 10.0  # idle time does not bank a burst of requests
    assert limiter.acquire() == 0.0 and limiter.acquire() == 0.5


def test_client_rate_limit_applies_to_every_attempt(
    fake_llm: FakeOpenAIServer, llm_config: LLMConfig,
) -> None:
    client, slept = make_client(llm_config, requests_per_minute=600)  # 0.1 s apart
    # The limiter's clock stands still (the sleeps are recorded, not slept): however long the failed
    # request takes on a loaded machine, the retry must wait for its slot.
    client._rate_limiter = RateLimiter(600, clock=lambda: 0.0, sleep=slept.append)
    fake_llm.push_status(500)
    fake_llm.push_reply("ok")
    client.complete(ASK)
    assert len(slept) == 2 and max(slept) == pytest.approx(0.1)  # one backoff (ms), one rate-limit wait


def test_complete_many_keeps_order_limits_concurrency_and_isolates_errors(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient
) -> None:
    in_flight = [0, 0]  # current, maximum seen
    lock = threading.Lock()

    def responder(request):  # type: ignore[no-untyped-def]
        with lock:
            in_flight[0] += 1
            in_flight[1] = max(in_flight[1], in_flight[0])
        time.sleep(0.05)
        with lock:
            in_flight[0] -= 1
        text = request.last_user_message
        if text == "q3":
            return Step(status=400, body=b'{"error": {"message": "bad"}}')
        return f"answer to {text}"

    fake_llm.respond_with(responder)
    requests = [([{"role": "user", "content": f"q{i}"}], {"temperature": 0}) for i in range(8)]
    results = complete_many(llm_client, requests, max_concurrency=3)

    assert isinstance(results[3], LLMError) and "HTTP 400: bad" in str(results[3])
    for i, result in enumerate(results):
        if i != 3:
            assert isinstance(result, ChatResult) and result.content == f"answer to q{i}"
    assert 2 <= in_flight[1] <= 3


# -- configuration --------------------------------------------------------------------------------------


def test_config_precedence_explicit_then_file_then_environment(
    tmp_path,
) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "llm.yaml"
    path.write_text("model: from-file\nbase_url: http://127.0.0.1:8000/v1\ntimeout_s: 5\n")
    env = {"OPENAI_API_KEY": "env-key", "OPENAI_BASE_URL": "http://127.0.0.1:1/v1"}
    config = load_llm_config(path, environ=env, model="explicit", max_retries=None)
    assert (config.model, config.base_url, config.timeout_s, config.api_key) == (
        "explicit", "http://127.0.0.1:8000/v1", 5, "env-key",
    )
    assert config.max_retries == LLMConfig(model="x").max_retries
    assert "env-key" not in repr(config)


def test_config_key_sources(tmp_path) -> None:  # type: ignore[no-untyped-def]
    both = {"SGPLAN_LLM_API_KEY": "sgplan-key", "OPENAI_API_KEY": "openai-key"}
    assert load_llm_config(environ=both, model="gpt-4o").api_key == "sgplan-key"
    local = load_llm_config(environ={}, model="llama3", base_url="http://127.0.0.1:11434/v1")
    assert local.api_key == PLACEHOLDER_API_KEY
    expected = r"no API key for https://api.openai.com/v1: set \$SGPLAN_LLM_API_KEY or \$OPENAI_API_KEY"
    with pytest.raises(LLMError, match=expected):
        load_llm_config(environ={}, model="gpt-4o")
    path = tmp_path / "llm.yaml"
    path.write_text("model: gpt-4o\napi_key_env: MY_KEY\n")
    assert load_llm_config(path, environ={"MY_KEY": "k", "OPENAI_API_KEY": "other"}).api_key == "k"
    with pytest.raises(LLMError, match=r"api_key_env names \$MY_KEY, which is not set"):
        load_llm_config(path, environ={})
    assert load_llm_config(environ={"SGPLAN_LLM_CONFIG": str(path), "MY_KEY": "k"}).model == "gpt-4o"


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("model: m\ntimeout: 3\n", r"llm.yaml: unknown LLM option\(s\) timeout"),
        ("model: m\ntimeout_s: -1\n", r"llm.yaml: LLM config: 'timeout_s' must be a finite number > 0"),
        ("model: m\nmax_retries: 1.5\n", r"llm.yaml: LLM config: 'max_retries' must be an integer"),
        ("model: m\nbase_url: localhost:8000\n", r"llm.yaml: LLM config: base_url 'localhost:8000' is not"),
        ("- model\n", r"llm.yaml: an LLM config file must be a mapping"),
        ("model: [\n", r"llm.yaml: cannot read the LLM config file"),
        ("base_url: http://127.0.0.1:1/v1\n", r"no LLM model given: .* or set 'model' in .*llm.yaml"),
    ],
)
def test_config_file_errors(tmp_path, text: str, expected: str) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "llm.yaml"
    path.write_text(text)
    with pytest.raises(LLMError, match=expected):
        load_llm_config(path, environ={"OPENAI_API_KEY": "k"})


def test_config_file_missing(tmp_path) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(LLMError, match=r"llm.yaml: LLM config file not found"):
        load_llm_config(tmp_path / "llm.yaml", environ={})


def test_tests_cannot_leave_loopback() -> None:
    with pytest.raises(AssertionError, match="must stay on loopback"):
        socket.getaddrinfo("api.openai.com", 443)
    with (
        socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock,
        pytest.raises(AssertionError, match="loopback"),
    ):
        sock.connect(("192.0.2.1", 443))  # TEST-NET-1; the guard refuses before any packet is sent
