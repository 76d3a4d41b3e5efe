"""The CLI's exception boundary: a bug is one 'internal error' line with exit code 70, never a traceback,
and never mistaken for bad input (exit code 2)."""

from __future__ import annotations

import pytest

from sgplan import cli
from sgplan.errors import MissionError


def _failing(error: BaseException):  # type: ignore[no-untyped-def]
    def run(args):  # type: ignore[no-untyped-def]
        raise error
    return run


@pytest.mark.parametrize(
    "error", [ValueError("x" * 10_000), RecursionError("deep"), MemoryError(), KeyError("k")]
)
def test_an_unexpected_exception_is_one_line_and_exit_70(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], error: BaseException
) -> None:
    monkeypatch.setattr(cli, "_build_parser", _parser_running(_failing(error)))
    assert cli.main(["plan", "--scene", "demo", "--formula", "F p"]) == cli.INTERNAL_ERROR
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and len(lines[0]) < 600
    assert lines[0].startswith(f"sgplan plan: internal error: {type(error).__name__}")
    assert "formula=F p" in lines[0] and "scene=demo" in lines[0] and "--debug" in lines[0]


def test_bad_input_stays_exit_2_and_debug_shows_the_traceback(monkeypatch: pytest.MonkeyPatch,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(cli, "_build_parser", _parser_running(_failing(MissionError("bad mission"))))
    assert cli.main(["plan", "--scene", "demo", "--formula", "F p"]) == 2
    assert capsys.readouterr().err.strip() == "sgplan: error: bad mission"
    monkeypatch.setattr(cli, "_build_parser", _parser_running(_failing(ValueError("bug"))))
    with pytest.raises(ValueError, match="bug"):
        cli.main(["--debug", "plan", "--scene", "demo", "--formula", "F p"])


def _parser_running(run):  # type: ignore[no-untyped-def]
    """The real parser, with every command's ``run`` replaced by ``run``."""
    build = cli._build_parser

    def parser():  # type: ignore[no-untyped-def]
        real = build()
        real.set_defaults(run=run)
        for action in real._subparsers._group_actions[0].choices.values():  # type: ignore[union-attr]
            action.set_defaults(run=run)
        return real
    return parser
