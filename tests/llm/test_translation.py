"""The translation pipeline against a real chat-completions server on 127.0.0.1 with scripted replies.

Demo building: room_4 kitchen, room_5 bathroom (floor 0, object_21 sink), room_7 dining room (object_28,
object_29 chairs), room_14 bathroom (floor 1). Each test scripts the grounding reply, then the translation
(and repair) replies, and checks that only a correct formula is ever accepted.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import pytest

from sgplan.errors import LLMError, MissionError
from sgplan.llm.cache import CachedChatBackend
from sgplan.llm.client import OpenAIChatClient
from sgplan.llm.config import LLMConfig
from sgplan.llm.grounding import RephraseError
from sgplan.llm.offline.evaluation import expand_shorthand, same_language
from sgplan.llm.records import RECORD_FORMAT, RunRecord
from sgplan.llm.translation import (
    LLMTranslator,
    check_formula,
    mark_token,
    reply_token_list,
    translate_to_folder,
)
from sgplan.logic import equivalent, parse_infix
from sgplan.mission import load_mission_folder
from sgplan.scene.demo import demo_building

TEXT = "Visit the bathroom on floor 0, then sit on a chair in the dining room. Always avoid the kitchen."
GROUNDED = "Visit room_5, then sit on object_28 or object_29 in room_7. Always avoid room_4."
GROUNDING_REPLY = json.dumps({"grounded": GROUNDED, "problems": []})
GOOD = ("['AND', 'EVENTUALLY', 'AND', 'enter(room_5)', 'EVENTUALLY', 'AND', 'OR', 'reach(object_28)', "
        "'reach(object_29)', 'enter(room_7)', 'ALWAYS', 'NOT', 'enter(room_4)']")
GOLD = "F(r5 & F((o28 | o29) & r7)) & G !r4"


@pytest.fixture(scope="module")
def demo():
    return demo_building()


def assert_gold(formula, gold: str = GOLD) -> None:
    same, why = same_language(formula, parse_infix(expand_shorthand(gold)))
    assert same, why


def calls_of(record: RunRecord) -> list[str]:
    return [c["step"] for c in record.calls]


def test_correct_replies_give_the_formula_and_a_complete_folder(
    fake_llm, llm_client, demo, tmp_path: Path
) -> None:
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply(f"Here is the list:\n```python\n{GOOD}\n```")
    record = RunRecord(llm_client.label)
    translation, mission = translate_to_folder(
        TEXT, demo, LLMTranslator(llm_client, record=record), tmp_path, record
    )
    assert_gold(translation.formula)
    assert translation.grounded_text == GROUNDED and translation.ids == (
        "room_5", "object_28", "object_29", "room_7", "room_4",
    )
    assert translation.repairs == 0 and translation.votes == (1,)
    # what the model was told: the hierarchy with connections, then the grounded text and its IDs
    first, second = fake_llm.requests
    assert "room_8: staircase. Connects to: room_2, room_9 (floor 1)." in first.last_user_message
    assert (
        second.last_user_message
        == f"IDs in the mission: [room_5, object_28, object_29, room_7, room_4]\nMission: {GROUNDED}"
    )
    assert first.json["temperature"] == 0.0
    # the folder: authors' layout + env_elements + the run record; it loads back to the same language
    names = {p.name for p in tmp_path.iterdir()}
    assert {"NL_instructions.txt", "NL_instructions_uuid.txt", "GPT_LTL_formula.txt", "Spot_LTL_formula.txt",
            "ap_dict.txt", "ap_desc.yaml", "automaton.aut", "building_desc.yaml", "env_elements.txt",
            "llm_record.json"} <= names
    assert (tmp_path / "env_elements.txt").read_text() == "[room_5, object_28, object_29, room_7, room_4]\n"
    loaded = load_mission_folder(tmp_path)
    assert loaded.text == TEXT and loaded.grounded_text == GROUNDED
    by_action = replace(loaded.automaton, aps=tuple(loaded.descriptions[ap] for ap in loaded.automaton.aps))
    assert equivalent(by_action, mission.automaton)
    saved = json.loads((tmp_path / "llm_record.json").read_text())
    assert saved["format"] == RECORD_FORMAT and saved["summary"]["calls"] == 2
    assert [c["prompt_version"] for c in saved["calls"]] == ["grounding/1+hierarchy/1", "translation/1"]
    assert (
        saved["calls"][1]["reply"].startswith("Here is the list") and saved["calls"][1]["from_cache"] is False
    )
    assert saved["calls"][0]["latency_s"] > 0 and saved["calls"][0]["error"] is None
    assert [e["kind"] for e in saved["events"]] == ["grounded", "formula-accepted", "saved", "explained"]
    assert "the kitchen (room_4, floor 0)" in saved["events"][-1]["text"]
    assert {"scene.yaml"} <= names


def test_a_syntax_error_is_repaired_with_the_precise_error(fake_llm, llm_client, demo) -> None:
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply("['AND', 'EVENTUALLY', 'enter(room_5)']")  # AND short of an operand
    fake_llm.push_reply("['EVENTUALY', 'enter(room_5)']")  # misspelt operator
    fake_llm.push_reply(GOOD)
    translator = LLMTranslator(llm_client)
    translation = translator.translate(TEXT, demo)
    assert_gold(translation.formula)
    assert translation.repairs == 2 and calls_of(translator.record) == [
        "grounding", "translation", "repair", "repair",
    ]
    repair = fake_llm.requests[2]
    assert "token 0 'AND' needs 2 operands" in repair.last_user_message
    assert "['AND'  <-- here, 'EVENTUALLY', 'enter(room_5)']" in repair.last_user_message
    # the repair continues the conversation: the bad reply is the assistant's last turn
    assert repair.messages[-2] == {"role": "assistant", "content": "['AND', 'EVENTUALLY', 'enter(room_5)']"}
    assert "token 0 'EVENTUALY' is not an operator" in fake_llm.requests[3].last_user_message
    assert translator.record.calls[2]["prompt_version"] == "repair/1"


def test_hopeless_replies_end_with_a_request_to_rephrase(fake_llm, llm_client, demo, tmp_path: Path) -> None:
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply("I think the robot should go to the bathroom.", times=3)
    record = RunRecord(llm_client.label)
    with pytest.raises(RephraseError, match=r"no valid formula .* in 3 attempts .* rephrase the mission"):
        translate_to_folder(
            TEXT, demo, LLMTranslator(llm_client, record=record, max_repairs=2), tmp_path, record
        )
    assert len(fake_llm.requests) == 4
    assert sorted(p.name for p in tmp_path.iterdir()) == ["llm_refused_record.json"]  # no half-made mission
    assert json.loads((tmp_path / "llm_refused_record.json").read_text())["events"][-1]["kind"] == "refused"


@pytest.mark.parametrize(
    ("bad", "fragment"),
    [
        ("['EVENTUALLY', 'enter(room_99)']", "names room_99, which is not a known room or object id"),
        # room_14 exists, but the grounded mission does not mention it: an invented reference too
        ("['EVENTUALLY', 'enter(room_14)']", "names room_14, which is not a known"),
        ("['EVENTUALLY', 'enter(object_21)']", "malformed"),
        (
            "['AND', 'EVENTUALLY', 'enter(room_5)', 'ALWAYS', 'NOT', 'enter(room_5)']",
            "can never be satisfied",
        ),
        # tautologies ask nothing of the robot; the second one only because rooms are mutually exclusive
        (
            "['OR', 'EVENTUALLY', 'enter(room_5)', 'NOT', 'EVENTUALLY', 'enter(room_5)']",
            "satisfied by every path",
        ),
        ("['ALWAYS', 'NOT', 'AND', 'enter(room_5)', 'enter(room_4)']", "asks nothing of the robot"),
    ],
)
def test_invented_ids_and_impossible_formulas_are_repaired_then_refused(
    fake_llm, llm_client, demo, bad, fragment
) -> None:
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply(bad)
    fake_llm.push_reply(GOOD)
    assert_gold(LLMTranslator(llm_client).translate(TEXT, demo).formula)
    assert fragment in fake_llm.requests[2].last_user_message
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply(bad, times=2)
    with pytest.raises(RephraseError, match=fragment):
        LLMTranslator(llm_client, max_repairs=1).translate(TEXT, demo)


def test_a_formula_whose_automaton_is_too_large_is_repaired(fake_llm, llm_client, demo) -> None:
    objects = [f"object_{n}" for n in range(15, 35)]  # 20 propositions: 2**20 labels exceed the table limit
    fake_llm.push_reply(json.dumps({"grounded": f"Reach {', '.join(objects)} in any order.", "problems": []}))
    fake_llm.push_reply(repr(conjunction_of_goals(objects)))
    fake_llm.push_reply("['EVENTUALLY', 'reach(object_15)']")
    translation = LLMTranslator(llm_client).translate("Reach 20 objects.", demo)
    assert translation.repairs == 1 and translation.tokens == ("EVENTUALLY", "reach(object_15)")
    assert "table entries, more than max_entries" in fake_llm.requests[2].last_user_message


def conjunction_of_goals(objects: list[str]) -> list[str]:
    """Prefix tokens of ``F reach(o1) & F reach(o2) & ...``."""
    tokens: list[str] = []
    for key in objects[:-1]:
        tokens += ["AND", "EVENTUALLY", f"reach({key})"]
    return [*tokens, "EVENTUALLY", f"reach({objects[-1]})"]


def test_ambiguous_references_are_never_guessed(fake_llm, llm_client, demo) -> None:
    fake_llm.push_reply(json.dumps({"grounded": "Visit the bathroom.", "problems": [
        {"phrase": "the bathroom", "kind": "ambiguous", "candidates": ["room_5", "room_14"]}]}))
    with pytest.raises(RephraseError) as info:
        LLMTranslator(llm_client).translate("Visit the bathroom.", demo)
    assert isinstance(info.value, MissionError)
    assert "room_5 (bathroom, floor 0), room_14 (bathroom, floor 1)" in str(info.value)
    assert info.value.problems[0].phrase == "the bathroom"
    assert len(fake_llm.requests) == 1  # no translation of an unresolved mission


def test_grounding_replies_with_invented_ids_or_no_json_are_sent_back(fake_llm, llm_client, demo) -> None:
    fake_llm.push_reply(json.dumps({"grounded": "Visit room_55.", "problems": []}))
    fake_llm.push_reply("Visit room_5.")
    fake_llm.push_reply(json.dumps({"grounded": "Visit room_5.", "problems": []}))
    fake_llm.push_reply("['EVENTUALLY', 'enter(room_5)']")
    translation = LLMTranslator(llm_client).translate("Visit the bathroom on floor 0.", demo)
    assert_gold(translation.formula, "F r5")
    assert "room_55 is not an ID of this building" in fake_llm.requests[1].last_user_message
    assert "contains no JSON object" in fake_llm.requests[2].last_user_message


def test_a_mission_naming_nothing_is_refused(fake_llm, llm_client, demo) -> None:
    fake_llm.push_reply(json.dumps({"grounded": "Dance.", "problems": []}))
    with pytest.raises(RephraseError, match="names no room or object"):
        LLMTranslator(llm_client).translate("Dance.", demo)


def test_warnings_are_kept_for_next_and_first_cell_constraints(fake_llm, llm_client, demo) -> None:
    fake_llm.push_reply(
        json.dumps({"grounded": "Start in room_5 and step into room_2 next.", "problems": []})
    )
    fake_llm.push_reply("['AND', 'enter(room_5)', 'NEXT', 'enter(room_2)']")
    translation = LLMTranslator(llm_client).translate(
        "Start in the bathroom on floor 0, then the corridor.", demo
    )
    text = " ".join(translation.warnings)
    assert "only constrains the first cell" in text and "X (NEXT)" in text


def test_majority_vote_groups_by_automaton_equivalence(fake_llm, llm_client, demo) -> None:
    swapped = (
        "['AND', 'ALWAYS', 'NOT', 'enter(room_4)', 'EVENTUALLY', 'AND', 'enter(room_5)', 'EVENTUALLY', "
        "'AND', 'enter(room_7)', 'OR', 'reach(object_29)', 'reach(object_28)']"
    )
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply("['EVENTUALLY', 'enter(room_5)']")  # a different reading
    fake_llm.push_reply(GOOD)
    fake_llm.push_reply(swapped)  # the same language as GOOD, written differently
    translator = LLMTranslator(llm_client, samples=3)
    translation = translator.translate(TEXT, demo)
    assert_gold(translation.formula)
    assert translation.votes == (2, 1)
    seeds = [r.json.get("seed") for r in fake_llm.requests]
    temperatures = [r.json.get("temperature") for r in fake_llm.requests]
    assert seeds == [None, 0, 1, 2] and temperatures == [0.0, 0.7, 0.7, 0.7]
    assert translator.record.events[-1]["kind"] == "vote"


def test_a_tied_vote_is_refused(fake_llm, llm_client, demo) -> None:
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply("['EVENTUALLY', 'enter(room_5)']")
    fake_llm.push_reply(GOOD)
    with pytest.raises(RephraseError, match="no majority"):
        LLMTranslator(llm_client, samples=2).translate(TEXT, demo)


def test_failed_samples_count_against_the_majority(fake_llm, llm_client, demo) -> None:
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply(GOOD)
    fake_llm.push_reply("no list", times=2)  # two samples fail (no repairs allowed)
    with pytest.raises(RephraseError, match=r"the 3 translations have no majority \(.* \(1x\); 2 failed\)"):
        LLMTranslator(llm_client, samples=3, max_repairs=0).translate(TEXT, demo)
    # two agreeing samples of three are a majority even when the third fails
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply(GOOD, times=2)
    fake_llm.push_reply("no list")
    translation = LLMTranslator(llm_client, samples=3, max_repairs=0).translate(TEXT, demo)
    assert_gold(translation.formula)
    assert translation.votes == (2,)


def fast_client(fake_llm, **overrides) -> OpenAIChatClient:
    settings = dict(model="fake-model", base_url=fake_llm.base_url, api_key="k", timeout_s=0.3, max_retries=1,
                    backoff_base_s=0.001, backoff_max_s=0.01)
    settings.update(overrides)
    return OpenAIChatClient(LLMConfig(**settings))


def test_transient_failures_are_retried_and_recorded(fake_llm, demo) -> None:
    fake_llm.push_delay(1.0)  # timeout, then success
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_status(429)  # rate limited, then success
    fake_llm.push_reply(GOOD)
    with fast_client(fake_llm) as client:
        translator = LLMTranslator(client)
        assert_gold(translator.translate(TEXT, demo).formula)
    assert [c["attempts"] for c in translator.record.calls] == [2, 2]


@pytest.mark.parametrize(
    ("script", "fragment"),
    [
        (lambda s: s.push_status(500, times=2), "HTTP 500"),
        (lambda s: s.push_delay(1.0) or s.push_delay(1.0), "timeout"),
        (lambda s: s.push_truncated_json(), "not valid JSON"),
        (lambda s: s.push_reply(""), "empty content"),
    ],
    ids=["500s", "timeouts", "truncated-json", "empty-content"],
)
def test_server_failures_end_in_one_llm_error_and_no_cache_entry(
    fake_llm, demo, tmp_path: Path, script, fragment
) -> None:
    script(fake_llm)
    with fast_client(fake_llm) as client:
        backend = CachedChatBackend(tmp_path / "cache", mode="record", inner=client)
        record = RunRecord(backend.label)
        with pytest.raises(LLMError, match=fragment) as info:
            translate_to_folder(
                TEXT, demo, LLMTranslator(backend, record=record), tmp_path / "mission", record
            )
    assert "\n" not in str(info.value)
    assert not (tmp_path / "cache").exists() or not list((tmp_path / "cache").iterdir())
    assert sorted(p.name for p in (tmp_path / "mission").iterdir()) == ["llm_refused_record.json"]
    assert record.calls[0]["error"] and record.calls[0]["reply"] is None


def test_record_then_replay_offline_gives_the_same_mission(
    fake_llm, llm_client, demo, tmp_path: Path
) -> None:
    cache = tmp_path / "cache"
    fake_llm.push_reply(GROUNDING_REPLY)
    fake_llm.push_reply("['AND', 'EVENTUALLY', 'enter(room_5)']")
    fake_llm.push_reply(GOOD)
    recorded = LLMTranslator(CachedChatBackend(cache, mode="record", inner=llm_client)).translate(TEXT, demo)
    assert len(list(cache.glob("*.json"))) == 3
    replayer = LLMTranslator(CachedChatBackend(cache, mode="replay", model="fake-model"))
    replayed = replayer.translate(TEXT, demo)
    assert replayed.tokens == recorded.tokens and replayed.repairs == 1
    assert len(fake_llm.requests) == 3  # nothing new was sent
    assert all(c["from_cache"] for c in replayer.record.calls)
    with pytest.raises(LLMError, match="replay: no recorded LLM call"):
        replayer.translate("Visit the kitchen.", demo)


def test_reply_parsing_helpers() -> None:
    assert reply_token_list("```\n['NOT', 'enter(room_2)']\n```") == ["NOT", "enter(room_2)"]
    assert mark_token(None, "no list here", None) == "no list here"
    assert mark_token(["AND", "x"], "", 1) == "['AND', 'x'  <-- here]"
    formula, warnings = check_formula(["EVENTUALLY", "enter(room_2)"], ("room_2", "object_3"))
    assert str(formula) == 'F "enter(room_2)"'
    assert any("object_3, which the formula does not use" in w for w in warnings)


@pytest.mark.gibson
def test_benevolence_mission_is_translated_and_checked_against_the_scene(
    fake_llm, llm_client, gibson_root, tmp_path
) -> None:
    from sgplan.formats import load_scene

    building = load_scene(gibson_root / "Benevolence")
    bathroom = next(r for r in building.rooms() if r.name == "bathroom")
    corridor = next(r for r in building.rooms() if r.name == "corridor")
    fake_llm.push_reply(
        json.dumps({"grounded": f"Go to {bathroom.key}, never entering {corridor.key}.", "problems": []})
    )
    fake_llm.push_reply(
        f"['AND', 'EVENTUALLY', 'enter({bathroom.key})', 'ALWAYS', 'NOT', 'enter({corridor.key})']"
    )
    record = RunRecord(llm_client.label)
    _, mission = translate_to_folder("Go to the bathroom, never entering the corridor.", building,
                                     LLMTranslator(llm_client, record=record), tmp_path, record)
    load_mission_folder(tmp_path).check_scene(building)
    assert mission.automaton.num_states == 3
    assert f"{bathroom.key}: bathroom." in fake_llm.requests[0].last_user_message
