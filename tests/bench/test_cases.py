"""Sweep definition: discovery of a data folder, grids, keys, selections and their errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.bench.cases import BenchError, Case, Grid, discover, expand, paper_grids, parse_selection
from tests.bench.conftest import SCENE


def test_discover_finds_scene_missions_and_starts(data_dir: Path) -> None:
    (scene,) = discover(data_dir)
    assert scene.name == SCENE and scene.missions == ("1", "2", "3") and scene.num_starts == 6


def test_expand_is_a_deduplicated_union_in_paper_order(data_dir: Path) -> None:
    scenes = discover(data_dir)
    grids = [Grid(missions=("1",), starts=(0,), setups=("A*", "ALL")),
             Grid(missions=("1",), starts=(0,), setups=("all", "NO_LLM"))]
    cases = expand(scenes, grids, profile="ltlf", time_limit_s=5)
    assert [c.setup for c in cases] == ["ALL", "NO-LLM", "A*"]
    assert cases[0].key == f"{SCENE}/1/0/ALL/ltlf/tl=5/reach=visible"
    assert Case.from_dict(cases[2].to_dict()) == cases[2] and cases[2].slug == f"{SCENE}_m1_s0_Astar"
    # time limits that differ only past the 6th digit are different cases
    near = [Case(SCENE, "1", 0, "ALL", "authors", "s", "m", t).key for t in (1.0000001, 1.0000002, 0.25)]
    assert near == [f"{SCENE}/1/0/ALL/authors/tl={t}" for t in ("1.0000001", "1.0000002", "0.25")]


def test_the_key_names_the_reach_model_unless_it_is_the_box(data_dir: Path) -> None:
    """Rows made before there was a choice used the box model: their keys (no reach part) still resume
    box cases, and an ltlf row of then is not taken for a visible one of now."""
    def key(profile: str, model: str | None) -> str:
        return Case(SCENE, "1", 0, "ALL", profile, "s", "m", None, model).key

    assert key("authors", None) == key("authors", "box") == key("ltlf", "box").replace("ltlf", "authors")
    assert key("ltlf", None) == key("ltlf", "visible") == f"{SCENE}/1/0/ALL/ltlf/tl=none/reach=visible"
    assert key("authors", "visible").endswith("/authors/tl=none/reach=visible")
    cases = expand(discover(data_dir), [Grid(missions=("1",), starts=(0,), setups=("ALL",))],
                   profile="authors", reach_model="visible")
    assert [c.effective_reach_model for c in cases] == ["visible"]


def test_paper_grids_add_table2_only_with_benevolence() -> None:
    assert len(paper_grids(["Allensville"])) == 1
    table3, table2 = paper_grids(["Allensville", "Benevolence"])
    assert table2.scenes == ("Benevolence",) and table2.missions == ("1",) and len(table2.setups) == 7
    assert table3.setups == ("ALL", "NO-LLM", "A*")


@pytest.mark.parametrize(
    ("grid", "message"),
    [
        (Grid(scenes=("Nowhere",)), "not in the sweep"),
        (Grid(missions=("9",)), "no mission 9"),
        (Grid(starts=(6,)), "6 initial positions; start index 6"),
    ],
)
def test_expand_names_what_is_missing(data_dir: Path, grid: Grid, message: str) -> None:
    with pytest.raises(BenchError, match=message):
        expand(discover(data_dir), [grid])


def test_discover_errors(tmp_path: Path, data_dir: Path) -> None:
    with pytest.raises(BenchError, match="does not exist"):
        discover(tmp_path / "absent")
    with pytest.raises(BenchError, match="holds no scene"):
        discover(tmp_path)
    with pytest.raises(BenchError, match="no scene Nowhere"):
        discover(data_dir, ["Nowhere"])


def test_parse_selection() -> None:
    assert parse_selection("0,2-4") == (0, 2, 3, 4)
    with pytest.raises(BenchError, match="bad start selection"):
        parse_selection("1-x")
