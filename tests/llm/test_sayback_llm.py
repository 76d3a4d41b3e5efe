"""A misgrounding LLM is visible before planning: the explanation names what the ids really are."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from sgplan.cli import main

from .fake_openai_server import RecordedRequest


def misgrounding_model(request: RecordedRequest) -> str:
    """Grounds "the kitchen" as room_5, which is the demo's bathroom."""
    system = request.messages[0]["content"]
    if system.startswith("You rewrite a robot's mission"):
        return json.dumps({"grounded": "Go to room_5.", "problems": []})
    return "['EVENTUALLY', 'enter(room_5)']"


@pytest.fixture(autouse=True)
def _clean_llm_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ("OPENAI_BASE_URL", "SGPLAN_LLM_CONFIG", "OPENAI_API_KEY", "SGPLAN_LLM_API_KEY"):
        monkeypatch.delenv(name, raising=False)


def test_plan_text_says_the_bathroom_was_understood(fake_llm, tmp_path: Path,  # type: ignore[no-untyped-def]
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    fake_llm.respond_with(misgrounding_model)
    config = tmp_path / "llm.yaml"
    config.write_text(yaml.safe_dump({"timeout_s": 2.0, "max_retries": 1}))
    out = tmp_path / "r.json"
    argv = [
        "plan", "--scene", "demo", "--text", "Go to the kitchen.", "--setup", "NO-LLM", "--json", str(out),
        "--llm", "openai:fake-model", "--base-url", fake_llm.base_url, "--llm-config", str(config),
        "--save-mission", str(tmp_path / "m"),
    ]
    assert main(argv) == 0
    assert "Go to the bathroom (room_5, floor 0)." in capsys.readouterr().out
    assert "bathroom (room_5" in json.loads(out.read_text())["explanation"]["text"]
    events = json.loads((tmp_path / "m" / "llm_record.json").read_text())["events"]
    assert any(e["kind"] == "explained" and "the bathroom (room_5" in e["text"] for e in events)
