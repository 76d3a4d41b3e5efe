"""Fixtures of the service's tests: one demo-scene service per module (its scene loaded and warm), a
client talking to it in process, and a helper that runs the real server as a subprocess."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

pytest.importorskip("fastapi", reason="the serve extra is not installed (pip install 'sgplan[serve]')")

from fastapi.testclient import TestClient

from sgplan.serve.app import create_app
from sgplan.serve.config import ServeConfig
from sgplan.serve.scenes import SceneRegistry
from sgplan.serve.service import MissionService

SERVE_DEMO = (sys.executable, "-m", "sgplan.cli", "serve", "--scene", "demo")
"""The command line that serves the demo scene (more options follow)."""
KITCHEN_TEXT = "Go to the kitchen, then the bedroom with the clock. Always avoid the bathroom on floor 0."


@pytest.fixture(scope="session")
def demo_scenes() -> SceneRegistry:
    """The demo scene loaded and warm once for every test of the session (services share it)."""
    return SceneRegistry.load(["demo"])


def make_client(scenes: SceneRegistry, state: Path, **settings: object) -> TestClient:
    config = ServeConfig(scenes=("demo",), state_dir=state, **settings)  # type: ignore[arg-type]
    return TestClient(create_app(service=MissionService.start(config.checked(), scenes)))


@pytest.fixture(scope="module")
def client(demo_scenes: SceneRegistry, tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    with make_client(demo_scenes, tmp_path_factory.mktemp("state")) as c:
        yield c


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class ServerProcess:
    """``sgplan serve`` as a child process on a free loopback port (:meth:`start`, :meth:`kill`)."""

    def __init__(self, state: Path, *extra: str) -> None:
        self.state, self.extra = state, extra
        self.port = free_port()
        self.process: subprocess.Popen[bytes] | None = None
        self.url = f"http://127.0.0.1:{self.port}"

    def start(self, timeout_s: float = 120.0) -> ServerProcess:
        import httpx

        command = [
            *SERVE_DEMO,
            "--port",
            str(self.port),
            "--state",
            str(self.state),
            *self.extra,
        ]
        self.process = subprocess.Popen(
            command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=os.environ.copy()
        )
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise AssertionError(f"the server exited: {self.process.stderr.read().decode()[-2000:]}")  # type: ignore[union-attr]
            try:
                if httpx.get(self.url + "/api/health", timeout=1.0).status_code in (200, 401):
                    return self
            except httpx.TransportError:
                time.sleep(0.2)
        self.kill()
        raise AssertionError("the server did not answer within the time limit")

    def kill(self) -> None:
        """SIGKILL: no shutdown handler runs."""
        if self.process is not None and self.process.poll() is None:
            self.process.kill()
            self.process.wait(timeout=30)
