"""The service's answers to a fixed set of demo-scene requests, as the bytes it sends, with the timing
fields zeroed, and their SHA-256: ``test_answers.py`` compares them with the digests recorded in
``data/answers.json`` (to see what changed, run this module on both versions and diff its ``--full``
output).

Recorded with the service before its warm-plan speed-ups, so those changed no byte of an answer. A change
that means to alter the answers records them again (and says why in its commit)::

    .venv/bin/python -m tests.serve.answers > tests/serve/data/answers.json
    .venv/bin/python -m tests.serve.answers --full > /tmp/answers-full.json
"""

from __future__ import annotations

import hashlib
import json
import re
import sys
import tempfile
from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient

from sgplan.serve.app import create_app
from sgplan.serve.config import ServeConfig
from sgplan.serve.scenes import SceneRegistry
from sgplan.serve.service import MissionService

FORMULA = 'F("enter(room_4)" & F "enter(room_11)") & G !"enter(room_5)"'
UPSTAIRS = ('F("enter(room_5)" & F("reach(object_28)" & F "enter(room_11)")) '
            '& G(!"enter(room_6)" & !"enter(room_4)")')
TEXT = "Go to the kitchen, then the bedroom with the clock. Always avoid the bathroom on floor 0."
REQUESTS: list[tuple[str, dict[str, Any]]] = [
    *(
        ("/api/plan", {"scene": "demo", "formula": formula, "start": start, "options": {"setup": setup}})
        for formula in (FORMULA, UPSTAIRS)
        for start, setup in (({"index": 0}, "A*"), ({"index": 0}, "ALL"), ({"room": "dining_room"}, "A*"),
                             ({"room": "home_office"}, "A*"), ({"room": "kitchen"}, "A*"))
    ),
    ("/api/plan", {"scene": "demo", "text": TEXT, "view": True, "start": {"room": "dining_room"}}),
    ("/api/plan", {"scene": "demo", "formula": FORMULA, "options": {"setup": "A*", "max_expansions": 5}}),
    ("/api/explain", {"scene": "demo", "text": TEXT, "start": {"index": 0}}),
]
"""(route, body): formulas from several starts and setups (one start the mission forbids), a text with
the page's overlays, a plan stopped by its budget, a say-back."""
_TIMING = re.compile(rb'"(time_s|prepare_s|precompute_s|search_s|wall_s)":[-+0-9.eE]+')


def without_timings(content: bytes) -> str:
    """``content`` with every timing field's value replaced by 0 (they differ from run to run)."""
    return _TIMING.sub(rb'"\1":0', content).decode()


def answers(client: TestClient, full: bool = False) -> list[dict[str, Any]]:
    """Each request of :data:`REQUESTS` with the status, length and SHA-256 of its answer (timings
    zeroed); ``full``: the answer's text too."""
    found = []
    for route, body in REQUESTS:
        response = client.post(route, json=body)
        text = without_timings(response.content)
        digest = hashlib.sha256(text.encode()).hexdigest()
        found.append({"route": route, "body": body, "status": response.status_code, "chars": len(text),
                      "sha256": digest} | ({"answer": text} if full else {}))
    return found


def service_client(scenes: SceneRegistry, state: Path) -> TestClient:
    # The longest request time limit: the first plan of a process whose numba cache is cold compiles the
    # kernels within its request, which on a loaded machine can outlast the default limit (a 408).
    config = ServeConfig(scenes=("demo",), state_dir=state, request_time_limit_s=3600).checked()
    return TestClient(create_app(service=MissionService.start(config, scenes)))


if __name__ == "__main__":
    with service_client(SceneRegistry.load(["demo"]), Path(tempfile.mkdtemp())) as c:
        json.dump(answers(c, full="--full" in sys.argv), sys.stdout, indent=1)
        sys.stdout.write("\n")
