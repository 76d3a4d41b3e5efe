"""docs/serve.md's robot-side client runs against a real server with a token."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from tests.serve.conftest import ServerProcess
from tests.test_docs import REPO, python_blocks

pytestmark = pytest.mark.slow


def test_the_robot_client_of_serve_md_runs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (code,) = [code for _, code in python_blocks(REPO / "docs" / "serve.md") if "/api/runs" in code]
    token = "doc-example-token-0123456789"
    token_file = tmp_path / "token"
    token_file.write_text(token + "\n")
    token_file.chmod(0o600)
    server = ServerProcess(tmp_path / "state", "--token-file", str(token_file)).start()
    try:
        namespace: dict[str, Any] = {"URL": server.url, "TOKEN": token}
        exec(compile(code, "docs/serve.md", "exec"), namespace)  # the doc's own example code
    finally:
        server.kill()
    printed = capsys.readouterr().out.splitlines()
    assert printed[0] == "in-progress - left: go to the kitchen (room_4, floor 0)"
    assert printed[1].startswith("replanned: ") and "go to the kitchen (room_4, floor 0)" in printed[1]
