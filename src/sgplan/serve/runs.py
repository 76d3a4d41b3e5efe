"""Runs: missions carried out by robots, on :class:`sgplan.execution.run.Run`, kept in the database,
their events streamed.

A run is created from a mission and a start and planned at once (in the plan pool); then its robot
reports poses (``observe``: the runtime monitor's verdict and what is left, in words), people and robots
report scene changes (``change``: a door closed, an area blocked; the run replans from where the robot
is, exactly) and amendments (``amend``: "also go to the kitchen"; refused, 409, when the rest of the
mission could then never be satisfied), or cancel it (a search of it still running stops at its next
poll). Every change of a run is one transaction in the store (its saved form and its new events), then
its events go to its streams.

A run is *hot* while its :class:`Run` is in memory (its grid, labels, monitor and planner parts); the
least recently used beyond ``max_hot`` are dropped and brought back from their saved form when next
needed (:meth:`Run.from_dict`: the changes replayed, the next plan made from the same cell and state).
After a restart every run is back, cold, as of its last committed change.

The answer about a run (``GET /api/runs/{id}``): ``id``, ``scene``, ``status`` (``in-progress``,
``done``, ``violated``, ``impossible``, ``cancelled``), ``why`` (impossible), ``request`` (mission,
start, options as given), ``position`` and ``state`` (the robot's cell and the mission's automaton state
there), ``left`` (what is left of the mission, in words), ``plan`` (the JSON of ``sgplan plan --json`` of
the current plan, ``plan_offset`` the robot's row on its path), ``monitor`` (poses, cells, metres),
``changes``, ``amendments``, ``events`` (how many), ``revision`` (how many changes of the run were
committed: it only grows).
"""

from __future__ import annotations

import asyncio
import logging
import secrets
import threading
from collections import OrderedDict
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from sgplan.serve.errors import HTTPProblem, not_found
from sgplan.serve.models import RunRequest
from sgplan.serve.planning import Budget, plan_options
from sgplan.serve.store import UNCHANGED, Unchanged
from sgplan.serve.streams import MAX_STREAMS_PER_RUN, EventHub, RunEvent
from sgplan.serve.views import overlays

if TYPE_CHECKING:
    from starlette.requests import Request
    from starlette.responses import Response

    from sgplan.execution.events import RunEvent as EngineEvent
    from sgplan.execution.run import Run
    from sgplan.serve.missions import MissionBook
    from sgplan.serve.models import AmendRequest, ChangesRequest, ObserveRequest
    from sgplan.serve.pool import WorkPool
    from sgplan.serve.scenes import SceneHost, SceneRegistry
    from sgplan.serve.store import RunStore

Plan = dict[str, Any] | Unchanged | None
"""What an operation leaves of a run's plan: a new one (``plan --json``'s JSON), none (``None``), or the
one it had (:data:`UNCHANGED`)."""
log = logging.getLogger("sgplan")
CANCELLED = "cancelled"
ENDED = ("done", "violated", CANCELLED)
"""Statuses after which a run takes no more poses, changes or amendments."""
REFUSED_CHANGES = ("scene_graph",)
"""Change kinds not taken over HTTP: a newer scene graph names a scene folder, and requests never name
files (scenes come from the server's own configuration)."""


@dataclass
class LiveRun:
    """A run as the service holds it: the saved form (always), the :class:`Run` (while hot), its place in
    the store, and the lock every operation on it takes."""

    id: str
    host: SceneHost
    request: dict[str, Any]
    saved: dict[str, Any]
    """:meth:`Run.to_dict` (its history: the changes only; the events are in the store) and the service's
    fields: ``status``, ``plan``, ``plan_offset``, ``left``, ``seq``."""
    version: int = 1
    run: Run | None = None
    lock: threading.Lock = field(default_factory=threading.Lock)
    budget: Budget | None = None
    """The budget of the operation running on the run (its cancel flag stops that search)."""
    pending: list[RunEvent] = field(default_factory=list)

    @property
    def status(self) -> str:
        return str(self.saved["status"])

    @property
    def seq(self) -> int:
        return int(self.saved.get("seq", 0))

    def public(self, view: bool = False, plan: bool = True) -> dict[str, Any]:
        """The run as ``GET /api/runs/{id}`` answers (see the module docstring); without ``plan``, the plan
        is left out but its cost (``plan_cost_m``): a pose report's answer stays small."""
        s = self.saved
        answer = {
            "id": self.id,
            "scene": self.host.name,
            "status": s["status"],
            "why": s.get("why"),
            "request": self.request,
            "position": s["position"],
            "state": s["state"],
            "left": s.get("left", ""),
            "plan": s.get("plan"),
            "plan_offset": s.get("plan_offset", 0),
            "monitor": s["monitor"],
            "changes": s["changes"],
            "amendments": s["amendments"],
            "events": self.seq,
            "revision": self.version,
        }
        if not plan:
            answer["plan_cost_m"] = (answer.pop("plan") or {}).get("cost_m")
        if view:
            current = s.get("plan") or {}
            answer["overlays"] = overlays(
                self.host, (current.get("path") or [])[s.get("plan_offset", 0) :] or None
            )
        return answer

    def summary(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "scene": self.host.name,
            "status": self.status,
            "poses": self.saved["monitor"]["poses"],
        }

    def on_event(self, event: EngineEvent) -> None:
        """The :class:`Run`'s callback: number its event and keep it for the next save."""
        self.saved["seq"] = self.seq + 1
        self.pending.append(RunEvent(self.seq, event.kind, {"message": event.message, **event.details}))


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
        max_hot: int = 8,
    ) -> None:
        self.scenes = scenes
        self.missions = missions
        self.pool = pool
        self.store = store
        self.request_time_limit_s = request_time_limit_s
        self.max_hot = max_hot
        self.hub = EventHub()
        self._runs: dict[str, LiveRun] = {}
        self._hot: OrderedDict[str, None] = OrderedDict()
        self._lock = threading.Lock()

    def attach_loop(self, loop: asyncio.AbstractEventLoop) -> None:
        self.hub.attach(loop)

    def count(self) -> int:
        return len(self._runs)

    def restore(self) -> int:
        """Bring back every run of the store whose scene this server serves (cold); returns how many."""
        for stored in self.store.load_all():
            if stored.scene.lower() not in {name.lower() for name in self.scenes.names()}:
                log.warning(
                    f"run {stored.id} is on scene {stored.scene!r}, which this server does not serve: "
                    "left in the database"
                )
                continue
            host = self.scenes[stored.scene]
            saved = dict(stored.record, plan=stored.plan)
            saved["seq"] = max(int(saved.get("seq", 0)), stored.last_seq)
            self._runs[stored.id] = LiveRun(stored.id, host, saved.pop("request"), saved, stored.version)
        return len(self._runs)

    # -- helpers -----------------------------------------------------------------------------------

    def _live(self, run_id: str) -> LiveRun:
        live = self._runs.get(run_id)
        if live is None:
            raise not_found("run", run_id)
        return live

    def _engine(self, live: LiveRun) -> Run:
        """The run's :class:`Run`, brought back from its saved form if it is cold (under ``live.lock``)."""
        from sgplan.execution.run import Run

        if live.run is None:
            live.run = Run.from_dict(live.saved, live.host.session)
            live.run.subscribe(live.on_event)
        with self._lock:
            self._hot[live.id] = None
            self._hot.move_to_end(live.id)
            cold = [k for k in self._hot if k != live.id][: max(0, len(self._hot) - self.max_hot)]
        for run_id in cold:
            self._cool(run_id)
        return live.run

    def _cool(self, run_id: str) -> None:
        """Drop a hot run's :class:`Run` (its saved form stays) unless an operation holds it now."""
        live = self._runs[run_id]
        if live.lock.acquire(blocking=False):
            try:
                live.run = None
                with self._lock:
                    self._hot.pop(run_id, None)
            finally:
                live.lock.release()

    @contextmanager
    def _operation(self, live: LiveRun) -> Iterator[Run]:
        """One operation on a run, all or nothing: under its lock, on its :class:`Run`; if anything fails
        before the operation is saved (a change that cannot apply, the deadline, a failed write), the run
        goes back to what the store holds (cold; its events of the operation dropped)."""
        with live.lock:
            self._check_open(live)
            seq = live.seq
            try:
                yield self._engine(live)
            except BaseException:
                live.run, live.pending = None, []
                live.saved["seq"] = seq
                with self._lock:
                    self._hot.pop(live.id, None)
                raise

    def _save(self, live: LiveRun, run: Run, plan: Plan = UNCHANGED, status: str | None = None) -> None:
        """Store the run as it is now with its pending events in one transaction, and ``plan`` unless it is
        :data:`UNCHANGED` (``None``: the run has no plan now: done, violated, impossible); then stream the
        events."""
        # The run's events are in the store; of its history it keeps the changes (they say why a run is
        # impossible), so neither the record nor the run in memory grows with every pose report.
        run.history = [event for event in run.history if event.kind == "changed"]
        saved = run.to_dict()
        saved.update(
            status=status or run.status,
            seq=live.seq,
            left=run.left(),
            plan_offset=run.remaining_offset if isinstance(plan, Unchanged) else 0,
        )
        rows = [(e.seq, e.kind, e.data) for e in live.pending]
        record = {"request": live.request, **saved}
        if live.version == 0:  # a new run: its first plan, or none
            first = None if isinstance(plan, Unchanged) else plan
            self.store.insert(live.id, live.host.name, saved["status"], record, first, rows)
            live.version = 1
        else:
            live.version = self.store.update(live.id, live.version, saved["status"], record, rows, plan)
        saved["plan"] = live.saved.get("plan") if isinstance(plan, Unchanged) else plan
        events, live.pending, live.saved = live.pending, [], saved
        self.hub.publish(live.id, events)

    def _check_open(self, live: LiveRun) -> None:
        if live.status in ENDED:
            raise HTTPProblem(409, f"run {live.id} has ended ({live.status}); start a new run")

    async def _in_pool(self, live: LiveRun, work: Callable[[Run], Plan]) -> dict[str, Any]:
        """Run ``work`` on the run in a plan worker, under the run's lock and a fresh budget (the run's
        searches stop at its deadline or when the run is cancelled), then save; the run's answer."""
        budget = Budget.of(self.request_time_limit_s)

        def job() -> dict[str, Any]:
            with self._operation(live) as run:
                live.budget, run.stop_when = budget, budget.stop_when
                try:
                    plan = work(run)
                finally:
                    live.budget, run.stop_when = None, None
                self._save(live, run, plan)
                return live.public(view=False)

        return await self.pool.run(job)

    # -- operations --------------------------------------------------------------------------------

    async def create(self, request: RunRequest) -> dict[str, Any]:
        """Start a run and plan it (in the plan pool); its first events are ``replanned`` (or ``done``
        when the start already satisfies the mission)."""
        host = self.scenes[request.scene]
        start = request.start.spec() if request.start is not None else None
        budget = Budget.of(self.request_time_limit_s)

        def job() -> LiveRun:
            from sgplan.execution.run import Run

            understood = self.missions.understand(host, request, start)
            live = LiveRun(
                secrets.token_hex(8),
                host,
                request.model_dump(mode="json", exclude_none=True),
                {"seq": 0},
                version=0,
            )
            run = Run(host.session, understood.mission, start, plan_options(request.options))
            run.subscribe(live.on_event)
            run.stop_when = budget.stop_when
            plan = _plan_record(run, budget)
            run.stop_when = None
            live.run = run
            self._save(live, run, plan)
            return live

        live = await self.pool.run(job)
        with self._lock:
            self._runs[live.id] = live
            self._hot[live.id] = None
        return live.public()

    def get(self, run_id: str, *, view: bool = False) -> dict[str, Any]:
        live = self._live(run_id)
        with live.lock:
            return live.public(view)

    def list(self) -> list[dict[str, Any]]:
        return [live.summary() for live in list(self._runs.values())]

    def observe(self, run_id: str, request: ObserveRequest) -> dict[str, Any]:
        """Read the robot's poses: the monitor's verdict, the state, what is left (in words). A robot that
        left its plan gets a new one at the next change or amendment, or from ``POST .../replan``."""
        live = self._live(run_id)
        with self._operation(live) as run:
            status = run.observe(request.poses)
            self._save(live, run)
            return {"run": live.public(plan=False), "monitor": status.to_dict()}

    async def change(self, run_id: str, request: ChangesRequest) -> dict[str, Any]:
        """Apply scene changes (all or none) and replan from where the robot is."""
        from sgplan.execution.changes import change_from_dict

        live = self._live(run_id)
        for k, change in enumerate(request.changes, 1):
            if change.get("kind") in REFUSED_CHANGES:
                raise HTTPProblem(
                    422,
                    f"change {k}: kind {change['kind']!r} is not taken over HTTP (it names a "
                    "scene folder); restart the server on the new scene instead",
                )
        typed = [change_from_dict(c, f"change {k}") for k, c in enumerate(request.changes, 1)]

        def work(run: Run) -> Plan:
            run.change(typed)
            return _plan_record(run, live.budget)

        return await self._in_pool(live, work)

    async def amend(self, run_id: str, request: AmendRequest) -> dict[str, Any]:
        """Join an amendment to what is left of the mission and replan; 409 naming the conflict when no
        path could then satisfy it (the mission stays as it was)."""
        live = self._live(run_id)
        refused: list[str] = []

        def work(run: Run) -> Plan:
            outcome = run.amend(request.text)
            if not outcome.accepted:
                said = " ".join(outcome.said_back.splitlines()[1:]).rstrip(".")
                refused.append(f"the amendment ({said}) is refused: {outcome.reason}")
                return UNCHANGED
            return _plan_record(run, live.budget)

        answer = await self._in_pool(live, work)
        if refused:
            raise HTTPProblem(409, refused[0], plan_status="unsatisfiable")
        return answer

    async def replan(self, run_id: str) -> dict[str, Any]:
        """Plan again from where the robot is (in the plan pool)."""
        live = self._live(run_id)

        def work(run: Run) -> Plan:
            run.replan()
            return _plan_record(run, live.budget)

        return await self._in_pool(live, work)

    def cancel(self, run_id: str) -> dict[str, Any]:
        """End the run: a search of it still running stops at its next poll; 409 if it has ended."""
        from sgplan.execution.events import RunEvent as EngineEvent

        live = self._live(run_id)
        running = live.budget
        if running is not None:
            running.cancel.cancel("the run was cancelled")
        with self._operation(live) as run:
            live.on_event(EngineEvent(CANCELLED, "cancelled on request"))
            self._save(live, run, status=CANCELLED)
            return live.public()

    async def stream(self, run_id: str, request: Request) -> Response:
        """The run's events as Server-Sent Events, from after ``Last-Event-ID`` (default: all)."""
        from sse_starlette.sse import EventSourceResponse

        from sgplan.serve.streams import KEEPALIVE_S

        live = self._live(run_id)
        if self.hub.streams(run_id) >= MAX_STREAMS_PER_RUN:
            raise HTTPProblem(
                429,
                f"run {run_id} has {MAX_STREAMS_PER_RUN} event streams open already; close one",
                retry_after_s=5,
            )
        header = request.headers.get("last-event-id", "0")
        after = int(header) if header.isdigit() else 0

        def replay() -> list[RunEvent]:
            return [RunEvent(e.seq, e.kind, e.data) for e in self.store.events(live.id, after)]

        return EventSourceResponse(self.hub.follow(live.id, replay), ping=int(KEEPALIVE_S))

    def close(self) -> None:
        self.hub.close_all()
        self.store.close()


def _plan_record(run: Run, budget: Budget | None) -> dict[str, Any] | None:
    """The run's current plan (made now if stale) as ``plan --json``'s JSON; ``None`` when there is none
    (done, violated, impossible). 408 when the server's deadline stopped the search before any path."""
    plan = run.plan
    if plan is None:
        return None
    if plan.path is None and budget is not None and budget.expired:
        raise budget.late()
    return plan.to_dict()
