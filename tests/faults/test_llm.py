"""A language-model server that hangs, stalls mid-body or answers garbage, and damaged cache entries:
each ends in one clean error within the call's deadline, with a visible line per retry."""

from __future__ import annotations

import json
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.faults.harness import PYTHONPATH, RECORD, check, generated
from tests.faults.strategies import damaged_json
from tests.llm.fake_openai_server import FakeOpenAIServer, Step, completion_body

DEADLINE_S = 4.0


def _under_test_has(text: str) -> bool:
    """Whether the sgplan under test knows ``text`` (an option added by the fix): when measuring an older
    checkout, options it lacks are left out rather than counted as its failures."""
    if not PYTHONPATH:
        return True
    return any(text in p.read_text() for p in Path(PYTHONPATH, "sgplan").rglob("*.py"))


@pytest.fixture
def server() -> Iterator[FakeOpenAIServer]:
    with FakeOpenAIServer(default_model="fake-model") as fake:
        yield fake


@pytest.fixture
def llm_args(server: FakeOpenAIServer, tmp_path: Path) -> list[str]:
    config = tmp_path / "llm.yaml"
    config.write_text("timeout_s: 1\nmax_retries: 2\nbackoff_base_s: 0.05\nbackoff_max_s: 0.1\n")
    args = ["--llm", "openai:fake-model", "--base-url", server.base_url, "--llm-config", str(config)]
    if _under_test_has("--llm-deadline"):
        args += ["--llm-deadline", str(DEADLINE_S)]
    return args


def _translate(tmp_path: Path, llm_args: list[str]) -> list[str]:
    return ["translate", "--scene", "demo", "--text", "Go to the bathroom on floor 0.", "--out",
            str(tmp_path / "mission"), *llm_args]


def _retry_lines(expected: int):  # type: ignore[no-untyped-def]
    def look(run):  # type: ignore[no-untyped-def]
        return None if run.stderr.count("retrying in") >= expected else "silent"
    return look


def test_server_that_never_answers(server: FakeOpenAIServer, tmp_path: Path, llm_args: list[str]) -> None:
    for _ in range(3):
        server.push_delay(600)
    run = check(
        "llm/server never answers", _translate(tmp_path, llm_args), must_fail=True, after=_retry_lines(2),
        allow=("clean",),
    )
    assert RECORD or run.wall_s < DEADLINE_S + 15


def test_server_that_stalls_mid_body(server: FakeOpenAIServer, tmp_path: Path, llm_args: list[str]) -> None:
    for _ in range(3):
        server.push_trickle(interval_s=0.2)
    run = check("llm/reply stalls mid-body", _translate(tmp_path, llm_args), must_fail=True)
    assert RECORD or "deadline" in run.stderr


_BODIES = st.one_of(
    st.sampled_from([
        b"<html><body>502 Bad Gateway</body></html>", b"", b"{", b"null", b"[]", b'{"choices": []}',
        b'{"choices": [{"message": {"content": null}}]}', b'{"choices": [{"message": {}}]}',
        b'{"choices": [{"message": {"content": "x"}, "finish_reason": "length"}]}', b'{"choices": "x"}',
        b'{"choices": [' + b"[" * 100_000 + b"]" * 100_000 + b"]}", b"\xff\xfe\x00garbage",
        json.dumps(completion_body("x" * 5_000_000)).encode(), b'{"choices": [{"message": {"content": 5}}]}',
    ]),
    st.binary(max_size=200),
)


@generated(10)
@given(body=_BODIES, status=st.sampled_from([200, 200, 500, 429]), content_type=st.sampled_from(
    ["application/json", "text/html"]))
def test_malformed_replies(server: FakeOpenAIServer, llm_args: list[str], body: bytes, status: int,
                           content_type: str) -> None:
    with tempfile.TemporaryDirectory(prefix="sgplan-fault-") as tmp:
        server.respond_with(lambda request: Step(status=status, body=body, content_type=content_type))
        check("llm/malformed reply", _translate(Path(tmp), llm_args), must_fail=True)
        server.respond_with(None)


@pytest.fixture(scope="module")
def recorded_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A cache holding the entries a translation recorded (the fake server answers every call "x")."""
    cache = tmp_path_factory.mktemp("llm-cache")
    with FakeOpenAIServer(default_model="fake-model") as fake:
        fake.respond_with(lambda request: "x")
        from sgplan.cli import main

        main(
            [
                "translate", "--scene", "demo", "--text", "Go to the bathroom on floor 0.", "--out",
                str(cache.parent / "recorded-mission"), "--llm", "openai:fake-model", "--base-url",
                fake.base_url, "--cache", str(cache),
            ]
        )
    assert list(cache.glob("*.json")), "the translation recorded no cache entry"
    return cache


@generated(12)
@given(data=st.data())
def test_damaged_cache_entries(recorded_cache: Path, data: st.DataObject) -> None:
    with tempfile.TemporaryDirectory(prefix="sgplan-fault-") as tmp:
        cache = Path(tmp) / "cache"
        cache.mkdir()
        for entry in sorted(recorded_cache.glob("*.json")):
            damaged = data.draw(damaged_json(json.loads(entry.read_text())))
            (cache / entry.name).write_bytes(damaged)
        check(
            "llm/damaged cache entry",
            [
                "translate", "--scene", "demo", "--text", "Go to the bathroom on floor 0.", "--out",
                str(Path(tmp) / "m"), "--llm", "openai:fake-model", "--cache", str(cache), "--replay",
            ],
        )


def test_cache_entry_with_empty_choices(recorded_cache: Path, tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    cache.mkdir()
    for entry in recorded_cache.glob("*.json"):
        document = json.loads(entry.read_text())
        document["response"]["choices"] = []
        (cache / entry.name).write_text(json.dumps(document))
    check(
        "llm/cache entry with empty choices",
        [
            "translate", "--scene", "demo", "--text", "Go to the bathroom on floor 0.", "--out",
            str(tmp_path / "m"), "--llm", "openai:fake-model", "--cache", str(cache), "--replay",
        ],
        must_fail=True,
    )
