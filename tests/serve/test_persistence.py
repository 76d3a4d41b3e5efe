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
                run = c.post(
                    "/api/runs", json={"scene": "demo", **mission, "start": start, "options": {"setup": "A*"}}
                ).json()
                waypoints = run["plan"]["waypoints"]
                if k == 0:
                    c.post(
                        f"/api/runs/{run['id']}/changes",
                        json={"changes": [{"kind": "close_door", "rooms": ["room_2", "room_4"]}]},
                    )
                if k == 1:
                    c.post(f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints[1:7])})
                    c.post(f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints[7:12])})
                    c.post(f"/api/runs/{run['id']}/amend", json={"text": "also go to the dining room"})
                    driven_to = [waypoints[11][key] for key in ("row", "col", "floor")]
                if k == 2:
                    c.post(f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints[1:])})
                if k == 3:
                    c.post(f"/api/runs/{run['id']}/cancel")
                made.append(c.get(f"/api/runs/{run['id']}").json())
            events = {run["id"]: _events(c, run) for run in made}
        assert [r["status"] for r in made] == ["impossible", "in-progress", "done", "cancelled"]
        assert made[0]["changes"] and made[1]["amendments"] and made[1]["position"] == driven_to
        server.kill()

        server.start()
        with httpx.Client(base_url=server.url, timeout=60) as c:
            assert c.get("/api/health").json()["runs"] == len(made)
            for before in made:
                assert c.get(f"/api/runs/{before['id']}").json() == before
                assert _events(c, before) == events[before["id"]]
            # The open runs plan the same from where they stand: still impossible (the closed door was the
            # kitchen's way out but through the forbidden bathroom), the other on the rest of its path.
            impossible = c.post(f"/api/runs/{made[0]['id']}/replan").json()
            assert impossible["status"] == "impossible" and impossible["why"] == made[0]["why"]
            before = made[1]
            again = c.post(f"/api/runs/{before['id']}/replan").json()
            assert again["plan"]["path"] == before["plan"]["path"][before["plan_offset"] :]
            assert again["position"] == before["position"] and again["state"] == before["state"]
            # and go on where they were.
            active = c.get(f"/api/runs/{made[1]['id']}").json()
            rest = _poses(active["plan"]["waypoints"][1:])
            done = c.post(f"/api/runs/{active['id']}/observe", json={"poses": rest}).json()
            assert done["run"]["status"] == "done"
    finally:
        server.kill()
