"""Record/replay cache: stable keys, atomic entries, offline replay, precise misses."""

from __future__ import annotations

import dataclasses
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from sgplan import files as files_module
from sgplan.errors import LLMError
from sgplan.llm.cache import CachedChatBackend, ChatCache, cache_key, cache_request, open_chat_backend
from sgplan.llm.client import ChatBackend, ChatResult, OpenAIChatClient, complete_many
from sgplan.llm.config import LLMConfig

from .fake_openai_server import FakeOpenAIServer

MESSAGES = [
    {"role": "system", "content": "You ground missions in a scene graph."},
    {"role": "user", "content": "Go to the bathroom on floor 0, then water the plant in the kitchen."},
]
PARAMS = {"temperature": 0.0, "max_tokens": 400, "n": 1, "seed": 3}

# The key of (MODEL, MESSAGES, PARAMS). Pinned: if it changes, every recorded cache becomes unreachable,
# so a change must come with a new key version on purpose.
GOLDEN_KEY = "3e54944eca6c93144f27e0d7c72afa5a895ed1762c7aaceacb0d4337f66bf799"
MODEL = "gpt-4o"


def entries(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir()) if directory.exists() else []


# -- keys -----------------------------------------------------------------------------------------------


def test_key_is_pinned() -> None:
    assert cache_key(MODEL, MESSAGES, PARAMS) == GOLDEN_KEY


def test_key_is_stable_across_processes() -> None:
    code = textwrap.dedent(
        f"""
        from sgplan.llm.cache import cache_key
        print(cache_key({MODEL!r}, {MESSAGES!r}, {PARAMS!r}))
        """
    )
    for seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        assert out.stdout.strip() == GOLDEN_KEY


@pytest.mark.parametrize(
    "change",
    [
        {"model": "gpt-4o-mini"},
        {"messages": [MESSAGES[0], {**MESSAGES[1], "content": MESSAGES[1]["content"] + " "}]},
        {"messages": [{**MESSAGES[0], "role": "user"}, MESSAGES[1]]},
        {"messages": MESSAGES[1:]},
        {"params": {**PARAMS, "temperature": 0.7}},
        {"params": {**PARAMS, "max_tokens": 401}},
        {"params": {**PARAMS, "n": 2}},
        {"params": {**PARAMS, "seed": 4}},
        {"params": {k: v for k, v in PARAMS.items() if k != "seed"}},
        {"params": {**PARAMS, "top_p": 0.9}},
        {"params": {**PARAMS, "stop": ["</command>"]}},
    ],
    ids=lambda change: next(iter(change)) + ":" + json.dumps(change)[:40],
)
def test_key_differs_when_anything_differs(change: dict) -> None:
    call = {"model": MODEL, "messages": MESSAGES, "params": PARAMS, **change}
    assert cache_key(call["model"], call["messages"], call["params"]) != GOLDEN_KEY


def test_key_ignores_spelling_of_equal_parameters() -> None:
    same = {"seed": 3, "n": 1, "max_tokens": 400, "temperature": 0, "top_p": None}
    assert cache_key(MODEL, MESSAGES, same) == GOLDEN_KEY
    assert cache_key(MODEL, [dict(m) for m in MESSAGES], PARAMS) == GOLDEN_KEY


# -- record and replay ----------------------------------------------------------------------------------


def test_record_then_replay_offline(
    fake_llm: FakeOpenAIServer, llm_config: LLMConfig, tmp_path: Path,
) -> None:
    fake_llm.push_reply("object_27 then room_4")
    with OpenAIChatClient(llm_config) as client:
        recorder = CachedChatBackend(tmp_path, mode="record", inner=client)
        recorded = recorder.complete(MESSAGES, **PARAMS)
        again = recorder.complete(MESSAGES, **PARAMS)  # a hit: no second request
    assert not recorded.from_cache and again.from_cache
    assert len(fake_llm.requests) == 1
    fake_llm.stop()

    replayer = CachedChatBackend(tmp_path, mode="replay", model=llm_config.model)
    replayed = replayer.complete(MESSAGES, **PARAMS)
    assert replayed == dataclasses.replace(recorded, from_cache=True)
    assert replayed.content == "object_27 then room_4"
    assert isinstance(replayer, ChatBackend) and isinstance(recorder, ChatBackend)


def record_one(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient, folder: Path, reply: str
) -> tuple[str, str]:
    """Record one call answered with ``reply`` into ``folder``; the entry's file name and text."""
    fake_llm.push_reply(reply)
    CachedChatBackend(folder, mode="record", inner=llm_client).complete(MESSAGES, temperature=0)
    (name,) = entries(folder)
    return name, (folder / name).read_text(encoding="utf-8")


def test_an_entry_recorded_with_its_reasoning_replays_without_it(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient, tmp_path: Path,
) -> None:
    name, _ = record_one(fake_llm, llm_client, tmp_path, "['enter(room_3)']")
    entry = json.loads((tmp_path / name).read_text(encoding="utf-8"))
    old = "<think>room_3 it is</think>['enter(room_3)']"  # as an earlier sgplan recorded it
    entry["response"].update(content=old, choices=[old])
    (tmp_path / name).write_text(json.dumps(entry), encoding="utf-8")
    replayed = CachedChatBackend(tmp_path, mode="replay", model="fake-model").complete(
        MESSAGES, temperature=0
    )
    assert replayed.content == "['enter(room_3)']" and replayed.choices == ("['enter(room_3)']",)


def test_entry_is_human_readable(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient, tmp_path: Path,
) -> None:
    name, text = record_one(fake_llm, llm_client, tmp_path, "['enter(room_3)']")
    entry = json.loads(text)
    assert name == f"{entry['key']}.json"
    assert entry["format"] == "sgplan-llm-cache/1"
    assert entry["request"] == {"model": "fake-model", "messages": MESSAGES, "params": {"temperature": 0.0}}
    assert entry["response"]["content"] == "['enter(room_3)']"
    assert entry["endpoint"] == llm_client.label
    assert "\n  " in text  # indented, one field per line


def test_replay_miss_names_the_call(tmp_path: Path) -> None:
    replayer = CachedChatBackend(tmp_path, mode="replay", model=MODEL)
    long_question = "Visit every bathroom on the second floor, " * 4
    messages = [MESSAGES[0], {"role": "user", "content": long_question}]
    messages.append({"role": "assistant", "content": "ok"})  # the last *user* message is quoted
    with pytest.raises(LLMError) as info:
        replayer.complete(messages, **PARAMS)
    key = cache_key(MODEL, messages, PARAMS)
    assert str(info.value) == (
        f"replay: no recorded LLM call for model 'gpt-4o' asking '{long_question[:77]}...' (key {key[:16]}) "
        f"in {tmp_path}; run once with recording enabled (a cache without --replay) to record it"
    )


def test_failed_calls_are_not_recorded(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient, tmp_path: Path,
) -> None:
    fake_llm.push_status(500, times=3)
    with pytest.raises(LLMError, match="failed after 3 attempts"):
        CachedChatBackend(tmp_path, mode="record", inner=llm_client).complete(MESSAGES)
    assert entries(tmp_path) == []


def test_concurrent_identical_misses_are_sent_once(
    fake_llm: FakeOpenAIServer, llm_client: OpenAIChatClient, tmp_path: Path,
) -> None:
    fake_llm.push_reply("shared", delay_s=0.1)
    recorder = CachedChatBackend(tmp_path, mode="record", inner=llm_client)
    results = complete_many(recorder, [(MESSAGES, PARAMS)] * 4, max_concurrency=4)
    assert all(isinstance(r, ChatResult) and r.content == "shared" for r in results)
    assert len(fake_llm.requests) == 1
    assert sum(not r.from_cache for r in results) == 1  # type: ignore[union-attr]


# -- atomic writes and damaged entries ------------------------------------------------------------------


def result(content: str = "answer") -> ChatResult:
    return ChatResult(content=content, model=MODEL, finish_reason="stop", latency_s=0.25)


@pytest.mark.parametrize("failure", [OSError("disk full"), KeyboardInterrupt()])
def test_interrupted_write_leaves_no_entry(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, failure: BaseException,
) -> None:
    cache = ChatCache(tmp_path)
    request = cache_request(MODEL, MESSAGES, PARAMS)
    written: list[str] = []

    def failing_replace(src: str, dst: str) -> None:
        written.append(Path(src).read_text(encoding="utf-8"))  # the temp file was fully written...
        raise failure  # ...but the process fails before it is moved into place

    monkeypatch.setattr(files_module.os, "replace", failing_replace)
    expected = LLMError if isinstance(failure, OSError) else KeyboardInterrupt
    with pytest.raises(expected):
        cache.put(GOLDEN_KEY, request, result(), endpoint="test")
    assert written and json.loads(written[0])["key"] == GOLDEN_KEY
    assert entries(tmp_path) == []  # neither the entry nor the temporary file remains
    monkeypatch.undo()
    assert cache.get(GOLDEN_KEY, request) is None


def test_crash_between_write_and_rename_leaves_no_entry(tmp_path: Path) -> None:
    # A real crash: the process dies (no cleanup runs) after writing the temp file, before the rename.
    code = textwrap.dedent(
        f"""
        import os
        from sgplan import files
        from sgplan.llm import cache as cache_module
        from sgplan.llm.client import ChatResult
        files.os.replace = lambda src, dst: os._exit(17)
        request = cache_module.cache_request({MODEL!r}, {MESSAGES!r}, {PARAMS!r})
        cache = cache_module.ChatCache({str(tmp_path)!r})
        cache.put({GOLDEN_KEY!r}, request, ChatResult("x", "m"), endpoint="t")
        """
    )
    assert subprocess.run([sys.executable, "-c", code], capture_output=True).returncode == 17
    (leftover,) = entries(tmp_path)
    assert leftover.startswith(".") and leftover.endswith(".tmp")
    replayer = CachedChatBackend(tmp_path, mode="replay", model=MODEL)
    with pytest.raises(LLMError, match="replay: no recorded LLM call"):
        replayer.complete(MESSAGES, **PARAMS)
    # Recording again works and the stray temporary file is never mistaken for an entry.
    ChatCache(tmp_path).put(GOLDEN_KEY, cache_request(MODEL, MESSAGES, PARAMS), result("y"), endpoint="t")
    assert replayer.complete(MESSAGES, **PARAMS).content == "y"


@pytest.mark.parametrize(
    ("damage", "expected"),
    [
        (lambda text: text[: len(text) // 2], "unreadable LLM cache entry"),
        (lambda text: "[]", "not an LLM cache entry of format 'sgplan-llm-cache/1'"),
        (lambda text: text.replace("Go to the bathroom", "Go to the kitchen"), "records a different request"),
        (lambda text: text.replace('"choices"', '"choice"'), "malformed 'response' in LLM cache entry"),
    ],
)
def test_damaged_entry_is_reported(
    tmp_path: Path, damage, expected: str,
) -> None:  # type: ignore[no-untyped-def]
    cache = ChatCache(tmp_path)
    request = cache_request(MODEL, MESSAGES, PARAMS)
    path = cache.put(GOLDEN_KEY, request, result(), endpoint="t")
    path.write_text(damage(path.read_text(encoding="utf-8")), encoding="utf-8")
    with pytest.raises(LLMError, match=f"{path.name}: .*{expected}"):
        cache.get(GOLDEN_KEY, request)


def test_a_cache_directory_that_is_a_file_is_refused_when_opened(tmp_path: Path) -> None:
    blocker = tmp_path / "not-a-dir"
    blocker.write_text("")
    with pytest.raises(LLMError, match=r"is a file, not a folder: give --cache a folder"):
        ChatCache(blocker)
    with pytest.raises(LLMError, match=r"inside .*not-a-dir, a file, not a folder"):
        ChatCache(blocker / "below")


def test_unwritable_cache_directory(tmp_path: Path) -> None:
    cache = ChatCache(tmp_path / "cache")
    (tmp_path / "cache").write_text("")  # made a file after the cache was opened
    with pytest.raises(LLMError, match="cannot write LLM cache entry"):
        cache.put(GOLDEN_KEY, cache_request(MODEL, MESSAGES, PARAMS), result(), endpoint="t")


# -- choosing a backend ---------------------------------------------------------------------------------


def test_open_chat_backend_modes(llm_config: LLMConfig, tmp_path: Path) -> None:
    live = open_chat_backend("live", config=llm_config)
    assert isinstance(live, OpenAIChatClient)
    record = open_chat_backend("record", config=llm_config, cache_dir=tmp_path)
    assert isinstance(record, CachedChatBackend) and record.mode == "record"
    assert record.label.endswith(f"recorded in {tmp_path}")
    replay = open_chat_backend("replay", cache_dir=tmp_path, model="gpt-4o")  # no config, no key needed
    assert replay.model == "gpt-4o" and replay.label == f"gpt-4o replayed from {tmp_path}"
    live.close()
    record.inner.close()  # type: ignore[union-attr]


@pytest.mark.parametrize(
    ("kwargs", "expected"),
    [
        ({"mode": "offline"}, "unknown LLM cache mode 'offline'"),
        ({"mode": "record"}, "needs a cache directory"),
        ({"mode": "replay", "cache_dir": "x"}, "replay needs the model name"),
        ({"mode": "record", "cache_dir": "x"}, "needs an endpoint configuration"),
    ],
)
def test_open_chat_backend_errors(kwargs: dict, expected: str) -> None:
    with pytest.raises(LLMError, match=expected):
        open_chat_backend(**kwargs)


def test_cached_backend_arguments(llm_client: OpenAIChatClient, tmp_path: Path) -> None:
    with pytest.raises(LLMError, match="record mode needs a live backend"):
        CachedChatBackend(tmp_path, mode="record")
    with pytest.raises(LLMError, match="differs from the backend's model"):
        CachedChatBackend(tmp_path, mode="record", inner=llm_client, model="other")


def test_replay_does_not_load_the_sdk(tmp_path: Path) -> None:
    # Offline runs stay fast: the OpenAI SDK (~0.6 s to import) is loaded only by a live client.
    code = textwrap.dedent(
        f"""
        import sys
        from sgplan.llm.cache import open_chat_backend
        backend = open_chat_backend("replay", cache_dir={str(tmp_path)!r}, model="m")
        assert "openai" not in sys.modules, "the SDK was imported"
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
