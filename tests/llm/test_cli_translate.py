"""``sgplan translate`` and ``sgplan guide``: offline and against the scripted server, record then replay,
one-line errors, and the interactive request to rephrase."""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path

import pytest
import yaml

from sgplan.cli import main
from sgplan.commands import translate
from sgplan.errors import LLMError, MissionError
from sgplan.llm.records import RunRecord

from .fake_openai_server import RecordedRequest

TEXT = "Visit the bathroom on floor 0, then the dining room. Always avoid the kitchen."
GROUNDED = "Visit room_5, then room_7. Always avoid room_4."
TOKENS = (
    "['AND', 'EVENTUALLY', 'AND', 'enter(room_5)', 'EVENTUALLY', 'enter(room_7)', "
    "'ALWAYS', 'NOT', 'enter(room_4)']"
)


def demo_model(request: RecordedRequest) -> str:
    """A well-behaved model for the demo building, answering by prompt kind."""
    system = request.messages[0]["content"]
    if system.startswith("You rewrite a robot's mission"):
        return json.dumps({"grounded": GROUNDED, "problems": []})
    if system.startswith("You translate a robot's mission"):
        return TOKENS
    room = re.search(r"You are in room_(\d+)\.", request.last_user_message).group(1)
    return f"<command>move(room_{room}, room_2)</command>"  # valid only where room_2 is a neighbour


@pytest.fixture(autouse=True)
def _clean_llm_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ("OPENAI_BASE_URL", "SGPLAN_LLM_CONFIG", "OPENAI_API_KEY", "SGPLAN_LLM_API_KEY"):
        monkeypatch.delenv(name, raising=False)


@pytest.fixture
def llm_args(fake_llm, tmp_path: Path) -> list[str]:
    config = tmp_path / "llm.yaml"
    config.write_text(yaml.safe_dump({"timeout_s": 2.0, "max_retries": 1, "backoff_base_s": 0.001,
                                      "backoff_max_s": 0.01}))
    return ["--llm", "openai:fake-model", "--base-url", fake_llm.base_url, "--llm-config", str(config)]


def test_offline_translate_then_guide(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "mission"
    assert main(["translate", "--scene", "demo", "--text", TEXT, "--out", str(out)]) == 0
    printed = capsys.readouterr()
    assert f"grounded: {GROUNDED}" in printed.out and "offline-pattern" in printed.err
    assert main(["guide", "--scene", "demo", "--mission-dir", str(out)]) == 0
    guidance = yaml.safe_load((out / "llm_heuristic.yaml").read_text())
    assert set(guidance) == {2, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}
    assert "offline-symbolic" in capsys.readouterr().err


def test_llm_translate_records_then_replays_without_a_server(fake_llm, llm_args, tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    fake_llm.respond_with(demo_model)
    cache, first, second = tmp_path / "cache", tmp_path / "m1", tmp_path / "m2"
    argv = ["translate", "--scene", "demo", "--text", TEXT, *llm_args, "--cache", str(cache)]
    assert main([*argv, "--out", str(first)]) == 0
    assert "2 LLM calls (0 from the cache)" in capsys.readouterr().err
    fake_llm.respond_with(None)  # any request now fails the test
    replay = [
        "translate", "--scene", "demo", "--text", TEXT, "--llm", "openai:fake-model", "--cache", str(cache),
        "--replay", "--out", str(second),
    ]
    assert main(replay) == 0
    assert len(fake_llm.requests) == 2
    assert (first / "GPT_LTL_formula.txt").read_text() == (second / "GPT_LTL_formula.txt").read_text()
    assert (second / "automaton.aut").read_text() == (first / "automaton.aut").read_text()
    record = json.loads((second / "llm_record.json").read_text())
    assert record["summary"]["from_cache"] == 2 and "replayed from" in record["backend"]


def test_llm_guide_writes_guidance_and_its_record(fake_llm, llm_args, tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    fake_llm.respond_with(demo_model)
    out = tmp_path / "mission"
    assert main(["translate", "--scene", "demo", "--text", TEXT, *llm_args, "--out", str(out)]) == 0
    assert (
        main(["guide", "--scene", "demo", "--mission-dir", str(out), *llm_args, "--max-concurrency", "2"])
        == 0
    )
    printed = capsys.readouterr().out
    guidance = yaml.safe_load((out / "llm_heuristic.yaml").read_text())
    assert guidance[5][0] == ["move(5, 2)"] and guidance[11][0] == []  # room_11 does not connect to room_2
    assert re.search(r"LLM: 22 entries asked \(0 from the cache\), 11 with nothing left to do, 0 failed; "
                     r"calls kept 10, dropped 12", printed)
    record = json.loads((out / "llm_guidance_record.json").read_text())
    assert record["summary"]["calls"] == 22 and record["calls"][0]["step"] == "guidance"


def test_llm_guide_keeps_the_record_when_every_call_fails(fake_llm, llm_args, tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    fake_llm.respond_with(demo_model)
    out = tmp_path / "mission"
    assert main(["translate", "--scene", "demo", "--text", TEXT, *llm_args, "--out", str(out)]) == 0
    fake_llm.respond_with(lambda request: "")  # empty content: every guidance call fails
    assert main(["guide", "--scene", "demo", "--mission-dir", str(out), *llm_args]) == 2
    assert "all 22 guidance calls failed" in capsys.readouterr().err
    record = json.loads((out / "llm_guidance_record.json").read_text())
    assert record["summary"]["calls"] == 22 and not (out / "llm_heuristic.yaml").exists()
    blocked = tmp_path / "a-file"
    blocked.write_text("")
    assert (
        main(
            [
                "guide", "--scene", "demo", "--mission-dir", str(out), *llm_args, "--out",
                str(blocked / "x.yaml"),
            ]
        )
        == 2
    )
    assert "all 22 guidance calls failed" in capsys.readouterr().err  # not hidden by the unsaved record


@pytest.mark.parametrize(
    ("extra", "fragment"),
    [
        (["--text", "Visit the bathroom."], "'the bathroom' matches 2 rooms"),
        (["--text", TEXT, "--llm", "openai:m", "--replay"], "--replay needs the cache"),
        (["--text", TEXT, "--llm", "gpt4"], "unknown --llm 'gpt4'"),
        (["--text", TEXT, "--base-url", "http://127.0.0.1:1/v1"], "only apply to a language model"),
        (["--text", TEXT, "--samples", "3"], "--samples only apply to a language model"),
        (
            ["--text", TEXT, "--llm", "openai:m", "--cache", "CACHE", "--replay"],
            "replay: no recorded LLM call",
        ),
    ],
)
def test_user_errors_are_one_line_exit_2(extra: list[str], fragment: str, tmp_path: Path,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["translate", "--scene", "demo", "--out", str(tmp_path / "m"),
            *[str(tmp_path / "cache") if a == "CACHE" else a for a in extra]]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("sgplan: error:") and fragment in err[-1] and "Traceback" not in "\n".join(err)


@pytest.mark.parametrize("command", ["translate", "plan"])
@pytest.mark.parametrize("cache", ["FILE", "FILE/inside"])
def test_a_cache_that_is_a_file_is_refused_before_any_call(
    fake_llm, llm_args, command: str, cache: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "FILE").write_text("not a folder")
    argv = [command, "--scene", "demo", "--text", TEXT, *llm_args, "--cache", str(tmp_path / cache)]
    argv += ["--out", str(tmp_path / "m")] if command == "translate" else ["--start-index", "0"]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith(f"sgplan: error: LLM cache {tmp_path / cache}") and "not a folder" in err
    assert fake_llm.requests == []  # refused before the server heard of it


def test_server_errors_are_one_line_exit_2(
    fake_llm, llm_args, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    fake_llm.push_status(500, times=2)
    assert (
        main(["translate", "--scene", "demo", "--text", TEXT, *llm_args, "--out", str(tmp_path / "m")]) == 2
    )
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith("sgplan: error: LLM call to") and "failed after 2 attempts: HTTP 500" in err


def test_interactive_rephrasing_after_an_ambiguous_mission(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    parser = argparse.ArgumentParser()
    translate.register(parser.add_subparsers())
    args = parser.parse_args(["translate", "--scene", "demo", "--text", "Visit the bathroom.",
                              "--out", str(tmp_path / "m")])
    questions: list[str] = []
    answers = iter(["Visit the bathroom on floor 1."])

    def ask(question: str) -> str:
        questions.append(question)
        return next(answers)

    assert translate.run(args, ask=ask) == 0
    assert len(questions) == 1 and "Rephrase the mission" in questions[0]
    assert "matches 2 rooms" in capsys.readouterr().err
    assert (tmp_path / "m" / "NL_instructions.txt").read_text() == "Visit the bathroom on floor 1.\n"
    # giving up (an empty answer) re-raises the original error
    args.text = "Visit the bathroom."
    with pytest.raises(MissionError, match="matches 2 rooms"):
        translate.run(args, ask=lambda question: "")


def test_a_new_mission_drops_the_old_guidance_and_a_refusal_keeps_the_old_mission(
    tmp_path: Path, capsys: pytest.CaptureFixture[str],
) -> None:
    out = tmp_path / "mission"
    translate_offline = ["translate", "--scene", "demo", "--out", str(out), "--text"]
    assert main([*translate_offline, TEXT]) == 0
    assert main(["guide", "--scene", "demo", "--mission-dir", str(out)]) == 0
    (out / "llm_guidance_record.json").write_text("{}\n")
    notes = out / "notes.txt"  # not a mission file: left alone
    notes.write_text("mine\n")
    # a refusal leaves the earlier mission whole (its guidance included) and records itself beside it
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert main([*translate_offline, "Visit the bathroom."]) == 2
    assert "matches 2 rooms" in capsys.readouterr().err
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.name != "llm_refused_record.json"} == before
    assert json.loads((out / "llm_refused_record.json").read_text())["events"][-1]["kind"] == "refused"
    # a new mission drops what was made for the old one, and the old refusal
    assert main([*translate_offline, "Visit the kitchen."]) == 0
    names = {p.name for p in out.iterdir()}
    assert not names & {"llm_heuristic.yaml", "llm_guidance_record.json", "llm_refused_record.json"}
    assert {"automaton.aut", "llm_record.json", "notes.txt"} <= names
    assert (out / "NL_instructions.txt").read_text() == "Visit the kitchen.\n"


@pytest.mark.parametrize(
    ("option", "fragment"),
    [(["--samples", "0"], "'0' is not a whole number >= 1"),
     (["--max-repairs", "-1"], "'-1' is not a whole number >= 0")],
)
def test_bad_counts_are_refused_by_the_parser(llm_args, tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                              option: list[str], fragment: str) -> None:
    argv = ["translate", "--scene", "demo", "--text", TEXT, *llm_args, "--out", str(tmp_path / "m"), *option]
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 2 and fragment in capsys.readouterr().err


@pytest.mark.parametrize(
    ("out", "fragment"),
    [("file", "is a file, not a mission folder"), ("file/m", "cannot write a mission folder here")],
)
def test_an_unusable_out_folder_is_one_line_and_not_a_reason_to_rephrase(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], out: str, fragment: str,
) -> None:
    (tmp_path / "file").write_text("not a folder\n")
    argv = ["translate", "--scene", "demo", "--text", TEXT, "--out", str(tmp_path / out)]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith(f"sgplan: error: {tmp_path / out}: {fragment}")
    parser = argparse.ArgumentParser()
    translate.register(parser.add_subparsers())

    def ask(question: str) -> str:
        raise AssertionError("asked to rephrase a mission that was not the problem")

    with pytest.raises(MissionError, match=fragment):
        translate.run(parser.parse_args(argv), ask=ask)


def test_a_record_that_cannot_be_saved_does_not_hide_the_refusal(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch,
) -> None:
    def save(record: RunRecord, path: Path) -> Path:
        raise LLMError(f"{path}: cannot write the LLM run record (disk full)")

    monkeypatch.setattr(RunRecord, "save", save)
    argv = ["translate", "--scene", "demo", "--text", "Visit the bathroom.", "--out", str(tmp_path / "m")]
    assert main(argv) == 2
    assert "matches 2 rooms" in capsys.readouterr().err.strip().splitlines()[-1]


def test_closed_stdin_at_the_rephrase_prompt_gives_up_with_the_refusal(tmp_path: Path) -> None:
    parser = argparse.ArgumentParser()
    translate.register(parser.add_subparsers())
    args = parser.parse_args(["translate", "--scene", "demo", "--text", "Visit the bathroom.",
                              "--out", str(tmp_path / "m")])

    def ask(question: str) -> str:
        raise EOFError

    with pytest.raises(MissionError, match="matches 2 rooms"):
        translate.run(args, ask=ask)


def test_plan_text_offline_translates_guides_and_verifies(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    saved, result = tmp_path / "mission", tmp_path / "result.json"
    argv = [
        "plan", "--scene", "demo", "--text", TEXT, "--verify", "--save-mission", str(saved), "--json",
        str(result),
    ]
    assert main(argv) == 0
    printed = capsys.readouterr()
    assert "verified:" in printed.out and "offline-symbolic" in printed.err
    record = json.loads(result.read_text())
    assert record["status"] == "optimal" and record["verified"] is True and "llm" not in record
    # The saved folder is the same mission: planning it again gives the same optimum.
    assert (
        main(["plan", "--scene", "demo", "--mission-dir", str(saved), "--json", str(tmp_path / "again.json")])
        == 0
    )
    assert json.loads((tmp_path / "again.json").read_text())["cost_m"] == record["cost_m"]


def test_plan_text_with_a_language_model_uses_its_translation_and_guidance(
    fake_llm, llm_args, tmp_path: Path, capsys: pytest.CaptureFixture[str],
) -> None:
    fake_llm.respond_with(demo_model)
    saved, result = tmp_path / "mission", tmp_path / "result.json"
    argv = ["plan", "--scene", "demo", "--text", TEXT, *llm_args, "--verify", "--save-mission", str(saved),
            "--json", str(result)]
    assert main(argv) == 0
    record = json.loads(result.read_text())
    guidance_calls = len(fake_llm.requests) - 2
    assert guidance_calls > 0 and record["llm"]["calls"] == len(fake_llm.requests)
    assert record["status"] == "optimal" and record["verified"] is True
    assert (saved / "GPT_LTL_formula.txt").read_text().strip() == TOKENS
    guidance = yaml.safe_load((saved / "llm_heuristic.yaml").read_text())
    assert any(calls == ["move(5, 2)"] for calls in guidance.get(5, {}).values())
    guide_prompts = [r.last_user_message for r in fake_llm.requests[2:]]
    assert all(p.startswith(f"The whole mission is: {GROUNDED}") for p in guide_prompts)  # grounded, not raw
    saved_record = json.loads((saved / "llm_record.json").read_text())
    assert saved_record["summary"]["calls"] == len(fake_llm.requests)


def test_plan_save_mission_needs_text(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["plan", "--scene", "demo", "--formula", "F enter(room_4)", "--save-mission", str(tmp_path / "m")]
    assert main(argv) == 2
    assert "use it with --text" in capsys.readouterr().err
