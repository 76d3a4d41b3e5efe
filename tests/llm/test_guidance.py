"""Guidance generation against a real chat-completions server: prompts, XML replies, validation,
batch/lazy."""

from __future__ import annotations

import re
import threading
import time
from dataclasses import replace
from pathlib import Path

import pytest
import yaml

from sgplan.errors import LLMError
from sgplan.llm.guidance import (
    IMPLAUSIBLE_LABEL_COST,
    LLMGuide,
    generate_guidance,
    label_costs,
    parse_commands,
    remaining_text,
    route_break,
    validate_call,
)
from sgplan.llm.records import RunRecord
from sgplan.mission import compile_mission, read_guidance, write_guidance
from sgplan.scene.demo import demo_building

from .fake_openai_server import RecordedRequest, Step, error_body

# demo: room_2 corridor (floor 0) connects to 4, 5, 6, 7, 8; room_4 kitchen holds object_19 (bowl);
# room_5 bathroom; room_7 dining room. Mission: bathroom, then dining room, never the kitchen.
FORMULA = (
    "['AND', 'EVENTUALLY', 'AND', 'enter(room_5)', 'EVENTUALLY', 'enter(room_7)', "
    "'ALWAYS', 'NOT', 'enter(room_4)']"
)
ROOM = re.compile(r"You are in room_(\d+)\.")


@pytest.fixture(scope="module")
def demo():
    return demo_building()


@pytest.fixture(scope="module")
def mission():
    return compile_mission(FORMULA)


def room_of(request: RecordedRequest) -> int:
    return int(ROOM.search(request.last_user_message).group(1))


def mixed_reply(demo):
    """Per room: reach of the bowl (valid only in room_4), one move to an object (dropped), one valid move."""

    def answer(request: RecordedRequest) -> str:
        room = demo.room(uuid=room_of(request))
        return (f"<command>reach({room.uuid}, 19)</command>\n"
                f"<command>move(room_{room.uuid}, object_21)</command>\n"
                f"<command>move(room_{room.uuid}, room_{room.connected_room_uuids[0]})</command>")

    return answer


def test_remaining_mission_keeps_order_and_only_real_avoidances(mission) -> None:
    a = mission.automaton
    texts = {q: remaining_text(a, q) for q in range(a.num_states)}
    assert texts[a.initial] == "1. enter room_5; 2. enter room_7. Throughout: never enter room_4."
    after_bathroom = a.step(a.initial, a.label_of({"enter(room_5)"}))
    # room_5 is not "to avoid" once visited, although it is false whenever the robot is in room_7
    assert texts[after_bathroom] == "1. enter room_7. Throughout: never enter room_4."
    sink = a.step(a.initial, a.label_of({"enter(room_4)"}))
    accepting = int(a.accepting.nonzero()[0][0])
    assert texts[sink] is None and texts[accepting] is None


def test_remaining_mission_over_p_names_uses_the_actions(mission) -> None:
    renamed = replace(mission.automaton, aps=("p1", "p2", "p3"))
    actions = dict(zip(("p1", "p2", "p3"), mission.automaton.aps))
    assert remaining_text(renamed, 0, actions) == remaining_text(mission.automaton, 0)


@pytest.mark.parametrize(
    ("reply", "commands"),
    [
        (
            "<command>move(room_2, room_5)</command><command> reach(room_5, object_21) </command>",
            ["move(room_2, room_5)", "reach(room_5, object_21)"],
        ),
        (
            "Sure! <command>move(2, 5)</command> & then <command>reach(5, 21)</command>",
            ["move(2, 5)", "reach(5, 21)"],
        ),
        ("<response><command>move(2, 5)</command><note>hi</note></response>", ["move(2, 5)"]),
        ("I cannot help with that.", []),
    ],
    ids=["xml", "prose-with-ampersand", "other-tags", "no-commands"],
)
def test_parse_commands(reply: str, commands: list[str]) -> None:
    assert parse_commands(reply) == commands


@pytest.mark.parametrize(
    ("call", "expected"),
    [
        ("move(room_2, room_5)", "move(2, 5)"),
        ("move(2, 5)", "move(2, 5)"),
        ("reach(room_4, object_19)", "reach(4, 19)"),
        ("move(room_5, room_7)", "room_5 does not connect to room_7"),
        ("reach(room_5, object_19)", "object_19 is not in room_5"),
        ("move(room_2, object_19)", "object_19 is not a room"),
        ("reach(room_4, room_2)", "room_2 is not an object"),
        ("reach(object_19, object_19)", "object_19 is not a room"),
        ("move(room_2, room_99)", "room_99 is not a room"),
        ("fly(room_2)", "is not move(room, room) or reach(room, object)"),
    ],
)
def test_validate_call(demo, call: str, expected: str) -> None:
    canonical, reason = validate_call(call, demo)
    if re.fullmatch(r"(move|reach)\(\d+, \d+\)", expected):
        assert (canonical, reason) == (expected, "")
    else:
        assert canonical is None and expected in reason


def test_batch_guidance_validates_counts_and_skips(
    fake_llm, llm_client, demo, mission, tmp_path: Path
) -> None:
    fake_llm.respond_with(mixed_reply(demo))
    record = RunRecord(llm_client.label)
    guidance, report = generate_guidance(demo, mission.automaton, llm_client, record,
                                         mission_text="Visit room_5, then room_7; avoid room_4.")
    rooms = [r.uuid for r in demo.rooms()]
    a = mission.automaton
    asked_states = [q for q in range(a.num_states) if remaining_text(a, q) is not None]
    assert sorted(guidance) == sorted(rooms) and len(asked_states) == 2
    assert report.asked == len(rooms) * 2 == len(fake_llm.requests) and report.failed == 0
    assert report.skipped == len(rooms)  # the sink: nothing to ask, no call
    assert report.calls_kept == len(rooms) * 2 + 2 and report.calls_dropped == len(rooms) * 2 * 2 - 2
    assert guidance[2][0] == ["move(2, 4)"] and guidance[4][0] == ["reach(4, 19)", "move(4, 2)"]
    sink = a.step(a.initial, a.label_of({"enter(room_4)"}))
    assert guidance[2][sink] == []
    prompts = [r.last_user_message for r in fake_llm.requests if room_of(r) == 2]
    assert all(
        p.startswith("The whole mission is: Visit room_5, then room_7; avoid room_4.") for p in prompts
    )
    assert sum("Remaining mission: 1. enter room_5; 2. enter room_7. Throughout: never enter room_4.\n" in p
               for p in prompts) == 1
    assert {c["prompt_version"] for c in record.calls} == {"guidance/1+hierarchy/1"} and len(
        record.calls
    ) == report.asked
    assert all(c["context"].keys() == {"room", "state"} for c in record.calls)
    # llm_heuristic.yaml round trip in the authors' form
    path = write_guidance(guidance, tmp_path / "llm_heuristic.yaml")
    assert read_guidance(path) == guidance
    assert yaml.safe_load(path.read_text())[4][0] == ["reach(4, 19)", "move(4, 2)"]


def test_failed_entries_are_empty_and_counted_and_all_failing_is_an_error(
    fake_llm, llm_client, demo, mission
) -> None:
    def answer(request: RecordedRequest):
        if room_of(request) == 2:
            return Step(status=500, body=__import__("json").dumps(error_body("boom")).encode())
        return "<command>move(room_5, room_2)</command>"

    fake_llm.respond_with(answer)
    guidance, report = generate_guidance(demo, mission.automaton, llm_client, RunRecord("x"))
    assert report.failed == 2 and guidance[2][0] == [] and guidance[5][0] == ["move(5, 2)"]
    assert any("HTTP 500" in r for r in report.reasons)
    fake_llm.respond_with(lambda request: Step(status=500, body=b"{}"))
    with pytest.raises(LLMError, match="all 22 guidance calls failed"):
        generate_guidance(demo, mission.automaton, llm_client, RunRecord("x"))


def test_batch_respects_the_concurrency_limit(fake_llm, llm_client, demo, mission) -> None:
    lock, state = threading.Lock(), {"now": 0, "max": 0}

    def answer(request: RecordedRequest) -> str:
        with lock:
            state["now"] += 1
            state["max"] = max(state["max"], state["now"])
        time.sleep(0.02)
        with lock:
            state["now"] -= 1
        return "<command>move(room_2, room_5)</command>"

    fake_llm.respond_with(answer)
    generate_guidance(demo, mission.automaton, llm_client, RunRecord("x"), max_concurrency=3)
    assert 2 <= state["max"] <= 3


def test_llm_guide_has_the_offline_guides_contract(fake_llm, llm_client, demo, mission) -> None:
    from sgplan.llm.offline import SymbolicGuide

    fake_llm.respond_with(mixed_reply(demo))
    guide = LLMGuide(llm_client, max_concurrency=2)
    ours = guide.guide(demo, mission.automaton, mission.descriptions)
    theirs = SymbolicGuide().guide(demo, mission.automaton, mission.descriptions)
    assert ours.keys() == theirs.keys() and guide.report.asked == 22 and guide.name == "llm:fake-model"


@pytest.mark.gibson
def test_authors_gpt4_guidance_replayed_through_the_pipeline(fake_llm, llm_client, gibson_root: Path) -> None:
    """Benevolence mission 1: the shipped GPT-4 calls are served back; the validator drops the bad ones."""
    from sgplan.formats import load_scene
    from sgplan.mission import load_mission_folder

    building = load_scene(gibson_root / "Benevolence")
    folder = gibson_root / "Benevolence" / "missions" / "1"
    mission = load_mission_folder(folder, profile="authors", guidance=False)
    shipped = yaml.safe_load((folder / "llm_heuristic.yaml").read_text())
    a, actions = mission.automaton, mission.descriptions
    by_text = {}
    costs = label_costs(a, building, actions)
    for q in range(a.num_states):
        by_text.setdefault(remaining_text(a, q, actions, costs), q)

    def answer(request: RecordedRequest) -> str:
        remaining = request.last_user_message.split("Remaining mission: ")[1].split("\nGive")[0]
        calls = shipped[room_of(request)][by_text[remaining]] or []
        return "\n".join(f"<command>{c}</command>" for c in calls) or "No calls are needed."

    fake_llm.respond_with(answer)
    guidance, report = generate_guidance(building, a, llm_client, RunRecord("x"), ap_actions=actions,
                                         max_concurrency=4)
    assert report.failed == 0 and report.asked == len(fake_llm.requests) > 0
    kept = [c for states in guidance.values() for calls in states.values() for c in calls]
    assert len(kept) == report.calls_kept and report.calls_dropped > 0
    assert all(validate_call(c, building)[0] == c for c in kept)


def test_route_breaks_are_found() -> None:
    assert route_break(["move(2, 4)", "reach(4, 19)", "move(4, 6)"], 2) == ""
    assert route_break([], 2) == ""
    assert "move(5, 6) starts in room_5, not in where move(2, 4) ended (room_4)" in route_break(
        ["move(2, 4)", "move(5, 6)", "move(6, 7)"], 2)
    assert "not in the current room (room_2)" in route_break(["reach(4, 19)"], 2)


def test_a_broken_route_is_counted_and_kept(fake_llm, llm_client, demo, mission) -> None:
    step = demo.room(uuid=2).connected_room_uuids[0]
    elsewhere = next(r.uuid for r in demo.rooms() if r.uuid not in (2, step) and r.connected_room_uuids)
    other = demo.room(uuid=elsewhere).connected_room_uuids[0]
    reply = f"<command>move(2, {step})</command><command>move({elsewhere}, {other})</command>"
    fake_llm.respond_with(lambda request: reply)
    guidance, report = generate_guidance(demo, mission.automaton, llm_client, RunRecord("x"))
    assert guidance[2][mission.automaton.initial] == [f"move(2, {step})", f"move({elsewhere}, {other})"]
    assert report.calls_dropped == 0 and report.calls_kept == 2 * report.asked
    assert report.routes_broken == report.asked  # from every room, one of the two calls is off the route
    assert any("route broken (calls kept)" in r for r in report.reasons)


def test_the_remaining_mission_avoids_labels_the_scene_makes_implausible(demo) -> None:
    a = compile_mission('F "enter(room_5)" & F "enter(room_7)" & F "reach(object_32)"').automaton
    assert demo.object(uuid=32).room_uuid not in (5, 7)
    costs = label_costs(a, demo)
    assert "enter room_7 and reach object_32" in remaining_text(
        a, a.initial
    )  # one letter, impossible at one cell
    assert (
        remaining_text(a, a.initial, weights=costs) == "1. reach object_32; 2. enter room_7; 3. enter room_5."
    )
    both = a.label_of({"enter(room_5)", "enter(room_7)"})
    assert (
        costs[both] == IMPLAUSIBLE_LABEL_COST
        and costs[a.label_of({"reach(object_32)", "enter(room_7)"})] == IMPLAUSIBLE_LABEL_COST
    )
    assert costs[a.label_of({"reach(object_32)"})] == costs[a.label_of({"enter(room_7)"})] == 1.0
