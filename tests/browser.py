"""Headless Chromium for the tests of pages (the HTML report, the live page of ``sgplan serve``): the
system's Chromium (Debian's ``/usr/bin/chromium``), never a downloaded one, driven by Playwright."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

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
