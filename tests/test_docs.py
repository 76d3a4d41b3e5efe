"""The docs stay true: every ```python block of README.md and docs/*.md runs, every `sgplan ...` command
line in their code blocks parses with the CLI's own parser, and every repository file they cite exists.

A block may carry one marker comment ``# doc-test: ...`` saying why it cannot simply run here:
``needs-gibson`` (runs only when the Gibson data is found), ``needs-llm`` (a language model server: never
run), ``house.house ...`` (gets the small .house of tests/importers/test_mp3d.py in its folder) and
``run by tests/llm/test_doc_example.py ...`` (a pytest example, run there with its fixtures). The blocks
of one page run in order in one namespace (a later block may use an earlier one's names), in a temporary
working directory so that their outputs (``out/...``) land there.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from sgplan.cli import _build_parser
from sgplan.datasets import find_gibson_root

REPO = Path(__file__).resolve().parents[1]
DOCS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.S | re.M)
MARKER = re.compile(r"^# doc-test: (.+)$", re.M)


def _name(doc: Path) -> str:
    return doc.relative_to(REPO).as_posix()


def python_blocks(doc: Path) -> list[tuple[int, str]]:
    """``(first line number, code)`` of each ```python block of ``doc``."""
    text = doc.read_text(encoding="utf-8")
    return [
        (text.count("\n", 0, m.start()) + 2, m.group(2))
        for m in FENCE.finditer(text)
        if m.group(1) == "python"
    ]


def code_lines(doc: Path) -> list[tuple[int, str]]:
    """Every line of the fenced and the indented (4 spaces) code blocks of ``doc``, numbered."""
    text = doc.read_text(encoding="utf-8")
    lines = text.splitlines()
    fenced: set[int] = set()
    for m in FENCE.finditer(text):
        first = text.count("\n", 0, m.start()) + 1  # index of the line after the opening fence
        fenced.update(range(first, first + m.group(2).count("\n")))
    return [(i + 1, line) for i, line in enumerate(lines)
            if i in fenced or (line.startswith("    ") and (i == 0 or not lines[i - 1].strip() or
                                                            lines[i - 1].startswith("    ")))]


def sgplan_commands(doc: Path) -> list[tuple[int, list[str]]]:
    """The ``sgplan ...`` command lines of ``doc``'s code blocks as argument lists (``\\`` continuations
    joined, ``# comments`` dropped)."""
    found: list[tuple[int, list[str]]] = []
    pending: tuple[int, str] | None = None
    for number, line in code_lines(doc):
        text = line.strip().removeprefix("$ ")
        if pending is not None:
            start, text = pending[0], pending[1] + " " + text
        elif re.match(r"(\.venv/bin/)?sgplan\s", text):
            start = number
        else:
            continue
        if text.endswith("\\"):
            pending = (start, text[:-1])
            continue
        pending = None
        found.append((start, shlex.split(text, comments=True)[1:]))
    return found


def _example_house(folder: Path) -> None:
    from tests.importers.test_mp3d import house_text

    (folder / "house.house").write_text(house_text())


DOCS_WITH_CODE = [doc for doc in DOCS if python_blocks(doc)]


@pytest.mark.parametrize("doc", DOCS_WITH_CODE, ids=_name)
def test_python_blocks_run(doc: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "doc_example"}
    ran, left = 0, []
    for line, code in python_blocks(doc):
        marker = MARKER.search(code)
        why = marker.group(1) if marker else ""
        where = f"{_name(doc)}:{line}"
        if why.startswith("needs-llm") or why.startswith("run by "):
            left.append(f"{where} ({why})")
            continue
        if why.startswith("needs-gibson"):
            if find_gibson_root() is None:
                left.append(f"{where} (needs the Gibson data)")
                continue
        elif why.startswith("house.house"):
            _example_house(tmp_path)
        elif why:
            pytest.fail(f"{where}: unknown doc-test marker {why!r}")
        exec(compile(code, where, "exec"), namespace)  # the doc's own example code
        ran += 1
    if not ran:
        pytest.skip("no block runnable here: " + "; ".join(left))


COMMANDS = [(doc, line, argv) for doc in DOCS for line, argv in sgplan_commands(doc)]


def test_docs_show_commands() -> None:
    assert len(COMMANDS) > 20 and {argv[0] for _, _, argv in COMMANDS} >= {
        "plan", "inspect", "bench", "import",
    }


@pytest.mark.parametrize(("doc", "line", "argv"), COMMANDS, ids=[f"{_name(d)}:{n}" for d, n, _ in COMMANDS])
def test_sgplan_command_lines_parse(
    doc: Path, line: int, argv: list[str], capsys: pytest.CaptureFixture
) -> None:
    try:
        args = _build_parser().parse_args(argv)
    except SystemExit as stop:  # argparse's way of refusing (or of answering --help / --version)
        assert stop.code == 0, f"{_name(doc)}:{line}: sgplan {shlex.join(argv)}\n{capsys.readouterr().err}"
        return
    assert callable(args.run)


# Repository paths cited in the docs: src/..., tests/..., benchmarks/..., docs/..., .ci/... and the package's
# own sgplan/....py; placeholders (<Scene>, *.png) and links to other pages are checked the same way.
CITED = re.compile(
    r"(?<![\w/.-])((?:src|tests|benchmarks|docs|\.ci)/[\w./-]*[\w/]|sgplan/[\w/]+\.py)(?![\w<*])"
)
LINK = re.compile(r"\]\(([\w./-]+\.md)\)")


@pytest.mark.parametrize("doc", DOCS, ids=_name)
def test_cited_files_are_shipped(doc: Path) -> None:
    text = doc.read_text(encoding="utf-8")
    cited = {m.group(1) for m in CITED.finditer(text)}
    missing = sorted(path for path in cited
                     if not (REPO / path).exists() and not (REPO / "src" / path).exists())
    missing += sorted(link for link in set(LINK.findall(text)) if not (doc.parent / link).exists())
    assert not missing, f"{_name(doc)} cites files the repository does not ship: {missing}"
    assert "/work/" not in text and "shared/design" not in text, f"{_name(doc)} cites a path of one machine"


def _option_helps(command: str) -> dict[str, str]:
    """Each option string of the sub-command ``command`` and its help text."""
    import argparse

    parser = _build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return {opt: action.help or "" for action in sub.choices[command]._actions
            for opt in action.option_strings}


def test_documented_commands_use_no_option_kept_only_for_old_scripts() -> None:
    """The README used `plan --verify`, which `plan --help` says is accepted for old scripts."""
    stale = [(f"{_name(doc)}:{line}", option) for doc, line, argv in COMMANDS
             for option in argv[1:] if "old scripts" in _option_helps(argv[0]).get(option, "")]
    assert stale == []


@pytest.mark.parametrize("doc", DOCS, ids=_name)
def test_docs_carry_no_notes_about_the_machine_load_of_the_day(doc: Path) -> None:
    """Measurements and the conditions of their run belong in benchmarks/results/, with the command."""
    text = doc.read_text(encoding="utf-8")
    assert not re.search(r"heavily loaded|loaded by other|load \d+\W\d+|load average", text), _name(doc)
