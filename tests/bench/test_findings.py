"""The report's findings, computed from the rows of the run: what is timed and reused, the comparison with
the paper, and the `authors` paths that break the mission as written (read again under `ltlf`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sgplan.bench import findings
from sgplan.bench.cases import Case
from sgplan.bench.ltlf_check import ltlf_reading
from sgplan.bench.report import write_report
from sgplan.bench.worker import measure
from sgplan.logic.automaton import Automaton
from tests.bench.test_report import _row

# "Go to g; never enter f" over (g, f): bit 0 = g, bit 1 = f. State 0 waits, 1 accepts, 2 is the sink.
LTLF = Automaton(aps=("g", "f"), table=np.array([[0, 1, 2, 2], [1, 1, 2, 2], [2, 2, 2, 2]]), initial=0,
                 accepting=np.array([False, True, False]))
# The same file read as the authors' C++ does: no edge for f, so f keeps the state.
AUTHORS = Automaton(aps=("g", "f"), table=np.array([[0, 1, 0, 0], [1, 1, 1, 1]]), initial=0,
                    accepting=np.array([False, True]))


def _path(labels: list[int]) -> tuple[np.ndarray, np.ndarray]:
    q, states = AUTHORS.initial, []
    for k, label in enumerate(labels):
        q = q if k == 0 else int(AUTHORS.table[q, label])  # authors: the start label is not read
        states.append(q)
    path = np.array([[k, 2 * k, 0, s] for k, s in enumerate(states)])
    return path, np.array(labels)


def test_a_path_through_a_forbidden_place_is_named_with_where_and_why() -> None:
    path, labels = _path([0, 2, 2, 0, 2, 0, 1])  # f twice (once two cells long), then g
    assert path[-1, 3] == 1  # accepted as the authors read it
    accepts, found = ltlf_reading(path, labels, np.arange(len(labels)) * 0.5, AUTHORS, LTLF,
                                  lambda p: f"the {p} room")
    assert not accepts and len(found) == 1
    v = found[0]
    assert (v.index, v.cell, v.cost_m, v.reason, v.state, v.places, v.times) == (
        1, (1, 2, 0), 0.5, "missing-edge", 0, ("the f room",), 2)
    accepts, found = ltlf_reading(*_path([2, 0, 1]), np.zeros(3), AUTHORS, LTLF, str)
    assert not accepts and [(v.reason, v.places) for v in found] == [("start-label", ("f",))]
    accepts, found = ltlf_reading(*_path([0, 0, 1]), np.zeros(3), AUTHORS, LTLF, str)
    assert accepts and found == []


def _violating_row(start: int, setup: str) -> dict:
    violation = {"index": 250, "cell": [86, 391, 2], "cost_m": 2.93, "reason": "missing-edge", "state": 2,
                 "places": ["the staircase (room_19, floor 1)"], "times": 1}
    return _row("Benevolence", "1", start, setup, 27.0, path_cells=900, ltlf_accepts=False,
                ltlf_violations=[violation], scene_reused=True)


def test_the_report_says_which_authors_paths_break_the_mission_and_why(tmp_path: Path) -> None:
    rows = [_violating_row(3, "ALL"), _violating_row(3, "A*"),
            _row("Benevolence", "1", 0, "ALL", 18.9, path_cells=800, ltlf_accepts=True, ltlf_violations=[],
                 scene_reused=False)]
    text = "\n".join(findings.semantics_section(rows))
    assert "1 of the 3 paths satisfy the mission as written, 2 do not" in text
    assert ("| Benevolence | 1 | 3 | ALL, A* | enters the staircase (room_19, floor 1) at (86, 391) on floor "
            "2, 2.93 m along the path: the automaton has no edge for that from state 2, which `authors` "
            "reads as staying in it |") in text
    ltlf = [dict(r, profile="ltlf") for r in rows]
    assert "each satisfies the mission as written" in "\n".join(findings.semantics_section(ltlf))
    report = (write_report(tmp_path, rows).markdown).read_text()
    assert "## What is timed" in report and "## Reading the comparison with the paper" in report
    assert "## Paths and the mission as written" in report


def test_the_timing_and_the_comparison_are_computed_from_the_rows() -> None:
    rows = [_row("Benevolence", "1", k, "ALL", 20.0, scene_reused=k > 0, precompute_s=3.0 if k == 0 else 1.0)
            for k in range(3)]
    rows += [_row("Benevolence", "1", k, "A*", 20.0, optimal_time_s=1.0, first_time_s=0.02, cost_ratio=1.0,
                  scene_reused=True, precompute_s=1.0) for k in range(3)]
    timing = "\n".join(findings.timing_section(rows))
    assert "5 cases of the 6 optimal ones ran in a worker that had loaded their scene" in timing
    assert "(mean 1.00 s, against 3.00 s for the 1 case that loaded their scene)" in timing
    reading = "\n".join(findings.comparison_section(rows, ("Benevolence", "1")))
    # Paper Table III, Benevolence: ALL 11.82 s and A* 14.22 s to the optimum; ours 2.0 s and 1.0 s.
    assert "the paper's time over ours: x5.91 to x14.2 (median x10.1) over 2 (scene, setup) cells" in reading
    assert "Fastest first path per scene, ours: Benevolence: ALL. The paper's: Benevolence: ALL." in reading
    assert "to the optimum per scene, ours: Benevolence: A*. The paper's: Benevolence: ALL." in reading
    assert "Worst first path (highest 1st cost ÷ opt.) per scene, ours: Benevolence: ALL." in reading
    assert "Table II (Benevolence mission 1, 2 setups): the paper's time to the optimum over ours" in reading


@pytest.mark.gibson
def test_benevolence_mission_1_start_3_crosses_the_forbidden_staircase(gibson_root: Path) -> None:
    """The first-day report's example: the `authors` optimum crosses the staircase and the living room."""
    scene = gibson_root / "Benevolence"
    case = Case("Benevolence", "1", 3, "A*", "authors", str(scene), str(scene / "missions" / "1"))
    out = measure(case)
    assert out["status"] == "optimal" and out["ltlf_accepts"] is False and out["scene_reused"] is False
    places = {p for v in out["ltlf_violations"] for p in v["places"]}
    assert places == {"the staircase (room_19, floor 1)", "the living room (room_16, floor 1)"}
    ltlf = measure(Case("Benevolence", "1", 3, "A*", "ltlf", str(scene), str(scene / "missions" / "1")))
    assert ltlf["status"] != "optimal" and ltlf["ltlf_accepts"] is None  # as written: no path from there
