"""Score of the offline pattern translator on tests/llm/data/pattern_missions.yaml."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.evaluation import evaluate, load_mission_set
from tests.shared_data import scene_building

SET = Path(__file__).parent / "data" / "pattern_missions.yaml"
MIN_SCORE = 0.85
"""Floor on the share of right translations over the whole set (the paper's own texts included)."""


building_of = scene_building


def test_the_set_is_large_and_varied():
    missions = load_mission_set(SET)
    assert len(missions) >= 40
    assert {m.scene for m in missions} == {"demo", "Allensville", "Benevolence", "Collierville"}
    assert sum(m.paper for m in missions) == 15
    assert len({m.id for m in missions}) == len(missions)


def test_demo_missions_score():
    results = evaluate(PatternTranslator(), [m for m in load_mission_set(SET) if m.scene == "demo"],
                       building_of)
    assert [r.mission.id for r in results if r.outcome != "right"] == []


@pytest.mark.gibson
def test_full_score(gibson_root):
    results = evaluate(PatternTranslator(), load_mission_set(SET), building_of)
    wrong = [f"{r.mission.id}: {r.detail}" for r in results if r.outcome == "wrong"]
    assert not wrong, "silently wrong translations:\n" + "\n".join(wrong)
    failed_must = [f"{r.mission.id}: {r.detail}" for r in results if r.mission.must_pass
                   and r.outcome != "right"]
    assert not failed_must, "\n".join(failed_must)
    score = sum(r.outcome == "right" for r in results) / len(results)
    assert score >= MIN_SCORE, f"score {score:.1%} < {MIN_SCORE:.0%}"
