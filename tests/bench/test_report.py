"""Report: tables in the paper's layout, excluded cases apart, figures, from a results folder."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from sgplan.bench import tables
from sgplan.bench.cases import BenchError, Case
from sgplan.bench.report import choose_condition, write_report
from sgplan.bench.results import ResultStore
from sgplan.cli import main
from tests.bench.conftest import BAD_START, SCENE


def test_report_from_a_results_folder(swept: tuple[list[Case], ResultStore], tmp_path: Path,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    _, store = swept
    shutil.copy(store.path, tmp_path / store.path.name)
    assert main(["bench", "report", "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    text = (tmp_path / "report.md").read_text()
    assert f"## Table II - {SCENE} mission 1" in text and "## Table III" in text
    assert "| ALL | 2 |" in text and "| A* | 2 |" in text  # 2 starts averaged; the invalid start is not
    assert (
        f"| {SCENE} | 1 | {BAD_START} | invalid-start | ALL | start (row 0, col 0, floor 0) lies in no room"
        in text
    )
    assert (
        f"| {SCENE} | 3 | 0 | unsatisfiable | ALL | no path in scene '{SCENE}' satisfies the mission" in text
    )
    assert "same optimal cost in each of the 2" in text
    assert "| setup | n | 1st iter. time (s) | paper |" in printed
    for name in ("cost_vs_time", "expansions_per_iteration"):
        for ext in ("png", "svg"):
            assert (tmp_path / "figures" / f"{name}.{ext}").stat().st_size > 5000
    assert (tmp_path / "results.csv").exists() and (tmp_path / "results.json").exists()


def test_report_without_results_says_what_to_do(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "report", "--out", str(tmp_path)]) == 2
    assert "run `sgplan bench --out" in capsys.readouterr().err


def _row(scene: str, mission: str, start: int, setup: str, cost: float, **extra: object) -> dict:
    its = [
        {"w1": 10.0, "w2": 20.0, "cost_m": cost * 1.5, "bound": 200.0, "time_s": 0.01, "expansions": [5, 5]},
        {"w1": 1.0, "w2": 1.0, "cost_m": cost, "bound": 1.0, "time_s": 2.0, "expansions": [50, 70]},
    ]
    row = {
        "key": f"{scene}/{mission}/{start}/{setup}", "scene": scene, "mission": mission, "start": start,
        "setup": setup, "profile": "authors", "status": "optimal", "cost_m": cost, "first_cost_m": cost * 1.5,
        "cost_ratio": 1.5, "first_time_s": 0.01, "optimal_time_s": 2.0, "precompute_s": 3.0, "load_s": 1.0,
        "wall_s": 7.0, "peak_rss_mb": 400.0, "expansions": 130, "iterations": its,
        "queues": ["LTL/anchor", "LTL/occupancy"],
    }
    row.update(extra)
    return row


def test_paper_numbers_stand_beside_ours() -> None:
    rows = [_row("Benevolence", "1", k, s, 20.0 + k) for k in (0, 2) for s in ("ALL", "A*")]
    rows.append(_row("Benevolence", "1", 1, "ALL", 0.0, status="invalid-start", reason="in collision"))
    rows.append(_row("Allensville", "2", 0, "ALL", 5.0, cost_ratio=2.5))
    assert tables.table2_case(rows) == ("Benevolence", "1")
    t2 = tables.table2(rows, "Benevolence", "1")
    assert "| ALL | 2 | 0.0100 | 0.0007 | 1.5000 | 1.3763 | 2.00 | 8.9062 | 3.00 | 7.00 | 400 |" in t2
    t3 = tables.table3(rows)
    assert (
        "| ALL | 0.0100 / 1.50 / 2.00 | 2 | 0.3200 / 1.24 / 11.82 | 0.0100 / 2.50 / 2.00 | 1 | 0.2400 / 1.69 "
        "/ 3.50 |"
        in t3
    )
    assert "in collision" in tables.excluded_table(rows)
    rows.append(_row("Benevolence", "1", 0, "NO-LLM", 20.5))
    compared, bad = tables.cost_disagreements(rows)
    assert compared == 2 and len(bad) == 1 and "NO-LLM 20.500000" in bad[0]


def test_the_report_never_mixes_profiles_or_time_limits(tmp_path: Path) -> None:
    authors = [_row("Benevolence", "1", k, "ALL", 20.0, finished_at="2026-01-01T10:00:00") for k in (0, 1)]
    ltlf = [_row("Benevolence", "1", k, "ALL", 30.0, profile="ltlf", finished_at="2026-01-02T10:00:00",
                 key=f"Benevolence/1/{k}/ALL/ltlf") for k in (0, 1, 2)]
    limited = [_row("Benevolence", "1", 0, "ALL", 25.0, time_limit_s=5.0, key="Benevolence/1/0/ALL/tl=5")]
    rows = authors + ltlf + limited
    latest = write_report(tmp_path, rows)  # default: the condition of the newest row (ltlf)
    text = (tmp_path / "report.md").read_text()
    assert "| ALL | 3 |" in latest.table2 and "profile ltlf, reach model box, no time limit" in text
    assert (
        "2 cases under profile authors, reach model box, no time limit" in text
        and "1 case under profile authors, reach model box, time limit 5 s" in text
    )
    chosen = write_report(tmp_path, rows, condition=("authors", "box", 5.0))
    assert "| ALL | 1 |" in chosen.table2
    with pytest.raises(BenchError, match="no results under profile ltlf, reach model box, time limit 9 s"):
        write_report(tmp_path, rows, condition=("ltlf", "box", 9.0))


def test_the_report_never_mixes_reach_models(tmp_path: Path) -> None:
    """Rows made before the choice existed (no reach_model field) used the box model."""
    old = [_row("Benevolence", "1", k, "ALL", 20.0, profile="ltlf", finished_at="2026-01-01T10:00:00",
                key=f"Benevolence/1/{k}/ALL/ltlf") for k in (0, 1)]
    new = [_row("Benevolence", "1", k, "ALL", 21.0, profile="ltlf", reach_model="visible",
                finished_at="2026-01-02T10:00:00", key=f"Benevolence/1/{k}/ALL/ltlf/reach=visible")
           for k in (0, 1, 2)]
    latest = write_report(tmp_path, old + new)
    text = (tmp_path / "report.md").read_text()
    assert "| ALL | 3 |" in latest.table2 and "profile ltlf, reach model visible, no time limit" in text
    assert "2 cases under profile ltlf, reach model box, no time limit" in text
    assert choose_condition(old + new, reach_model="box") == ("ltlf", "box", None)


def test_report_rows_are_chosen_by_profile_and_time_limit() -> None:
    rows = [_row("B", "1", 0, "ALL", 1.0, finished_at="2026-01-01"),
            _row("B", "1", 0, "ALL", 1.0, profile="ltlf", time_limit_s=0.1234567, finished_at="2026-01-03"),
            _row("B", "1", 0, "ALL", 1.0, time_limit_s=5.0, finished_at="2026-01-02")]
    assert choose_condition(rows) == ("ltlf", "box", 0.1234567)
    assert choose_condition(rows, profile="authors") == ("authors", "box", 5.0)  # the newest authors limit
    assert choose_condition(rows, time_limit_s=0.1234567) == ("ltlf", "box", 0.1234567)
    with pytest.raises(BenchError, match=r"no results with profile ltlf, time limit 5 s; recorded: .*"
                                         r"profile ltlf, reach model box, time limit 0.1234567 s"):
        choose_condition(rows, "ltlf", 5.0)
    with pytest.raises(BenchError, match=r"no results with profile ltlf, reach model visible; recorded"):
        choose_condition(rows, "ltlf", reach_model="visible")


def test_report_of_an_empty_results_file_says_what_to_do(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "results.jsonl").write_text('{"key": "a", "scene"')  # only a torn first row
    assert main(["bench", "report", "--out", str(tmp_path)]) == 2
    assert "no results in" in capsys.readouterr().err
