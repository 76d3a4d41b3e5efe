"""Shared fixtures: the Gibson data folder (tests needing it skip cleanly when it is absent)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import settings

from sgplan.scene.cache import DIR_ENV, OFF_ENV
from tests import shared_data

# Property tests run a bounded number of examples so the suite stays well inside CI's budget.
settings.register_profile("ci", max_examples=60, deadline=None)
settings.register_profile("dev", max_examples=30, deadline=None)
settings.load_profile("ci")


@pytest.fixture(scope="session", autouse=True)
def _private_scene_cache(tmp_path_factory: pytest.TempPathFactory) -> None:
    """The on-disk scene cache (sgplan.scene.cache) of the test session: a fresh folder, never the user's
    (worker and CLI subprocesses inherit it)."""
    os.environ[DIR_ENV] = str(tmp_path_factory.mktemp("scene-cache"))
    os.environ.pop(OFF_ENV, None)


@pytest.fixture(scope="session")
def gibson_root() -> Path:
    """The Gibson data folder (:func:`tests.shared_data.gibson_root`: skips when absent)."""
    return shared_data.gibson_root()
