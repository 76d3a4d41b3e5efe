"""``sgplan eval-translation`` and :mod:`sgplan.llm.evaluate`: scoring a backend on a JSONL set, offline
and against the scripted OpenAI-compatible server (record, then replay without it)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from sgplan.cli import main
from sgplan.errors import AutomatonError, MissionError
from sgplan.llm.evaluate import load_jsonl_set, score_translator
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.evaluation import expand_shorthand, same_language
from sgplan.logic import parse_infix
from sgplan.scene.demo import demo_building

from .fake_openai_server import RecordedRequest

# demo building: room_4 kitchen (object_19 bowl), room_5 / room_14 bathrooms, room_6 living room,
# room_11 bedroom with the teddy bear.
MISSIONS = [
    {"id": "kitchen", "scene": "demo", "text": "Go to the kitchen, then the living room.",
     "formula": 'F("enter(room_4)" & F "enter(room_6)")'},
    {"id": "bowl", "scene": "demo", "text": "Take the bowl in the kitchen.", "formula": "F o19"},
    {"id": "bathroom", "scene": "demo", "text": "Visit the bathroom.", "formula": "F(r5 | r14)"},
    {"id": "garage", "scene": "demo", "text": "Visit the garage.", "formula": None, "expect_error": "garage"},
    {"id": "either", "scene": "demo", "text": "Visit the kitchen and the living room.",
     "formula": "F(r4 | r6)", "note": "a deliberately wrong gold: the backend must be scored wrong"},
]


def write_set(path: Path, missions: list[dict]) -> Path:
    path.write_text(
        "# a comment line\n" + "\n".join(json.dumps(m) for m in missions) + "\n\n", encoding="utf-8"
    )
    return path


@pytest.fixture
def mission_set(tmp_path: Path) -> Path:
    return write_set(tmp_path / "set.jsonl", MISSIONS)


def test_scene_facts_make_an_object_imply_its_room():
    demo = demo_building()
    got, gold = parse_infix(expand_shorthand("F(o19 & r4)")), parse_infix(expand_shorthand("F o19"))
    assert same_language(got, gold, demo) == (True, "")
    assert not same_language(got, gold)[0]  # without the scene the room is an independent proposition
    # one room at a time: a local "not in the kitchen" while in the bedroom says nothing, a global one does
    local, scoped = (
        parse_infix(expand_shorthand("F(r11 & !r4)")),
        parse_infix(expand_shorthand("F r11 & G !r4")),
    )
    assert same_language(local, parse_infix(expand_shorthand("F r11")), demo)[0]
    same, why = same_language(local, scoped, demo)
    assert not same and why == "they differ on {enter(room_4)} {enter(room_11)}"


def test_missions_over_many_rooms_are_compared_over_the_possible_letters():
    """Staying out of 22 rooms while visiting two (24 propositions): the dense automaton would be too large
    to build, yet the comparison is made, over the letters a robot can produce (one room at a time)."""
    others = " | ".join(f"r{i}" for i in range(10, 32))
    ordered = parse_infix(expand_shorthand(f"F(r1 & F r2) & G !({others})"))
    next_ordered = parse_infix(expand_shorthand(f"F(r1 & X F r2) & G !({others})"))
    either = parse_infix(expand_shorthand(f"F r1 & F r2 & G !({others})"))
    assert same_language(ordered, next_ordered) == (True, "")
    assert same_language(ordered, either) == (False, "they differ on {enter(room_2)} {enter(room_1)}")
    with pytest.raises(AutomatonError, match="25 propositions, more than the 24 compared"):
        same_language(ordered, parse_infix(expand_shorthand(f"F r1 & F r2 & F r3 & G !({others})")))


def test_offline_score_counts_and_explains_the_wrong_ones(mission_set: Path):
    demo = demo_building()
    score = score_translator(PatternTranslator(), load_jsonl_set(mission_set), lambda scene: demo,
                             explain=lambda f, b: f"<{len(str(f))} chars>")
    outcome = {r.mission.id: r.outcome for r in score.results}
    assert outcome == {"kitchen": "right", "bowl": "right", "bathroom": "refused", "garage": "right",
                       "either": "wrong"}
    assert score.counts == {"right": 3, "wrong": 1, "refused": 1}
    assert set(score.explanations) == {"either"}
    report = score.to_dict()
    assert report["counts"] == {"right": 3, "wrong": 1, "refused": 1} and report["total"] == 5
    wrong = next(m for m in report["missions"] if m["id"] == "either")
    assert wrong["translation"] == 'F "enter(room_4)" & F "enter(room_6)"' and wrong[
        "gold_explanation"
    ].startswith("<")


def test_cli_offline_prints_refused_and_wrong_side_by_side(mission_set: Path, tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]):
    report = tmp_path / "report.json"
    assert (
        main(["eval-translation", "--set", str(mission_set), "--llm", "offline", "--json", str(report)]) == 1
    )
    out = capsys.readouterr().out
    assert "[refused] bathroom (demo): Visit the bathroom.\n    'the bathroom' matches 2 rooms" in out
    block = out[out.index("[wrong] either"):]
    expected = block[block.index("\n    expected: "):block.index("\n    got:      ")]
    got = block[block.index("\n    got:      "):block.index("\n    they differ on {enter(room_4)}")]
    # plain words from sgplan.explain, one under the other: a choice against two goals
    assert "kitchen (room_4, floor 0) or the living room (room_6, floor 0)" in expected
    assert " or " not in got and "kitchen (room_4, floor 0)" in got and "living room (room_6, floor 0)" in got
    assert "[right]" not in out and out.strip().endswith(
        "right 3/5 (60.0%), wrong 1, refused 1  [offline-pattern]"
    )
    assert json.loads(report.read_text())["counts"]["wrong"] == 1
    # without the wrong gold, nothing is wrong: exit status 0
    clean = write_set(tmp_path / "clean.jsonl", MISSIONS[:4])
    assert main(["eval-translation", "--set", str(clean), "--llm", "offline", "--show-right"]) == 0
    assert "[right] kitchen" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("line", "fragment"),
    [
        ("{not json", "line 2: not JSON"),
        (
            json.dumps({"id": "x", "scene": "demo", "text": "t"}),
            "line 2: expected an object with id, scene, text and formula",
        ),
        (
            json.dumps({"id": "x", "scene": "demo", "text": "t", "formula": "F ("}),
            "mission 'x'): the gold formula does not parse",
        ),
        (
            json.dumps({"id": "x", "scene": "demo", "text": "Visit the kitchen.", "formula": "F r99"}),
            "mission 'x': the gold formula: proposition 'enter(room_99)' names no room or object of the "
            "scene",
        ),
        (
            json.dumps({"id": "kitchen", "scene": "demo", "text": "t", "formula": "F r4"}),
            "the id 'kitchen' is used twice",
        ),
        (json.dumps({"id": "x", "scene": "nowhere", "text": "t", "formula": "F r4"}), "scene 'nowhere'"),
    ],
)
def test_bad_sets_are_one_line_errors(
    tmp_path: Path, line: str, fragment: str, capsys: pytest.CaptureFixture[str]
):
    path = tmp_path / "bad.jsonl"
    path.write_text(json.dumps(MISSIONS[0]) + "\n" + line + "\n", encoding="utf-8")
    assert main(["eval-translation", "--set", str(path), "--llm", "offline"]) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith("sgplan: error:") and fragment in err


def test_empty_or_missing_set_is_an_error(tmp_path: Path):
    (tmp_path / "empty.jsonl").write_text("\n# nothing\n")
    with pytest.raises(MissionError, match="holds no mission"):
        load_jsonl_set(tmp_path / "empty.jsonl")
    with pytest.raises(MissionError, match="cannot read the mission set"):
        load_jsonl_set(tmp_path / "absent.jsonl")


# A scripted model: grounds "the kitchen" as the bathroom room_5 (the misreading of issue 11), refuses
# "the bathroom" as ambiguous, and translates whatever grounded text it wrote.
GROUNDINGS = {
    "Go to the kitchen, then the living room.": ("Go to room_5, then room_6.", []),
    "Take the bowl in the kitchen.": ("Take object_19 in room_4.", []),
    "Visit the bathroom.": (
        "Visit the bathroom.",
        [{"phrase": "the bathroom", "kind": "ambiguous", "candidates": ["room_5", "room_14"]}],
    ),
}
TOKENS = {
    "Go to room_5, then room_6.": "['EVENTUALLY', 'AND', 'enter(room_5)', 'EVENTUALLY', 'enter(room_6)']",
    "Take object_19 in room_4.": "['EVENTUALLY', 'AND', 'reach(object_19)', 'enter(room_4)']",
}


def scripted_model(request: RecordedRequest) -> str:
    system, user = request.messages[0]["content"], request.last_user_message
    if system.startswith("You rewrite a robot's mission"):
        text = next(t for t in GROUNDINGS if t in user)
        grounded, problems = GROUNDINGS[text]
        return json.dumps({"grounded": grounded, "problems": problems})
    return next(tokens for grounded, tokens in TOKENS.items() if grounded in user)


def test_against_the_fake_openai_server_then_replayed(
    fake_llm, tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
):
    for name in ("OPENAI_BASE_URL", "SGPLAN_LLM_CONFIG", "OPENAI_API_KEY", "SGPLAN_LLM_API_KEY"):
        monkeypatch.delenv(name, raising=False)
    config = tmp_path / "llm.yaml"
    config.write_text(yaml.safe_dump({"timeout_s": 2.0, "max_retries": 1, "backoff_base_s": 0.001,
                                      "backoff_max_s": 0.01}))
    mission_set = write_set(tmp_path / "set.jsonl", MISSIONS[:3])
    fake_llm.respond_with(scripted_model)
    cache = tmp_path / "cache"
    argv = [
        "eval-translation", "--set", str(mission_set), "--llm", "openai:fake-model", "--cache", str(cache),
    ]
    assert main([*argv, "--base-url", fake_llm.base_url, "--llm-config", str(config)]) == 1
    printed = capsys.readouterr()
    assert "[wrong] kitchen (demo)" in printed.out and "room_5" in printed.out
    assert "[refused] bathroom" in printed.out and "right 1/3 (33.3%), wrong 1, refused 1" in printed.out
    assert "5 LLM calls (0 from the cache)" in printed.err  # 2 + 2 + 1 (grounding refused)
    fake_llm.respond_with(None)  # any request now fails the test
    report = tmp_path / "replayed.json"
    assert main([*argv, "--replay", "--json", str(report)]) == 1
    assert "5 LLM calls (5 from the cache)" in capsys.readouterr().err
    data = json.loads(report.read_text())
    assert data["counts"] == {"right": 1, "wrong": 1, "refused": 1} and data["backend"].startswith("llm")
    assert len(fake_llm.requests) == 5


def test_start_floor_reaches_the_offline_translator(tmp_path: Path):
    missions = [
        {
            "id": "up", "scene": "demo", "text": "Go to the bathroom downstairs.", "formula": "F r5",
            "start_floor": 1,
        },
        {
            "id": "here", "scene": "demo", "text": "Go to the bathroom on this floor.", "formula": "F r14",
            "start_floor": 1,
        },
        {"id": "unknown", "scene": "demo", "text": "Go to the bathroom on this floor.", "formula": "F r14"},
    ]
    demo = demo_building()
    score = score_translator(PatternTranslator(), load_jsonl_set(write_set(tmp_path / "s.jsonl", missions)),
                             lambda scene: demo)
    assert [r.outcome for r in score.results] == ["right", "right", "refused"]
    bad = write_set(tmp_path / "bad.jsonl", [{**missions[0], "start_floor": "one"}])
    with pytest.raises(MissionError, match="start_floor must be a floor number"):
        load_jsonl_set(bad)
