"""The planned demo mission as a fixture for the report tests."""

from __future__ import annotations

import pytest

from tests.plans import DemoPlan
from tests.plans import demo_plan as _demo_plan


@pytest.fixture(scope="session")
def demo_plan() -> DemoPlan:
    return _demo_plan()
