"""Who gets in: loopback by default, a token for anything else (checked in constant time on every
request), the token file's permissions, no CORS unless configured, unknown routes in the JSON shape."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from sgplan.serve.config import ServeConfig, ServeError, is_loopback, read_token_file
from sgplan.serve.scenes import SceneRegistry
from tests.serve.conftest import SERVE_DEMO, make_client

TOKEN = "s3cret-token-of-the-test-0123456789"


@pytest.fixture(scope="module")
def guarded(demo_scenes: SceneRegistry, tmp_path_factory: pytest.TempPathFactory) -> TestClient:
    with make_client(demo_scenes, tmp_path_factory.mktemp("state"), token=TOKEN, host="0.0.0.0") as c:
        yield c


def test_every_request_needs_the_token(guarded: TestClient) -> None:
    for path in ("/", "/api/scenes", "/assets/page.js", "/docs", "/openapi.json", "/api/runs/x/events"):
        response = guarded.get(path)
        assert response.status_code == 401, path
        assert response.headers["www-authenticate"] == "Bearer"
        assert "carried no token" in response.json()["error"]["message"]
    wrong = guarded.get("/api/scenes", headers={"Authorization": "Bearer " + TOKEN[:-1] + "x"})
    assert "a wrong token" in wrong.json()["error"]["message"]
    assert guarded.get("/api/scenes", headers={"Authorization": "Bearer " + TOKEN}).status_code == 200
    assert guarded.get("/api/scenes", headers={"Authorization": "bearer " + TOKEN}).status_code == 200
    # A browser opens the page with ?token=...; event streams carry it so too. Never a POST.
    assert guarded.get("/?token=" + TOKEN).status_code == 200
    body = {"scene": "demo", "text": "Go to the kitchen."}
    assert guarded.post("/api/explain?token=" + TOKEN, json=body).status_code == 401
    assert (
        guarded.post("/api/explain", json=body, headers={"Authorization": "Bearer " + TOKEN}).status_code
        == 200
    )


def test_other_addresses_refuse_to_start_without_a_token(tmp_path: Path) -> None:
    assert is_loopback("127.0.0.1") and is_loopback("::1") and is_loopback("localhost")
    assert not is_loopback("0.0.0.0") and not is_loopback("192.168.1.5") and not is_loopback("example.org")
    with pytest.raises(ServeError, match=r"refusing to listen on 0\.0\.0\.0 without a token"):
        ServeConfig(scenes=("demo",), host="0.0.0.0").checked()
    with pytest.raises(ServeError, match="use at least 16"):
        ServeConfig(scenes=("demo",), token="short").checked()
    ServeConfig(scenes=("demo",), host="0.0.0.0", token=TOKEN).checked()
    done = subprocess.run(
        [
            *SERVE_DEMO,
            "--host",
            "0.0.0.0",
            "--state",
            str(tmp_path),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2 and done.stderr.strip().splitlines()[-1].startswith(
        "sgplan: error: refusing to listen on 0.0.0.0 without a token"
    )
    assert list(tmp_path.iterdir()) == []  # nothing was written


def test_the_token_file_must_be_private(tmp_path: Path) -> None:
    path = tmp_path / "token"
    path.write_text(TOKEN + "\n")
    path.chmod(0o644)
    with pytest.raises(ServeError, match="may be read by others; chmod 600"):
        read_token_file(path)
    path.chmod(0o600)
    assert read_token_file(path) == TOKEN
    path.write_text("\n")
    with pytest.raises(ServeError, match="is empty"):
        read_token_file(path)
    with pytest.raises(ServeError, match="token file"):
        read_token_file(tmp_path / "missing")


def test_no_cors_unless_configured(client: TestClient, demo_scenes: SceneRegistry, tmp_path: Path) -> None:
    asked = {"Origin": "http://elsewhere.example", "Access-Control-Request-Method": "POST"}
    assert "access-control-allow-origin" not in client.options("/api/plan", headers=asked).headers
    assert "access-control-allow-origin" not in client.get("/api/scenes", headers=asked).headers
    with make_client(demo_scenes, tmp_path, cors_origins=("http://fleet.example",)) as c:
        allowed = c.options("/api/plan", headers={**asked, "Origin": "http://fleet.example"})
        assert allowed.headers["access-control-allow-origin"] == "http://fleet.example"
        assert "access-control-allow-origin" not in c.options("/api/plan", headers=asked).headers


def test_unknown_routes_and_methods_answer_in_the_json_shape(client: TestClient) -> None:
    missing = client.get("/api/nothing").json()["error"]
    assert missing["status"] == 404 and "described at /docs" in missing["message"]
    assert client.delete("/api/scenes").json()["error"]["status"] == 405


def test_state_stays_in_the_state_folder(client: TestClient, tmp_path: Path) -> None:
    """Requests name scenes, never paths, and nothing they carry names a file: the only file the server
    writes is its database, in its state folder."""
    before = set(Path.cwd().iterdir())
    client.post(
        "/api/runs", json={"scene": "demo", "text": "Go to the kitchen.", "start": {"room": "../../etc"}}
    )
    client.post("/api/plan", json={"scene": "../../../tmp/x", "text": "Go to the kitchen."})
    assert set(Path.cwd().iterdir()) == before
    state = Path(client.app.state.service.config.state_dir)  # type: ignore[attr-defined]
    assert {p.name for p in state.iterdir()} <= {"runs.sqlite", "runs.sqlite-wal", "runs.sqlite-shm"}
    assert os.stat(state).st_mode & 0o077 == 0
