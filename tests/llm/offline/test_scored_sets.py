"""The offline translator on its two scored sets (``sets/``): 78 missions with the paper's own texts
(``pattern_missions.jsonl``) and 63 everyday missions of our own over the four scenes
(``everyday_missions.jsonl``); gold formulas compared by automaton equivalence under the scene's facts."""

from __future__ import annotations

import pytest

from sgplan.llm.evaluate import load_jsonl_set, score_translator
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.evaluation import evaluate
from tests.llm.offline.corpus import SETS
from tests.shared_data import scene_building

PATTERN_SET = SETS / "pattern_missions.jsonl"
EVERYDAY_SET = SETS / "everyday_missions.jsonl"
MIN_SCORE = 0.85
"""Floor on the share of right translations over the pattern set (the paper's own texts included)."""


def test_the_pattern_set_is_large_and_varied() -> None:
    missions = load_jsonl_set(PATTERN_SET)
    assert len(missions) >= 40
    assert {m.scene for m in missions} == {"demo", "Allensville", "Benevolence", "Collierville"}
    assert sum(m.paper for m in missions) == 15
    assert len({m.id for m in missions}) == len(missions)


def test_pattern_set_demo_missions() -> None:
    results = evaluate(PatternTranslator(), [m for m in load_jsonl_set(PATTERN_SET) if m.scene == "demo"],
                       scene_building)
    assert [r.mission.id for r in results if r.outcome != "right"] == []


@pytest.mark.gibson
def test_pattern_set_full_score(gibson_root: object) -> None:
    results = evaluate(PatternTranslator(), load_jsonl_set(PATTERN_SET), scene_building)
    wrong = [f"{r.mission.id}: {r.detail}" for r in results if r.outcome == "wrong"]
    assert not wrong, "silently wrong translations:\n" + "\n".join(wrong)
    failed_must = [f"{r.mission.id}: {r.detail}" for r in results if r.mission.must_pass
                   and r.outcome != "right"]
    assert not failed_must, "\n".join(failed_must)
    score = sum(r.outcome == "right" for r in results) / len(results)
    assert score >= MIN_SCORE, f"score {score:.1%} < {MIN_SCORE:.0%}"


def test_the_everyday_set_is_varied() -> None:
    missions = load_jsonl_set(EVERYDAY_SET)
    assert len(missions) >= 60
    assert {m.scene for m in missions} == {"demo", "Allensville", "Benevolence", "Collierville"}
    assert sum(m.gold is None for m in missions) >= 4  # missions that must be refused
    assert sum(m.start_floor is not None for m in missions) >= 10


def test_everyday_demo_missions() -> None:
    missions = [m for m in load_jsonl_set(EVERYDAY_SET) if m.scene == "demo"]
    score = score_translator(PatternTranslator(), missions, scene_building)
    assert [f"{r.mission.id}: {r.detail}" for r in score.results if r.outcome != "right"] == []


@pytest.mark.gibson
def test_everyday_gibson_missions(gibson_root: object) -> None:
    missions = [m for m in load_jsonl_set(EVERYDAY_SET) if m.scene != "demo"]
    score = score_translator(PatternTranslator(), missions, scene_building)
    assert [f"{r.mission.id}: {r.detail}" for r in score.results if r.outcome != "right"] == []
