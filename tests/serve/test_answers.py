"""The service's answers are byte for byte those recorded (timing fields aside): speeding up a warm plan
changes no byte of what a client reads (:mod:`tests.serve.answers`)."""

from __future__ import annotations

import json
from pathlib import Path

from sgplan.serve.scenes import SceneRegistry
from tests.serve.answers import answers, service_client

RECORDED = Path(__file__).parent / "data" / "answers.json"


def test_the_answers_are_the_recorded_bytes(demo_scenes: SceneRegistry, tmp_path: Path) -> None:
    recorded = json.loads(RECORDED.read_text())
    with service_client(demo_scenes, tmp_path) as client:
        first, again = answers(client), answers(client)  # cold, then from everything kept warm
    for run, found in (("cold", first), ("warm", again)):
        for expected, answer in zip(recorded, found, strict=True):
            assert answer == expected, f"{run}: {answer['route']} {answer['body']} answered otherwise"
