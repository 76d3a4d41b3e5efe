"""The service's JSON API: every route, the answers' shapes, and every error status with its message."""

from __future__ import annotations

import io
import json
import threading
import time
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from PIL import Image

import sgplan
from sgplan.limits import MAX_MISSION_TEXT_CHARS, MAX_POSES_PER_BATCH, MAX_REQUEST_BYTES
from sgplan.serve.scenes import SceneRegistry
from tests.planning.oracle import optimal_cost
from tests.serve.conftest import KITCHEN_TEXT, make_client

FORMULA = 'F("enter(room_4)" & F "enter(room_11)") & G !"enter(room_5)"'


def error_of(response: object, status: int) -> dict[str, object]:
    assert response.status_code == status, response.text  # type: ignore[attr-defined]
    body = response.json()["error"]  # type: ignore[attr-defined]
    assert body["status"] == status and "\n" not in body["message"]
    return body


# -- scenes ----------------------------------------------------------------------------------------------


def test_scenes_are_listed_and_summarised_with_their_doors(client: TestClient) -> None:
    assert client.get("/api/scenes").json() == [
        {"name": "demo-house", "floors": 2, "rooms": 11, "objects": 28}
    ]
    summary = client.get("/api/scenes/DEMO").json()  # the configured name or the building's, any case
    assert summary["name"] == "demo-house" and len(summary["floors"]) == 2
    doors = {tuple(d["rooms"]): d for d in summary["doors"]}
    door = doors[("room_2", "room_4")]  # corridor - kitchen
    assert door["names"] == ["corridor", "kitchen"] and door["floor"] == 0
    building = sgplan.load_scene("demo")
    assert building.floors[0].room_map[door["row"], door["col"]] in (2, 4)  # the door cell is in one of them
    picture = client.get("/api/scenes/demo-house/floors/1.png")
    assert picture.headers["content-type"] == "image/png"
    with Image.open(io.BytesIO(picture.content)) as image:
        assert image.size == building.floors[1].shape[::-1]


def test_unknown_scene_and_floor_are_404_naming_what_exists(client: TestClient) -> None:
    body = error_of(client.get("/api/scenes/Atlantis"), 404)
    assert "unknown scene 'Atlantis'" in body["message"] and "demo-house" in body["message"]
    assert "floors are 0, 1" in error_of(client.get("/api/scenes/demo/floors/7.png"), 404)["message"]
    # A path is never a scene: only the server's own scenes are served.
    error_of(client.post("/api/plan", json={"scene": "/etc", "formula": FORMULA}), 404)


def test_layers_are_the_reports_floors(client: TestClient) -> None:
    layers = client.get("/api/scenes/demo/layers").json()
    assert layers["html"].count('class="floor"') == 2 and 'class="ids rooms"' in layers["html"]
    rooms = json.loads(layers["entities"])["rooms"].values()
    assert {"name": "kitchen", "key": "room_4", "floor": 0}.items() <= next(
        r for r in rooms if r["key"] == "room_4"
    ).items()


# -- explain ---------------------------------------------------------------------------------------------


def test_explain_says_back_text_with_entities_named_and_checks(client: TestClient) -> None:
    answer = client.post("/api/explain", json={"scene": "demo", "text": KITCHEN_TEXT}).json()
    assert "Go to the kitchen (room_4, floor 0)" in answer["explanation"]
    assert "Never enter the bathroom (room_5, floor 0)" in answer["explanation"]
    assert answer["formula"] == FORMULA and answer["method"] == "patterns" and answer["scene_check"] == []
    same = client.post("/api/explain", json={"scene": "demo", "formula": FORMULA}).json()
    assert same["explanation"] == answer["explanation"]


def test_explain_runs_the_start_checks_when_given_a_start(client: TestClient) -> None:
    answer = client.post(
        "/api/explain", json={"scene": "demo", "formula": FORMULA, "start": {"room": "bathroom on floor 0"}}
    ).json()
    assert [f["kind"] for f in answer["scene_check"]] == ["unsatisfiable-from-start"]
    contradiction = client.post(
        "/api/explain", json={"scene": "demo", "formula": 'F "enter(room_4)" & G !"enter(room_4)"'}
    ).json()
    assert contradiction["scene_check"][0]["kind"] == "unsatisfiable"


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ({"scene": "demo", "text": "Go to the gym."}, "no room or object of this scene is called 'gym'"),
        ({"scene": "demo", "formula": 'F "enter(room_999)"'}, "room_999"),
        ({"scene": "demo", "formula": "F (("}, "formula"),
        ({"scene": "demo", "text": "x", "formula": "F a"}, "give exactly one of text"),
        ({"scene": "demo", "text": "   "}, "the mission is blank"),
        ({"scene": "demo", "text": "a" * (MAX_MISSION_TEXT_CHARS + 1)}, "field text"),
        (
            {"scene": "demo", "formula": FORMULA, "start": {"room": "kitchen", "index": 0}},
            "exactly one of cell",
        ),
        ({"scene": "demo", "formula": FORMULA, "options": {"setup": "FAST"}}, "field options.setup"),
        ({"scene": "demo", "formula": FORMULA, "colour": "red"}, "field colour"),
    ],
)
def test_bad_missions_are_422_with_one_line(client: TestClient, body: dict[str, object], words: str) -> None:
    assert words in str(error_of(client.post("/api/explain", json=body), 422)["message"])


# -- plan ------------------------------------------------------------------------------------------------


def test_plan_is_the_cli_json_and_optimal(client: TestClient) -> None:
    start = {"room": "room_13"}
    record = client.post(
        "/api/plan", json={"scene": "demo", "formula": FORMULA, "start": start, "options": {"setup": "A*"}}
    ).json()
    building = sgplan.load_scene("demo")
    mission = sgplan.mission_from_formula(FORMULA, building)
    direct = sgplan.plan(building, mission, start="room_13", setup="A*").to_dict()
    assert set(record) == set(direct)
    for key in ("status", "cost_m", "path", "start", "events", "explanation", "scene_check", "formula"):
        assert record[key] == direct[key] if key != "formula" else record["mission"] == direct["mission"]
    session = sgplan.Session(building)
    oracle = optimal_cost(session.grid(), session.labels(mission), mission.automaton, tuple(record["start"]))
    assert record["status"] == "optimal" and record["cost_m"] == pytest.approx(oracle, abs=1e-9)


def test_plan_with_view_returns_one_overlay_per_floor(client: TestClient) -> None:
    record = client.post(
        "/api/plan", json={"scene": "demo", "text": KITCHEN_TEXT, "view": True, "start": {"room": "kitchen"}}
    ).json()
    overlays = record["overlays"]
    assert len(overlays) == 2 and all(o.startswith("<svg") for o in overlays)
    assert (
        'class="start"' in overlays[0] and 'class="end"' in overlays[1]
    )  # kitchen, then the bedroom upstairs


def test_plan_errors_carry_the_plan_status(client: TestClient) -> None:
    start_in_forbidden = {"scene": "demo", "formula": FORMULA, "start": {"room": "bathroom on floor 0"}}
    assert error_of(client.post("/api/plan", json=start_in_forbidden), 422)["plan_status"] == "invalid-start"
    never = {"scene": "demo", "formula": 'F "enter(room_4)" & G !"enter(room_4)"'}
    assert error_of(client.post("/api/plan", json=never), 422)["plan_status"] == "unsatisfiable"
    wall = error_of(
        client.post("/api/plan", json={"scene": "demo", "formula": FORMULA, "start": {"cell": [0, 0, 0]}}),
        422,
    )
    assert "row 0" in str(wall["message"]) or "(0, 0" in str(wall["message"])


def test_a_budget_of_the_request_returns_the_best_path_so_far(client: TestClient) -> None:
    record = client.post(
        "/api/plan",
        json={
            "scene": "demo",
            "formula": FORMULA,
            "start": {"room": "kitchen"},
            "options": {"setup": "ALL", "max_expansions": 1},
        },
    ).json()
    assert record["status"] == "timeout"


def test_the_server_time_limit_answers_408_with_retry_after(
    demo_scenes: SceneRegistry, tmp_path: Path
) -> None:
    with make_client(demo_scenes, tmp_path, request_time_limit_s=1e-9) as c:
        response = c.post(
            "/api/plan", json={"scene": "demo", "formula": FORMULA, "start": {"room": "kitchen"}}
        )
        assert "time limit" in str(error_of(response, 408)["message"])
        assert response.headers["Retry-After"] == "1"


def test_a_full_pool_answers_503_with_retry_after(demo_scenes: SceneRegistry, tmp_path: Path) -> None:
    with make_client(demo_scenes, tmp_path, plan_workers=1, plan_backlog=0) as c:
        host = demo_scenes["demo"]
        body = {"scene": "demo", "formula": FORMULA, "start": {"room": "kitchen"}}
        first: list[int] = []
        with host.planner():  # the one worker waits for the scene's one session: the pool is full
            waiting = threading.Thread(
                target=lambda: first.append(c.post("/api/plan", json=body).status_code)
            )
            waiting.start()
            while c.get("/api/health").json()["plans_in_flight"] < 1:
                time.sleep(0.01)
            refused = c.post("/api/plan", json=body)
            assert "busy" in str(error_of(refused, 503)["message"]) and refused.headers["Retry-After"] == "1"
            # The rest of the service still answers while the worker waits.
            assert c.post("/api/explain", json=body).status_code == 200
        waiting.join()
        assert first == [200] and c.get("/api/health").json()["plans_refused"] == 1


def test_oversized_bodies_are_413(client: TestClient) -> None:
    big = json.dumps({"poses": [[1.0, 1.0, 0]] * (MAX_REQUEST_BYTES // 10)})
    assert len(big) > MAX_REQUEST_BYTES
    body = error_of(
        client.post("/api/runs/x/observe", content=big, headers={"content-type": "application/json"}), 413
    )
    assert "larger than" in str(body["message"])

    def chunks() -> object:  # no Content-Length: counted as it streams
        for _ in range(MAX_REQUEST_BYTES // 65536 + 2):
            yield b" " * 65536

    error_of(client.post("/api/explain", content=chunks(), headers={"content-type": "application/json"}), 413)


# -- runs ------------------------------------------------------------------------------------------------


def _poses(waypoints: list[dict[str, float]]) -> list[list[float]]:
    return [[w["x_m"], w["y_m"], w["floor"]] for w in waypoints]


def _events(client: TestClient, run_id: str, count: int, last: int = 0) -> list[tuple[str, str]]:
    """The first ``count`` events of the run's stream after ``last``, as (id, kind)."""
    seen: list[tuple[str, str]] = []
    with client.stream("GET", f"/api/runs/{run_id}/events", headers={"Last-Event-ID": str(last)}) as stream:
        event_id = ""
        for line in stream.iter_lines():
            if line.startswith("id:"):
                event_id = line.split(": ", 1)[1]
            elif line.startswith("event:"):
                seen.append((event_id, line.split(": ", 1)[1]))
                if len(seen) == count:
                    break
    return seen


def test_a_run_follows_its_robot_to_done_and_streams_its_events(client: TestClient) -> None:
    created = client.post(
        "/api/runs",
        json={
            "scene": "demo",
            "text": KITCHEN_TEXT,
            "start": {"room": "kitchen"},
            "options": {"setup": "A*"},
        },
    )
    assert created.status_code == 201
    run = created.json()
    assert run["status"] == "in-progress" and run["plan"]["status"] == "optimal"
    # The start is in the kitchen already: what is left says so.
    assert run["left"] == "go to the bedroom (room_11, floor 1); never enter the bathroom (room_5, floor 0)"
    waypoints = run["plan"]["waypoints"]
    half = client.post(
        f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints[1 : len(waypoints) // 2])}
    )
    answer = half.json()
    assert (
        answer["monitor"]["verdict"] == "in-progress"
        and answer["run"]["plan_offset"] == len(waypoints) // 2 - 1
    )
    rest = client.post(
        f"/api/runs/{run['id']}/observe", json={"poses": _poses(waypoints[len(waypoints) // 2 :])}
    )
    assert rest.json()["run"]["status"] == "done" and rest.json()["monitor"]["verdict"] == "done"
    got = client.get(f"/api/runs/{run['id']}").json()
    assert {k: v for k, v in got.items() if k != "plan"} | {
        "plan_cost_m": got["plan"]["cost_m"]
    } == rest.json()["run"]
    assert got["position"] == [waypoints[-1]["row"], waypoints[-1]["col"], waypoints[-1]["floor"]]
    assert {
        "id": run["id"],
        "scene": "demo-house",
        "status": "done",
        "poses": got["monitor"]["poses"],
    } in client.get("/api/runs").json()
    # Progress events come when the mission moves on: here only at the end.
    assert _events(client, run["id"], got["events"]) == [("1", "replanned"), ("2", "done")]
    # A reconnecting client gets what it missed.
    assert _events(client, run["id"], 1, last=1) == [("2", "done")]
    assert "has ended (done)" in str(error_of(client.post(f"/api/runs/{run['id']}/cancel"), 409)["message"])


def _kitchen_run(client: TestClient) -> dict[str, Any]:
    """A run to the kitchen from the dining room (A*)."""
    body = {
        "scene": "demo",
        "formula": 'F "enter(room_4)"',
        "start": {"room": "room_7"},
        "options": {"setup": "A*"},
    }
    return dict(client.post("/api/runs", json=body).json())


def test_a_closed_door_replans_the_run_and_a_bad_change_changes_nothing(client: TestClient) -> None:
    run = _kitchen_run(client)
    before = run["plan"]["cost_m"]
    closed = client.post(
        f"/api/runs/{run['id']}/changes",
        json={"changes": [{"kind": "close_door", "rooms": ["corridor on floor 0", "kitchen"]}]},
    ).json()
    assert closed["changes"] == [{"kind": "close_door", "rooms": ["corridor on floor 0", "kitchen"]}]
    assert closed["plan"]["cost_m"] > before  # the kitchen's other door is farther
    door = next(
        d for d in client.get("/api/scenes/demo").json()["doors"] if d["rooms"] == ["room_2", "room_4"]
    )
    assert [door["row"], door["col"], 0] not in [p[:3] for p in closed["plan"]["path"]]
    bad = client.post(
        f"/api/runs/{run['id']}/changes",
        json={
            "changes": [
                {"kind": "open_door", "rooms": ["corridor on floor 0", "kitchen"]},
                {"kind": "close_door", "rooms": ["corridor", "gym"]},
            ]
        },
    )
    assert "change 2" in str(error_of(bad, 422)["message"])
    assert client.get(f"/api/runs/{run['id']}").json() == closed  # all or none
    refused = client.post(
        f"/api/runs/{run['id']}/changes", json={"changes": [{"kind": "scene_graph", "scene": "/etc"}]}
    )
    assert "not taken over HTTP" in str(error_of(refused, 422)["message"])
    reopened = client.post(
        f"/api/runs/{run['id']}/changes",
        json={"changes": [{"kind": "open_door", "rooms": ["corridor on floor 0", "kitchen"]}]},
    ).json()
    assert reopened["plan"]["cost_m"] == pytest.approx(before)


def test_amendments_replan_or_are_refused_with_409(client: TestClient) -> None:
    run = _kitchen_run(client)
    refused = client.post(f"/api/runs/{run['id']}/amend", json={"text": "always avoid the kitchen"})
    body = error_of(refused, 409)
    assert "never enter the kitchen (room_4, floor 0)" in str(body["message"]).lower()
    assert body["plan_status"] == "unsatisfiable"
    amended = client.post(
        f"/api/runs/{run['id']}/amend", json={"text": "also go to the bathroom on floor 0"}
    ).json()
    assert amended["amendments"] == ["also go to the bathroom on floor 0"]
    assert (
        "bathroom (room_5, floor 0)" in amended["left"] and amended["plan"]["cost_m"] > run["plan"]["cost_m"]
    )


def test_a_run_that_breaks_the_mission_is_violated(client: TestClient) -> None:
    run = client.post(
        "/api/runs",
        json={"scene": "demo", "formula": FORMULA, "start": {"room": "kitchen"}, "options": {"setup": "A*"}},
    ).json()
    building = sgplan.load_scene("demo")
    bathroom = next(r for r in building.rooms() if r.key == "room_5")
    x, y = bathroom.location_m[:2]
    answer = client.post(f"/api/runs/{run['id']}/observe", json={"poses": [[float(x), float(y), 0]]}).json()
    assert answer["run"]["status"] == "violated" and answer["monitor"]["verdict"] == "violated"
    assert "never enter the bathroom (room_5, floor 0)" in answer["monitor"]["violation"]["text"]


def test_run_errors(client: TestClient) -> None:
    assert "unknown run" in str(error_of(client.get("/api/runs/nope"), 404)["message"])
    error_of(client.post("/api/runs/nope/observe", json={"poses": [[0.0, 0.0, 0]]}), 404)
    run = client.post(
        "/api/runs",
        json={"scene": "demo", "formula": FORMULA, "start": {"room": "kitchen"}, "options": {"setup": "A*"}},
    ).json()
    off = client.post(f"/api/runs/{run['id']}/observe", json={"poses": [[1e6, 0.0, 0]]})
    error_of(off, 422)
    error_of(client.post(f"/api/runs/{run['id']}/observe", json={"poses": [[0.0, 0.0, 5]]}), 422)
    too_many = {"poses": [[0.0, 0.0, 0]] * (MAX_POSES_PER_BATCH + 1)}
    assert "field poses" in str(
        error_of(client.post(f"/api/runs/{run['id']}/observe", json=too_many), 422)["message"]
    )
    assert client.get(f"/api/runs/{run['id']}").json() == run  # refused batches change nothing
    assert client.post(f"/api/runs/{run['id']}/cancel").json()["status"] == "cancelled"
    error_of(client.post(f"/api/runs/{run['id']}/observe", json={"poses": [[0.0, 0.0, 0]]}), 409)
    error_of(client.post(f"/api/runs/{run['id']}/amend", json={"text": "also go to the kitchen"}), 409)


def test_the_openapi_description_lists_every_route(client: TestClient) -> None:
    paths = client.get("/openapi.json").json()["paths"]
    for path in (
        "/api/scenes",
        "/api/explain",
        "/api/plan",
        "/api/runs",
        "/api/runs/{run_id}/observe",
        "/api/runs/{run_id}/changes",
        "/api/runs/{run_id}/amend",
        "/api/runs/{run_id}/cancel",
        "/api/runs/{run_id}/events",
    ):
        assert path in paths
    assert client.get("/docs").status_code == 200


def test_the_page_and_its_assets_are_served_and_nothing_else(client: TestClient) -> None:
    page = client.get("/").text
    assert '<script src="/assets/page.js">' in page and "http" not in page.replace("http-equiv", "")
    for name in ("page.js", "page.css", "report.js", "report.css"):
        assert client.get(f"/assets/{name}").status_code == 200
    error_of(client.get("/assets/..%2Fapp.py"), 404)
    error_of(client.get("/assets/app.py"), 404)


def test_kept_missions_are_understood_once(client: TestClient) -> None:
    book = client.app.state.service.missions  # type: ignore[attr-defined]
    text = "Go to the dining room."
    client.post("/api/explain", json={"scene": "demo", "text": text})
    made = book.made
    client.post("/api/explain", json={"scene": "demo", "text": text})
    client.post("/api/plan", json={"scene": "demo", "text": text, "start": {"room": "kitchen"}})
    assert book.made == made
