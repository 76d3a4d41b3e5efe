"""The mission service without HTTP: served scenes, missions understood, plans in a bounded pool, runs.

:class:`MissionService` is what every route calls (:mod:`sgplan.serve.app` only maps HTTP onto it), so
it can be driven from Python in tests and embedders the same way.
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from sgplan import __version__
from sgplan.serve.config import ServeConfig
from sgplan.serve.missions import MissionBook, checks_from_start
from sgplan.serve.planning import Budget, plan_on_host
from sgplan.serve.pool import WorkPool
from sgplan.serve.scenes import SceneRegistry
from sgplan.serve.views import overlays, scene_layers

if TYPE_CHECKING:
    from sgplan.serve.models import ExplainRequest, PlanRequest
    from sgplan.serve.runs import RunBook


@dataclass
class MissionService:
    """Everything one server holds: its configuration, the scenes, the missions understood lately, the
    plan pool and the runs."""

    config: ServeConfig
    scenes: SceneRegistry
    missions: MissionBook
    pool: WorkPool
    runs: RunBook

    @classmethod
    def start(cls, config: ServeConfig, scenes: SceneRegistry | None = None) -> MissionService:
        """Load the scenes (unless given), open the runs' database and bring back the runs it holds."""
        from sgplan.serve.runs import RunBook
        from sgplan.serve.store import RunStore

        if scenes is None:
            scenes = SceneRegistry.load(config.scenes, config.data, planners=config.plan_workers)
        missions = MissionBook()
        pool = WorkPool(config.plan_workers, config.plan_backlog)
        store = RunStore.open(config.database_url, config.state_dir)
        runs = RunBook(
            scenes,
            missions,
            pool,
            store,
            request_time_limit_s=config.request_time_limit_s,
            max_hot=config.hot_runs,
        )
        runs.restore()
        return cls(config, scenes, missions, pool, runs)

    def attach_loop(self) -> None:
        """Called when the server's event loop starts: run events are handed to their streams on it."""
        self.runs.attach_loop(asyncio.get_running_loop())

    def close(self) -> None:
        """Stop taking plans, wait for those running, close the database."""
        self.pool.shutdown()
        self.runs.close()

    def health(self) -> dict[str, Any]:
        return {
            "status": "ok",
            "version": __version__,
            "scenes": self.scenes.names(),
            "plans_in_flight": self.pool.in_flight,
            "plans_refused": self.pool.refused,
            "runs": self.runs.count(),
        }

    def layers(self, scene: str) -> dict[str, Any]:
        return scene_layers(self.scenes[scene])

    def explain(self, request: ExplainRequest) -> dict[str, Any]:
        """What the server understood of ``request`` (:class:`sgplan.serve.models.ExplainResponse`)."""
        host = self.scenes[request.scene]
        start = request.start.spec() if request.start is not None else None
        understood = self.missions.understand(host, request, start)
        checks = checks_from_start(host, understood, request) if request.start is not None else None
        return understood.record(host.name, checks)

    async def plan(self, request: PlanRequest) -> dict[str, Any]:
        """A one-shot plan in the pool: :meth:`sgplan.PlanResult.to_dict` (with ``request.view``:
        ``"overlays"``, one SVG per floor)."""
        host = self.scenes[request.scene]
        budget = Budget.of(self.config.request_time_limit_s)
        start = request.start.spec() if request.start is not None else None

        def job() -> dict[str, Any]:
            understood = self.missions.understand(host, request, start)
            result = plan_on_host(host, understood, request.start, request.options, budget)
            record = result.to_dict()
            if request.view:
                record["overlays"] = overlays(host, result.path, result.events)
            return record

        return await self.pool.run(job)
