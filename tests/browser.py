"""Headless Chromium for the tests of pages (the HTML report, the live page of ``sgplan serve``): the
system's Chromium (Debian's ``/usr/bin/chromium``), never a downloaded one, driven by Playwright."""

from __future__ import annotations

import os
import shutil
from pathlib import Path
from typing import Any

import pytest

BROWSER_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]


def browser() -> tuple[object, str]:
    """Playwright's sync API and a Chromium executable, or skip saying what is missing."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        pytest.skip("the Python package playwright is not installed (pip install -e '.[test]')")
    candidates = [
        os.environ.get("SGPLAN_CHROMIUM"),
        "/usr/bin/chromium",
        shutil.which("chromium"),
        shutil.which("chromium-browser"),
        shutil.which("google-chrome"),
    ]
    executable = next((c for c in candidates if c and Path(c).is_file()), None)
    if executable is None:
        pytest.skip(
            "no Chromium found (apt-get install chromium, or set SGPLAN_CHROMIUM); "
            ".ci/run installs it when run as root"
        )
    return sync_playwright, executable


def launch(playwright: Any, executable: str) -> Any:
    """Headless Chromium from ``executable``, or skip the test when it does not start."""
    try:
        return playwright.chromium.launch(executable_path=executable, args=BROWSER_FLAGS, headless=True)
    except Exception as error:  # noqa: BLE001 - any launch failure means "no usable browser here"
        pytest.skip(f"Chromium at {executable} did not start: {str(error).splitlines()[0]}")


def watch(page: Any, *, quiet_failures: tuple[str, ...] = ()) -> list[str]:
    """The problems ``page`` runs into, as they happen: console errors and warnings, script errors,
    failed requests (but those whose URL ends with one of ``quiet_failures``: requests the page itself
    ends, such as an event stream it closes)."""
    problems: list[str] = []
    page.on(
        "console",
        lambda m: problems.append(f"console {m.type}: {m.text}") if m.type in ("error", "warning") else None,
    )
    page.on("pageerror", lambda e: problems.append(f"page error: {e}"))
    page.on(
        "requestfailed",
        lambda r: (
            None
            if r.url.endswith(quiet_failures)
            else problems.append(f"request failed: {r.url} {r.failure}")
        ),
    )
    return problems
