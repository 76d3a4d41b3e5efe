"""Prompt templates: every shipped file parses, carries its version, and renders strictly."""

from __future__ import annotations

import pytest

from sgplan.errors import LLMError
from sgplan.llm.grounding import environment_text
from sgplan.llm.prompts import PROMPT_NAMES, load_prompt, parse_template
from sgplan.scene.demo import demo_building

EXPECTED = {
    "hierarchy": {"hierarchy"},
    "grounding": {"environment", "mission"},
    "grounding_repair": {"error"},
    "translation": {"ids", "grounded"},
    "repair": {"error", "marked", "ids"},
    "guidance": {"environment", "mission_context", "room", "remaining"},
}


@pytest.mark.parametrize("name", PROMPT_NAMES)
def test_shipped_templates_have_versions_and_the_expected_placeholders(name: str) -> None:
    template = load_prompt(name)
    assert template.version.startswith(f"{name}/")
    assert template.placeholders == EXPECTED[name]


def test_chat_templates_render_roles_in_order_and_fragments_render_text() -> None:
    messages = load_prompt("translation").messages(ids="[room_2]", grounded="Visit room_2.")
    assert [m["role"] for m in messages] == ["system", "user"]
    assert messages[-1]["content"] == "IDs in the mission: [room_2]\nMission: Visit room_2."
    assert "NEXT" in messages[0]["content"] and "'NEXT', 'enter(room_2)'" in messages[0]["content"]
    guidance = load_prompt("guidance").messages(
        environment="E", mission_context="", room="room_2", remaining="1. x."
    )
    assert [m["role"] for m in guidance] == ["system", "user", "assistant", "user"]
    with pytest.raises(LLMError, match="fragment"):
        load_prompt("hierarchy").messages(hierarchy="x")
    with pytest.raises(LLMError, match="not a text fragment"):
        load_prompt("repair").text(error="e", marked="m", ids="i")


def test_rendering_refuses_missing_and_unused_values() -> None:
    with pytest.raises(LLMError, match=r"missing for \['grounded'\]"):
        load_prompt("translation").messages(ids="[room_2]")
    with pytest.raises(LLMError, match=r"unused \['extra'\]"):
        load_prompt("translation").messages(ids="x", grounded="y", extra="z")


def test_values_are_inserted_verbatim_even_with_dollars_and_braces() -> None:
    text = load_prompt("repair").messages(error="cost $5 {x}", marked="[]", ids="[]")[0]["content"]
    assert "cost $5 {x}" in text


@pytest.mark.parametrize(
    ("source", "fragment"),
    [
        ("=== user ===\nhi\n", "version"),
        ("# version: t/1\n=== robot ===\nhi\n", "unknown role"),
        ("# version: t/1\nhello\n=== user ===\nhi\n", "before the first"),
        ("# version: t/1\n=== user ===\n\n", "empty"),
        ("# version: t/1\n=== user ===\ncosts 5$\n", "dollar"),
    ],
)
def test_malformed_templates_are_refused(source: str, fragment: str) -> None:
    with pytest.raises(LLMError, match=fragment):
        parse_template("t", source)


def test_environment_is_the_hierarchy_with_connections() -> None:
    text = environment_text(demo_building())
    assert "unique ID" in text
    assert "room_8: staircase. Connects to: room_2, room_9 (floor 1)." in text
    assert "object_21 (sink)" in text
