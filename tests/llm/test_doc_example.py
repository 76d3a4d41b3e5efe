"""docs/llm.md's pytest example runs, with the fixtures it names (tests/llm/conftest.py)."""

from __future__ import annotations

from typing import Any

from tests.test_docs import REPO, python_blocks


def test_the_retry_example_of_llm_md_passes(fake_llm: Any, llm_client: Any) -> None:
    (code,) = [code for _, code in python_blocks(REPO / "docs" / "llm.md") if "def test_retry(" in code]
    namespace: dict[str, Any] = {}
    exec(compile(code, "docs/llm.md", "exec"), namespace)  # the doc's own example code
    namespace["test_retry"](fake_llm, llm_client)
