"""Run event streams: replay then live, ending at a run's last event, a client that leaves dropped at once,
a stream that falls too far behind closed (its client replays from the database)."""

from __future__ import annotations

import asyncio

from sgplan.serve.streams import QUEUE_EVENTS, EventHub, RunEvent


def _kinds(messages: list[dict[str, object]]) -> list[object]:
    return [m["event"] for m in messages]


def test_replay_then_live_until_the_last_event() -> None:
    async def scenario() -> list[dict[str, object]]:
        hub = EventHub()
        hub.attach(asyncio.get_running_loop())
        stream = hub.follow("r", lambda: [RunEvent(1, "replanned", {}), RunEvent(2, "progress", {})])
        got = [await anext(stream), await anext(stream)]
        hub.publish("r", [RunEvent(2, "progress", {}), RunEvent(3, "changed", {}), RunEvent(4, "done", {})])
        got += [message async for message in stream]  # the duplicate 2 is skipped; done ends it
        assert hub.streams("r") == 0
        return got

    assert _kinds(asyncio.run(scenario())) == ["replanned", "progress", "changed", "done"]


def test_a_client_that_leaves_is_dropped_and_a_slow_one_is_closed() -> None:
    async def scenario() -> None:
        hub = EventHub()
        hub.attach(asyncio.get_running_loop())
        leaving = hub.follow("r", lambda: [RunEvent(1, "replanned", {})])
        await anext(leaving)
        assert hub.streams("r") == 1
        await leaving.aclose()  # what the server does when the client goes away
        assert hub.streams("r") == 0
        slow = hub.follow("r", lambda: [])
        waiting = asyncio.ensure_future(anext(slow))
        await asyncio.sleep(0)
        hub.publish("r", [RunEvent(k, "progress", {}) for k in range(1, QUEUE_EVENTS + 10)])
        await asyncio.sleep(0.05)
        assert hub.streams("r") == 0  # too far behind: closed, the client replays from the database
        assert (await waiting)["id"] == "1"
        rest = [message async for message in slow]
        assert len(rest) < QUEUE_EVENTS

    asyncio.run(scenario())
