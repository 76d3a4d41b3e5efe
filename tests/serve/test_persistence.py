"""Runs survive the server's death: started as a real process, killed with SIGKILL (no shutdown code
runs), started again on the same state folder: every run is there, at the same progress, with the same
plan, and plans the same."""

from __future__ import annotations

from pathlib import Path

import httpx
import pytest

from tests.serve.conftest import KITCHEN_TEXT, ServerProcess

pytestmark = pytest.mark.slow
FORMULA = 'F("enter(room_4)" & F "enter(room_11)") & G !"enter(room_5)"'


def _poses(waypoints: list[dict[str, float]]) -> list[list[float]]:
    return [[w["x_m"], w["y_m"], w["floor"]] for w in waypoints]


def _events(c: httpx.Client, run: dict[str, object]) -> list[str]:
    """The run's ``run["events"]`` events as SSE lines (an active run's stream stays open after them)."""
    lines: list[str] = []
    with c.stream("GET", f"/api/runs/{run['id']}/events") as stream:
        for line in stream.iter_lines():
            lines.append(line)
            if sum(x.startswith("data:") for x in lines) == run["events"]:
                break
    return lines


def test_runs_survive_sigkill_at_the_same_progress(tmp_path: Path) -> None:
    server = ServerProcess(tmp_path / "state").start()
    try:
        made = []
        with httpx.Client(base_url=server.url, timeout=60) as c:
            for k, (mission, start) in enumerate(
                [
                    ({"text": KITCHEN_TEXT}, {"room": "kitchen"}),
                    ({"formula": FORMULA}, {"index": 0}),
                    ({"text": "Go to the dining room."}, {"room": "room_13"}),
                    ({"formula": FORMULA}, {"room": "living_room"}),
                ]
            ):
                run = c.post("/api/runs", json={"scene": "demo", **mission, "start": start}).json()
                waypoints = run["plan"]["waypoints"]
                if k == 1:
                    c.post(f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints[:7])})
                    c.post(f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints[7:12])})
                if k == 2:
                    c.post(f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints)})
                if k == 3:
                    c.post(f"/api/runs/{run['id']}/cancel")
                made.append(c.get(f"/api/runs/{run['id']}").json())
            events = {run["id"]: _events(c, run) for run in made}
        assert [r["status"] for r in made] == ["active", "active", "done", "cancelled"]
        server.kill()

        server.start()
        with httpx.Client(base_url=server.url, timeout=60) as c:
            assert c.get("/api/health").json()["runs"] == len(made)
            for before in made:
                after = c.get(f"/api/runs/{before['id']}").json()
                assert after == before
                assert _events(c, before) == events[before["id"]]
                again = c.post(
                    "/api/plan",
                    json={
                        "scene": "demo",
                        **{
                            k: v
                            for k, v in before["request"].items()
                            if k in ("text", "formula", "start", "options")
                        },
                    },
                )
                assert again.json()["path"] == before["plan"]["path"]
                assert again.json()["cost_m"] == before["plan"]["cost_m"]
            # The restored runs go on where they were.
            active = made[1]
            rest = _poses(active["plan"]["waypoints"][12:])
            done = c.post(f"/api/runs/{active['id']}/observe", json={"poses": rest}).json()
            assert done["status"] == "done" and done["progress"]["poses"] == len(active["plan"]["waypoints"])
    finally:
        server.kill()
