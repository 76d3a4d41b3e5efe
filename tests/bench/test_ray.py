"""The Ray executor gives the local executor's results (skipped when Ray is not installed)."""

from __future__ import annotations

import pytest

from sgplan.bench.cases import Case
from sgplan.bench.executors import RayExecutor
from sgplan.bench.results import ResultStore


def test_ray_executor_gives_identical_costs(swept: tuple[list[Case], ResultStore]) -> None:
    ray = pytest.importorskip("ray")
    cases, store = swept
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        rows = {r["key"]: r for r in RayExecutor(timeout_s=300).run(cases)}
    finally:
        ray.shutdown()
    assert set(rows) == {c.key for c in cases}
    for case in cases:
        local, remote = store.get(case.key), rows[case.key]
        assert remote["executor"] == "ray" and remote["status"] == local["status"]
        assert remote["cost_m"] == local["cost_m"] and remote.get("first_cost_m") == local.get("first_cost_m")
        assert remote.get("reason") == local.get("reason")
