"""The live client's total deadline per call and its line per retry."""

from __future__ import annotations

import dataclasses
import time

import pytest

from sgplan.errors import LLMError
from sgplan.llm.client import OpenAIChatClient
from sgplan.llm.config import LLMConfig, load_llm_config
from tests.llm.fake_openai_server import FakeOpenAIServer

ASK = [{"role": "user", "content": "hi"}]


def test_a_reply_that_trickles_in_is_cut_at_the_deadline(
    fake_llm: FakeOpenAIServer, llm_config: LLMConfig
) -> None:
    fake_llm.push_trickle(interval_s=0.1)  # never trips the 2 s per-read timeout
    config = dataclasses.replace(llm_config, deadline_s=1.0)
    started = time.monotonic()
    with (
        OpenAIChatClient(config, notify=lambda line: None) as client,
        pytest.raises(LLMError, match="1 s deadline"),
    ):
        client.complete(ASK)
    assert time.monotonic() - started < 5


def test_every_retry_is_announced_and_the_deadline_bounds_the_retries(fake_llm: FakeOpenAIServer,
                                                                      llm_config: LLMConfig) -> None:
    lines: list[str] = []
    fake_llm.push_status(503, times=2)
    fake_llm.push_reply("done")
    with OpenAIChatClient(llm_config, notify=lines.append) as client:
        assert client.complete(ASK).content == "done"
    assert len(lines) == 2 and all("retrying in" in line and "HTTP 503" in line for line in lines)

    fake_llm.push_delay(30)
    fake_llm.push_delay(30)
    config = dataclasses.replace(
        llm_config, timeout_s=0.5, deadline_s=1.2, backoff_base_s=0.3, backoff_max_s=0.3
    )
    started = time.monotonic()
    with OpenAIChatClient(config, notify=lines.append) as client, pytest.raises(LLMError, match="deadline"):
        client.complete(ASK)
    assert time.monotonic() - started < 4


def test_the_deadline_is_a_config_value() -> None:
    assert LLMConfig(model="m").deadline_s == 120.0
    assert (
        load_llm_config(None, model="m", base_url="http://127.0.0.1:1/v1", deadline_s=5.0).deadline_s == 5.0
    )
    with pytest.raises(LLMError, match="deadline_s"):
        LLMConfig(model="m", deadline_s=0)
