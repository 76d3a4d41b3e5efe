"""sgplan.safeio (bounded reading and quoting) and sgplan.files (atomic files and folders)."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from sgplan.errors import SceneError
from sgplan.files import rebuild_folder, write_text_atomically, write_texts_atomically
from sgplan.safeio import (
    MAX_DEPTH,
    json_depth,
    load_json,
    load_yaml,
    parse_json,
    parse_yaml,
    quote,
    read_text,
)


def test_quote_is_bounded_in_length_and_time() -> None:
    huge: list = list(range(10**6))
    deep: list = []
    for _ in range(100_000):
        deep = [deep]
    started = time.perf_counter()
    for value in (huge, "x" * 10**7, deep, {i: i for i in range(10**5)}):
        assert len(quote(value)) <= 80
    assert time.perf_counter() - started < 1.0
    assert quote("short") == "'short'"


@pytest.mark.parametrize(("text", "message"), [
    ("a: 1\na: 2\n", "duplicate key 'a' at line 2"),
    ("[" * 100_000, "nest"),
    ("- " * 5_000 + "x\n", "nesting deeper than 64 levels"),
    ("a: &a [1]\nb: [" + ", ".join(["*a"] * 1001) + "]\n", "more than 1,000 aliases"),
    ("&a [*a]\n", "refers to itself"),
    ("a: !!python/object:os.system x\n", "invalid YAML at line 1"),
])
def test_yaml_limits(text: str, message: str) -> None:
    with pytest.raises(SceneError, match=message):
        parse_yaml(text, SceneError, Path("f.yaml"))


def test_yaml_alias_bomb_is_refused_before_it_expands() -> None:
    levels = ["a0: &a0 [x, x, x, x, x, x, x, x, x]"]
    levels += [f"a{k}: &a{k} [" + ", ".join([f"*a{k - 1}"] * 9) + "]" for k in range(1, 9)]
    with pytest.raises(SceneError, match="expands to more than"):
        parse_yaml("\n".join(levels) + "\n", SceneError, None)


def test_yaml_within_the_limits_reads_as_usual() -> None:
    nested = "[" * (MAX_DEPTH - 1) + "1" + "]" * (MAX_DEPTH - 1)
    assert parse_yaml(f"a: {nested}\nb: &x [1, 2]\nc: *x\n1: one\n'1': text\n", SceneError, None)["c"] == [
        1,
        2,
    ]


def test_json_limits() -> None:
    assert json_depth('{"a": "[[[[", "b": [[1]]}') == 3
    with pytest.raises(SceneError, match="nests deeper than 64"):
        parse_json("[" * 100 + "]" * 100, SceneError, None)
    with pytest.raises(SceneError, match="NaN is not a JSON number"):
        parse_json('{"a": NaN}', SceneError, None)
    with pytest.raises(SceneError, match="invalid JSON at line 1 column 2"):
        parse_json("{", SceneError, None)


def test_reading_refuses_what_is_not_a_regular_file(tmp_path: Path) -> None:
    (tmp_path / "dir").mkdir()
    os.symlink(tmp_path / "loop2", tmp_path / "loop1")
    os.symlink(tmp_path / "loop1", tmp_path / "loop2")
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "big").write_bytes(b"x" * 100)
    (tmp_path / "latin").write_bytes(b"caf\xe9")
    for name, message in (("dir", "is a directory"), ("loop1", "cannot open"), ("fifo", "FIFO"),
                          ("missing", "does not exist"), ("latin", "not UTF-8 text \\(byte 3\\)")):
        with pytest.raises(SceneError, match=f"{name}: .*{message}"):
            read_text(tmp_path / name, SceneError)
    with pytest.raises(SceneError, match="100 bytes, more than the 10"):
        read_text(tmp_path / "big", SceneError, max_bytes=10)
    (tmp_path / "ok.yaml").write_text("a: [1, 2]\n")
    (tmp_path / "ok.json").write_text('{"a": [1, 2]}')
    assert load_yaml(tmp_path / "ok.yaml", SceneError) == load_json(tmp_path / "ok.json", SceneError)


def test_write_texts_atomically_writes_all_or_nothing(tmp_path: Path) -> None:
    first, second = tmp_path / "a.csv", tmp_path / "b.json"
    write_texts_atomically({first: "old a", second: "old b"})
    # Every text is written in full before any rename: a failed write (here, a missing folder) leaves
    # the first file's old text, and no temporary file behind.
    with pytest.raises(OSError):
        write_texts_atomically({first: "new a", tmp_path / "no" / "such" / "file": "x"})
    assert first.read_text() == "old a"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.json"]
    write_text_atomically(second, "new b")
    assert second.read_text() == "new b"


def test_rebuild_folder_swaps_a_whole_folder(tmp_path: Path) -> None:
    folder = tmp_path / "mission"
    folder.mkdir()
    (folder / "keep.txt").write_text("user's")
    (folder / "drop.txt").write_text("stale")
    (folder / "old.txt").write_text("old")

    def build(staging: Path) -> None:
        (staging / "old.txt").write_text("new")

    rebuild_folder(folder, build, carry_over=lambda name: name != "drop.txt")
    assert {p.name: p.read_text() for p in folder.iterdir()} == {"keep.txt": "user's", "old.txt": "new"}

    def failing(staging: Path) -> None:
        (staging / "old.txt").write_text("half")
        raise OSError(28, "No space left on device")

    with pytest.raises(OSError, match="No space"):
        rebuild_folder(folder, failing, carry_over=lambda name: True)
    assert {p.name: p.read_text() for p in folder.iterdir()} == {"keep.txt": "user's", "old.txt": "new"}
    assert sorted(p.name for p in tmp_path.iterdir()) == [".mission.lock", "mission"]
