"""A run's events to whoever listens: live fan-out to Server-Sent Event streams, replay from the store.

Events are produced wherever a run changes (a plan worker, a request thread); :class:`EventHub` hands
each one to the streams of its run on the server's event loop (thread-safe), each stream holding a
bounded queue: a stream that falls :data:`QUEUE_EVENTS` behind is closed rather than let grow, and its
client reconnects with ``Last-Event-ID`` and gets what it missed from the database. A client that goes
away mid-stream is dropped at once (its queue removed, nothing else disturbed).
"""

from __future__ import annotations

import asyncio
import json
import threading
from collections.abc import AsyncIterator, Callable
from dataclasses import dataclass
from typing import Any

QUEUE_EVENTS = 1_000
"""Events one stream may lag behind before it is closed (its client reconnects and replays)."""
MAX_STREAMS_PER_RUN = 32
"""Streams one run may have open at once; more are refused (429)."""
FINAL_KINDS = frozenset({"done", "violated", "cancelled"})
"""The kinds of event after which a run has no more (done, a mission no path can satisfy any more,
cancelled): its streams end there."""
KEEPALIVE_S = 15.0
"""Seconds between comments on an idle stream, so proxies keep it open."""


@dataclass(frozen=True)
class RunEvent:
    """One event of a run: its number in the run (from 1), kind and data."""

    seq: int
    kind: str
    data: dict[str, Any]

    def sse(self) -> dict[str, Any]:
        """As sse-starlette sends it: ``id``, ``event``, ``data`` (JSON text)."""
        return {"id": str(self.seq), "event": self.kind, "data": json.dumps(self.data)}


_CLOSED = RunEvent(0, "", {})
"""Put in a stream's queue to end it."""


class EventHub:
    """Streams of run events by run id."""

    def __init__(self) -> None:
        self._loop: asyncio.AbstractEventLoop | None = None
        self._queues: dict[str, set[asyncio.Queue[RunEvent]]] = {}
        self._lock = threading.Lock()

    def attach(self, loop: asyncio.AbstractEventLoop) -> None:
        self._loop = loop

    def streams(self, run_id: str) -> int:
        with self._lock:
            return len(self._queues.get(run_id, ()))

    def publish(self, run_id: str, events: list[RunEvent]) -> None:
        """Hand ``events`` to every stream of the run (from any thread)."""
        with self._lock:
            queues = list(self._queues.get(run_id, ()))
        if not queues or self._loop is None or self._loop.is_closed():
            return
        for queue in queues:
            self._loop.call_soon_threadsafe(self._offer, run_id, queue, events)

    def _offer(self, run_id: str, queue: asyncio.Queue[RunEvent], events: list[RunEvent]) -> None:
        for item in events:
            if queue.qsize() >= QUEUE_EVENTS - 1:  # too far behind: end it; the client replays
                self._remove(run_id, queue)
                queue.put_nowait(_CLOSED)
                return
            queue.put_nowait(item)

    def _remove(self, run_id: str, queue: asyncio.Queue[RunEvent]) -> None:
        with self._lock:
            queues = self._queues.get(run_id)
            if queues is not None:
                queues.discard(queue)
                if not queues:
                    del self._queues[run_id]

    async def follow(
        self, run_id: str, replay: Callable[[], list[RunEvent]]
    ) -> AsyncIterator[dict[str, Any]]:
        """The run's events as SSE messages: first ``replay()`` (what the client missed, read after this
        stream is registered, so nothing falls between), then live ones, up to the run's last event (one
        of :data:`FINAL_KINDS`), or until the client goes away."""
        queue: asyncio.Queue[RunEvent] = asyncio.Queue()
        with self._lock:
            self._queues.setdefault(run_id, set()).add(queue)
        try:
            last = 0
            for item in await asyncio.to_thread(replay):
                last = item.seq
                yield item.sse()
                if item.kind in FINAL_KINDS:
                    return
            while True:
                item = await queue.get()
                if item is _CLOSED:
                    return
                if item.seq <= last:
                    continue  # already sent by the replay
                last = item.seq
                yield item.sse()
                if item.kind in FINAL_KINDS:
                    return
        finally:
            self._remove(run_id, queue)

    def close_all(self) -> None:
        """End every stream (the server is stopping)."""
        with self._lock:
            pairs = [(run_id, q) for run_id, queues in self._queues.items() for q in queues]
        if self._loop is None or self._loop.is_closed():
            return
        for _, queue in pairs:
            self._loop.call_soon_threadsafe(queue.put_nowait, _CLOSED)
