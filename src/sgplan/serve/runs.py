"""Runs: missions being carried out, kept in the database, their events streamed.

A run is created from a mission and a start (planned at once, in the plan pool), then follows its
robot: ``observe`` reads the poses it reports (:mod:`sgplan.serve.progress`), ``cancel`` ends it. Every
change of a run is one transaction in the store (its record and its new events), then its events go to
the run's streams. After a restart :meth:`RunBook.restore` brings every run back from the database as
it was at its last committed change.

The record of a run (``GET /api/runs/{id}``): ``id``, ``scene``, ``status`` (``active``, ``done``,
``violated``, ``cancelled``), ``request`` (mission, start, options as given), ``plan`` (the JSON of
``sgplan plan --json``), ``progress``, ``left_to_do``, ``events`` (how many).
"""

from __future__ import annotations

import asyncio
import secrets
import threading
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from sgplan.errors import SgplanError
from sgplan.serve.errors import HTTPProblem, not_found
from sgplan.serve.models import RunRequest
from sgplan.serve.planning import Deadline, plan_on_host
from sgplan.serve.progress import DONE, VIOLATED, Progress, advance, left_to_do, start_progress
from sgplan.serve.streams import MAX_STREAMS_PER_RUN, EventHub, RunEvent
from sgplan.serve.views import overlays

if TYPE_CHECKING:
    from starlette.requests import Request
    from starlette.responses import Response

    from sgplan.serve.missions import MissionBook, Understood
    from sgplan.serve.models import ObserveRequest
    from sgplan.serve.pool import WorkPool
    from sgplan.serve.scenes import SceneHost, SceneRegistry
    from sgplan.serve.store import RunStore

ACTIVE, CANCELLED = "active", "cancelled"


@dataclass
class LiveRun:
    """A run held in memory: what it was asked, its plan and progress, and its place in the store."""

    id: str
    host: SceneHost
    understood: Understood
    request: dict[str, Any]
    plan: dict[str, Any]
    progress: Progress
    status: str
    version: int = 1
    seq: int = 0
    lock: threading.Lock = field(default_factory=threading.Lock)
    _labels: np.ndarray | None = None

    def record(self) -> dict[str, Any]:
        """What the store keeps of the run (all that :meth:`RunBook.restore` needs)."""
        return {
            "request": self.request,
            "plan": self.plan,
            "progress": self.progress.to_dict(),
            "seq": self.seq,
        }

    def public(self, view: bool = False) -> dict[str, Any]:
        """The run as ``GET /api/runs/{id}`` answers."""
        answer = {
            "id": self.id,
            "scene": self.host.name,
            "status": self.status,
            "request": self.request,
            "plan": self.plan,
            "progress": self.progress.to_dict(),
            "left_to_do": self.left(self.progress),
            "events": self.seq,
        }
        if view:
            answer["overlays"] = overlays(self.host, self.plan.get("path"))
        return answer

    def summary(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "scene": self.host.name,
            "status": self.status,
            "verdict": self.progress.verdict,
            "poses": self.progress.poses,
        }

    def left(self, progress: Progress) -> list[str]:
        """What is left to do from ``progress`` along the plan, entities named as people name them."""
        from sgplan.explain import entity_of

        propositions, building = self.understood.mission.propositions, self.host.building
        return left_to_do(
            self.plan.get("events", []),
            progress,
            lambda name: entity_of(name, propositions.get(name), building).phrase(),
        )

    def labels(self) -> np.ndarray:
        """The mission's label raster at the plan's reach radius (from the scene's warm session)."""
        if self._labels is None:
            reach = self.plan["radii"]["reach_m"]
            self._labels = self.host.session.labels(self.understood.mission, reach)
        return self._labels

    def event(self, kind: str, data: dict[str, Any]) -> RunEvent:
        self.seq += 1
        return RunEvent(self.seq, kind, data)


class RunBook:
    """Every run of the server, by id; see the module docstring."""

    def __init__(
        self,
        scenes: SceneRegistry,
        missions: MissionBook,
        pool: WorkPool,
        store: RunStore,
        *,
        request_time_limit_s: float,
    ) -> None:
        self.scenes = scenes
        self.missions = missions
        self.pool = pool
        self.store = store
        self.request_time_limit_s = request_time_limit_s
        self.hub = EventHub()
        self._runs: dict[str, LiveRun] = {}
        self._lock = threading.Lock()

    def attach_loop(self, loop: asyncio.AbstractEventLoop) -> None:
        self.hub.attach(loop)

    def count(self) -> int:
        return len(self._runs)

    def restore(self) -> int:
        """Bring back every run of the store whose scene this server serves; returns how many."""
        for stored in self.store.load_all():
            host = self.scenes[stored.scene]
            request = RunRequest.model_validate(stored.record["request"])
            understood = self.missions.understand(host, request, _start_spec(request))
            self._runs[stored.id] = LiveRun(
                stored.id,
                host,
                understood,
                stored.record["request"],
                stored.record["plan"],
                Progress.from_dict(stored.record["progress"]),
                stored.status,
                stored.version,
                max(int(stored.record.get("seq", 0)), stored.last_seq),
            )
        return len(self._runs)

    def _run(self, run_id: str) -> LiveRun:
        run = self._runs.get(run_id)
        if run is None:
            raise not_found("run", run_id)
        return run

    async def create(self, request: RunRequest) -> dict[str, Any]:
        """Plan the run's mission (in the plan pool) and store the run; its first event is ``planned``."""
        host = self.scenes[request.scene]
        deadline = Deadline.after(self.request_time_limit_s)
        start = _start_spec(request)

        def job() -> LiveRun:
            understood = self.missions.understand(host, request, start)
            result = plan_on_host(host, understood, request.start, request.options, deadline)
            plan = result.to_dict()
            progress = start_progress(understood.mission.automaton, plan["path"])
            run = LiveRun(
                secrets.token_hex(8),
                host,
                understood,
                request.model_dump(mode="json", exclude_none=True),
                plan,
                progress,
                DONE if progress.verdict == DONE else ACTIVE,
            )
            first = [run.event("planned", _plan_event(plan))]
            if run.status == DONE:
                first.append(run.event("done", {"message": "the start already satisfies the mission"}))
            self.store.insert(run.id, host.name, run.status, run.record(), _rows(first))
            return run

        run = await self.pool.run(job)
        with self._lock:
            self._runs[run.id] = run
        return run.public()

    def get(self, run_id: str, *, view: bool = False) -> dict[str, Any]:
        run = self._run(run_id)
        with run.lock:
            return run.public(view)

    def list(self) -> list[dict[str, Any]]:
        return [run.summary() for run in list(self._runs.values())]

    def observe(self, run_id: str, request: ObserveRequest) -> dict[str, Any]:
        """Read the robot's poses: progress, the verdict (``on-track``, ``done``, ``violated``) and what
        is left; one ``progress`` event, then ``done`` or ``violated`` when that is the verdict."""
        run = self._run(run_id)
        with run.lock:
            _check_active(run)
            grid = run.host.session.grid(run.plan["radii"]["robot_m"])
            automaton = run.understood.mission.automaton
            progress = advance(
                run.progress,
                request.poses,
                run.host.building,
                grid,
                run.labels(),
                automaton,
                run.plan.get("path"),
            )
            status = {DONE: DONE, VIOLATED: VIOLATED}.get(progress.verdict, ACTIVE)
            saved_seq = run.seq
            events = [run.event("progress", progress.to_dict() | {"left_to_do": run.left(progress)})]
            if status != ACTIVE:
                events.append(run.event(status, {"verdict": progress.verdict, "state": progress.state}))
            try:
                run.version = self.store.update(
                    run.id, run.version, status, _record(run, progress), _rows(events)
                )
            except SgplanError:
                run.seq = saved_seq
                raise
            run.progress, run.status = progress, status
            answer = run.public()
        self.hub.publish(run.id, events)
        return answer

    def cancel(self, run_id: str) -> dict[str, Any]:
        """End the run (409 if it has ended already)."""
        run = self._run(run_id)
        with run.lock:
            _check_active(run)
            events = [run.event("cancelled", {"message": "cancelled on request"})]
            run.version = self.store.update(run.id, run.version, CANCELLED, run.record(), _rows(events))
            run.status = CANCELLED
            answer = run.public()
        self.hub.publish(run.id, events)
        return answer

    async def change(self, run_id: str, request: Any) -> dict[str, Any]:
        raise HTTPProblem(501, "scene changes on a run need sgplan.execution, which this build lacks")

    async def amend(self, run_id: str, request: Any) -> dict[str, Any]:
        raise HTTPProblem(501, "amending a run needs sgplan.execution, which this build lacks")

    async def stream(self, run_id: str, request: Request) -> Response:
        """The run's events as Server-Sent Events, from after ``Last-Event-ID`` (default: all)."""
        from sse_starlette.sse import EventSourceResponse

        from sgplan.serve.streams import KEEPALIVE_S

        run = self._run(run_id)
        if self.hub.streams(run_id) >= MAX_STREAMS_PER_RUN:
            raise HTTPProblem(
                429,
                f"run {run_id} has {MAX_STREAMS_PER_RUN} event streams open already; close one",
                retry_after_s=5,
            )
        header = request.headers.get("last-event-id", "0")
        after = int(header) if header.isdigit() else 0

        def replay() -> list[RunEvent]:
            return [RunEvent(e.seq, e.kind, e.data) for e in self.store.events(run.id, after)]

        return EventSourceResponse(self.hub.follow(run.id, replay), ping=int(KEEPALIVE_S))

    def close(self) -> None:
        self.hub.close_all()
        self.store.close()


def _start_spec(request: RunRequest) -> Any:
    return request.start.spec() if request.start is not None else None


def _check_active(run: LiveRun) -> None:
    if run.status != ACTIVE:
        raise HTTPProblem(409, f"run {run.id} has ended ({run.status}); start a new run")


def _record(run: LiveRun, progress: Progress) -> dict[str, Any]:
    return run.record() | {"progress": progress.to_dict()}


def _rows(events: list[RunEvent]) -> list[tuple[int, str, dict[str, Any]]]:
    return [(e.seq, e.kind, e.data) for e in events]


def _plan_event(plan: dict[str, Any]) -> dict[str, Any]:
    """The ``planned`` / ``replanned`` event: the plan without its long lists but the simplified waypoints."""
    keys = ("status", "cost_m", "bound", "start", "setup", "waypoints_simplified")
    return {key: plan.get(key) for key in keys}
