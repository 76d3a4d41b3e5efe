"""Damaged input files of every format, fed to the CLI: each ends in one clean error line (or, if the
damage left a valid file, a normal run), within the time budget, never a traceback, hang or crash."""

from __future__ import annotations

import json
import sys
import tempfile
import threading
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.faults.harness import check, generated
from tests.faults.inputs import fresh_copy, pickled_npz, scene_graph_dict, write_npz
from tests.faults.strategies import BAD_SCALARS, DEEP, damaged_hoa, damaged_json, damaged_yaml, token_lists

GENERATED = generated(12)

PLAN = ["--time-limit", "5", "--setup", "NO-LLM"]
"""Planning options of the mission cases: a small budget and no guidance needed."""


def _inspect(scene: Path) -> list[str]:
    return ["inspect", str(scene)]


def _plan_mission(folder: Path) -> list[str]:
    return ["plan", "--scene", "demo", "--mission-dir", str(folder), *PLAN]


# -- scene files -----------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["building.yaml", "initial_positions.yaml"])
@GENERATED
@given(data=st.data())
def test_authors_yaml(templates: dict[str, Path], name: str, data: st.DataObject) -> None:
    text = (templates["authors"] / name).read_text()
    damaged = data.draw(damaged_yaml(text))
    with fresh_copy(templates["authors"]) as scene:
        (scene / name).write_bytes(damaged)
        check(f"authors/{name}", _inspect(scene))


@GENERATED
@given(value=BAD_SCALARS, key=st.sampled_from(["ROBOT_RADIUS", "OBJECT_REACH_RADIUS"]))
def test_radius_config(templates: dict[str, Path], value: str, key: str) -> None:
    with fresh_copy(templates["authors"]) as scene:
        (scene / "radius_config.bash").write_text(f"{key}={value}\n")
        check("authors/radius_config.bash", _inspect(scene))


@GENERATED
@given(data=st.data())
def test_native_scene_json(templates: dict[str, Path], data: st.DataObject) -> None:
    document = json.loads((templates["native"] / "scene.json").read_text())
    damaged = data.draw(damaged_json(document))
    with fresh_copy(templates["native"]) as scene:
        (scene / "scene.json").write_bytes(damaged)
        check("native/scene.json", _inspect(scene))


@GENERATED
@given(cut=st.integers(0, 10_000), flip=st.integers(0, 10_000))
def test_png_maps(templates: dict[str, Path], cut: int, flip: int) -> None:
    with fresh_copy(templates["authors"]) as scene:
        png = scene / "cat_maps" / "0.png"
        data = bytearray(png.read_bytes())
        data[flip % len(data)] ^= 0xFF
        png.write_bytes(bytes(data[: max(1, cut % (len(data) + 1))]))
        check("authors/png", _inspect(scene))


_NPZ_VALUES = st.sampled_from(
    [
        None,
        1,
        "x",
        [],
        [[[[]]]],
        {"building": None},
        {"building": {}, "room": [], "object": {}},
        {"building": {"id": "1", "name": 5}, "room": {}, "object": {}},
        {"building": {"id": 1, "name": "n"}, "room": {1: {"id": 1, "floor_number": "AB"}}, "object": {}},
        {
            "building": {"id": 1, "name": "n"},
            "room": {
                1: {
                    "id": 1, "floor_number": "A", "scene_category": "k", "location": [float("nan")] * 3,
                    "size": [1, 1],
                }
            },
            "object": {},
        },
    ]
)


@GENERATED
@given(value=_NPZ_VALUES, cut=st.integers(0, 2000), protocol=st.sampled_from([0, 2, 4]))
def test_gibson_npz(templates: dict[str, Path], value: object, cut: int, protocol: int) -> None:
    with fresh_copy(templates["npz"]) as npz:
        if cut % 3 == 0:
            write_npz(npz, value, protocol)
        else:
            data = npz.read_bytes()
            npz.write_bytes(data[: cut % len(data)])
        check("gibson/npz", _inspect(npz))


# -- mission files ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["ap_desc.yaml", "llm_heuristic.yaml"])
@GENERATED
@given(data=st.data())
def test_mission_yaml(templates: dict[str, Path], name: str, data: st.DataObject) -> None:
    damaged = data.draw(damaged_yaml((templates["mission"] / name).read_text()))
    with fresh_copy(templates["mission"]) as mission:
        (mission / name).write_bytes(damaged)
        check(f"mission/{name}", _plan_mission(mission))


@GENERATED
@given(data=st.data())
def test_hoa(templates: dict[str, Path], data: st.DataObject) -> None:
    damaged = data.draw(damaged_hoa((templates["mission"] / "automaton.aut").read_text()))
    with fresh_copy(templates["mission"]) as mission:
        (mission / "automaton.aut").write_bytes(damaged)
        check("mission/automaton.aut", _plan_mission(mission))


@GENERATED
@given(text=token_lists(["enter(room_5)", "enter(room_7)", "reach(object_32)"]))
def test_formula_tokens(text: str) -> None:
    check("formula/tokens", ["plan", "--scene", "demo", "--formula", text, *PLAN])


@GENERATED
@given(data=st.data())
def test_gpt_formula_file(templates: dict[str, Path], data: st.DataObject) -> None:
    text = data.draw(token_lists(["enter(room_5)", "enter(room_7)", "reach(object_32)"]))
    with fresh_copy(templates["mission"]) as mission:
        (mission / "GPT_LTL_formula.txt").write_text(text)
        check("mission/GPT_LTL_formula.txt", _plan_mission(mission))


# -- benchmark results and LLM cache entries --------------------------------------------------------------

_ROW = {
    "key": "demo-house/1/0/ALL/authors/none", "scene": "demo-house", "mission": "1", "start": 0,
    "setup": "ALL", "profile": "authors", "time_limit_s": None, "status": "optimal", "reason": None,
    "cost_m": 3.5, "first_cost_m": 3.5, "cost_ratio": 1.0, "first_time_s": 0.01, "optimal_time_s": 0.02,
    "num_iterations": 1, "expansions": 10, "load_s": 0.1, "precompute_s": 0.1, "search_s": 0.02,
    "wall_s": 1.0, "peak_rss_mb": 100.0, "path_cells": 5,
}


@GENERATED
@given(data=st.data())
def test_bench_rows(data: st.DataObject) -> None:
    damaged = data.draw(damaged_json(_ROW))
    with tempfile.TemporaryDirectory(prefix="sgplan-fault-") as tmp:
        out = Path(tmp)
        (out / "results.jsonl").write_bytes(
            json.dumps(_ROW).encode() + b"\n" + damaged.replace(b"\n", b" ") + b"\n"
        )
        check("bench/results.jsonl", ["bench", "report", "--out", str(out)])


@pytest.mark.parametrize("value", ["NaN", '["a", "list"]', '"12 s"', "1e999", "-Infinity"])
def test_bench_row_fields(value: str) -> None:
    """The three row faults of the issue: NaN, a list as key, strings as timings."""
    with tempfile.TemporaryDirectory(prefix="sgplan-fault-") as tmp:
        out = Path(tmp)
        row = json.dumps(_ROW)
        field = '"key": ' if value.startswith("[") else '"search_s": '
        old = row[row.index(field):].split(",")[0]
        (out / "results.jsonl").write_text(row.replace(old, field + value) + "\n")
        check(f"bench/row {value}", ["bench", "report", "--out", str(out)], must_fail=True)


def test_deep_pickle_npz() -> None:
    """A pickle nesting lists 100,000 deep, and one nesting tuples (MARK) as deep."""
    deep_lists = b"\x80\x02" + b"]q\x00" * 0 + b"]" * DEEP + b"a" * (DEEP - 1) + b"."
    deep_marks = b"\x80\x02" + b"(" * DEEP + b"t" * DEEP + b"."
    for name, payload in (("lists", deep_lists), ("marks", deep_marks)):
        with tempfile.TemporaryDirectory(prefix="sgplan-fault-") as tmp:
            npz = Path(tmp) / "deep.npz"
            pickled_npz(npz, payload)
            check(f"gibson/deep pickle {name}", _inspect(npz), subprocess_only=True)


def test_deep_value_in_npz_field(tmp_path: Path) -> None:
    """A field of the scene-graph dict holding a list nested 100,000 deep (quoted in the error message)."""
    value = scene_graph_dict()
    deep: list = []
    for _ in range(DEEP):
        deep = [deep]
    value["room"][1]["location"] = deep  # type: ignore[index]
    npz = tmp_path / "deep.npz"
    _with_deep_stack(lambda: write_npz(npz, value))
    check("gibson/deep field", _inspect(npz), subprocess_only=True)


def _with_deep_stack(job: Callable[[], None]) -> None:
    """Run ``job`` (the pickler, which recurses once per level) in a thread with room for 100,000 levels."""
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(10 * DEEP)
    threading.stack_size(512 * 2**20)
    try:
        worker = threading.Thread(target=job)
        worker.start()
        worker.join()
    finally:
        sys.setrecursionlimit(limit)
        threading.stack_size(0)
