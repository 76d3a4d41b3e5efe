"""The scenes a service serves, each loaded once and kept warm.

A :class:`SceneHost` holds one building and its warm :class:`sgplan.Session` objects (grids, label masks
and the planner's building-only parts, kept between requests): one per plan worker, each lent to one plan
at a time (a session's action maps fill themselves during a search, so two searches must not share one),
so a scene's one-shot plans run side by side. The first session also serves the say-back and the runs.
Requests name a scene by its building's name (any case), never by a path: the list is the server's own
configuration (:class:`sgplan.serve.config.ServeConfig`).
"""

from __future__ import annotations

import dataclasses
import io
import queue
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from functools import cached_property
from typing import Any

import numpy as np

from sgplan.api import Session, load_scene
from sgplan.scene.model import Building
from sgplan.serve.config import ServeError
from sgplan.serve.errors import not_found


class SceneHost:
    """One served scene: its building and warm sessions (``planners`` of them, see the module); pictures
    and lists made once."""

    def __init__(self, building: Building, *, planners: int = 1, max_shared_bytes: int | None = None) -> None:
        self.building = building
        self.session = Session(building, max_shared_bytes=max_shared_bytes)
        """The say-back's and the runs' session (runs plan on parts of their own), and the first planner."""
        # Last in, first out: a lone client's plans all go to the session it warmed last (the planner's
        # parts of its missions kept there), not round the sessions; concurrent plans take the others.
        self._free: queue.LifoQueue[Session] = queue.LifoQueue()
        self.sessions = (self.session, *(Session(building, max_shared_bytes=max_shared_bytes)
                                         for _ in range(planners - 1)))
        """Every planner session, the first one first."""
        for session in reversed(self.sessions):  # the first is lent first
            self._free.put(session)

    @contextmanager
    def planner(self, wait_s: float | None = None) -> Iterator[Session]:
        """A session no other plan uses, for the time of one plan; waits at most ``wait_s`` seconds
        (``None``: as long as it takes).

        Raises
        ------
        TimeoutError
            no session came free in time.
        """
        try:
            session = self._free.get(timeout=wait_s)
        except queue.Empty:
            raise TimeoutError from None
        try:
            yield session
        finally:
            self._free.put(session)

    @property
    def name(self) -> str:
        return self.building.name

    def info(self) -> dict[str, Any]:
        """Name and counts of floors, rooms and objects."""
        b = self.building
        return {
            "name": b.name,
            "floors": b.num_floors,
            "rooms": sum(1 for _ in b.rooms()),
            "objects": sum(1 for _ in b.objects()),
        }

    @cached_property
    def summary(self) -> dict[str, Any]:
        """``sgplan inspect --json``'s summary (:func:`sgplan.scene.summary.summarize`) on the served grid,
        with the doors (:meth:`doors`)."""
        from sgplan.scene.summary import summarize

        grid = self.session.grid()
        return dataclasses.asdict(summarize(self.building, grid)) | {"doors": self.doors}

    @cached_property
    def doors(self) -> list[dict[str, Any]]:
        """Every opening between two rooms of one floor, at the door cell nearest its middle, with both
        rooms' keys and categories (what the page draws as a door to close or open)."""
        found = []
        for room in self.building.rooms():
            for other_id in room.connected_room_ids:
                other = self.building.room(id=other_id)
                if other_id < room.id or other.floor != room.floor:
                    continue
                sides = [
                    c for c in (room.door_cells.get(other_id), other.door_cells.get(room.id)) if c is not None
                ]
                if not sides:
                    continue
                cells = np.concatenate(sides)
                middle = cells[np.argmin(((cells - cells.mean(axis=0)) ** 2).sum(axis=1))]
                found.append(
                    {
                        "floor": room.floor,
                        "rooms": [room.key, other.key],
                        "names": [room.name, other.name],
                        "row": int(middle[0]),
                        "col": int(middle[1]),
                    }
                )
        return found

    def floor_png(self, floor: int) -> bytes:
        """The floor's picture as PNG bytes (the report's colours: rooms, objects, walls, cells the robot
        may not enter shaded); made once per floor."""
        if not (0 <= floor < self.building.num_floors):
            raise not_found("floor", str(floor), [str(k) for k in range(self.building.num_floors)])
        return self._pictures[floor]

    @cached_property
    def _pictures(self) -> list[bytes]:
        from PIL import Image

        from sgplan.scene.draw import floor_image

        grid = self.session.grid()
        pictures = []
        for k in range(self.building.num_floors):
            buffer = io.BytesIO()
            Image.fromarray((floor_image(self.building, k, grid) * 255).round().astype(np.uint8)).save(
                buffer, format="PNG"
            )
            pictures.append(buffer.getvalue())
        return pictures


class SceneRegistry:
    """The served scenes by name (case-insensitive): the building's name, or the name the server was
    given for it (``demo`` for ``demo-house``)."""

    def __init__(self, hosts: Iterable[SceneHost], aliases: dict[str, str] | None = None) -> None:
        self._hosts: dict[str, SceneHost] = {}
        for host in hosts:
            if host.name.lower() in self._hosts:
                raise ServeError(f"two scenes are called {host.name!r}; serve each building once")
            self._hosts[host.name.lower()] = host
        self._aliases = {
            alias.lower(): name.lower()
            for alias, name in (aliases or {}).items()
            if alias.lower() not in self._hosts
        }

    @classmethod
    def load(cls, specs: Iterable[str], data: str | None = None, planners: int = 1) -> SceneRegistry:
        """Load every scene of ``specs`` (names or folders, as :func:`sgplan.load_scene` takes them) with
        ``planners`` sessions each and build their default grids, so the first requests do not pay for
        them."""
        hosts, aliases = [], {}
        for spec in specs:
            host = SceneHost(load_scene(spec, data), planners=planners)
            for session in host.sessions:
                session.grid()
            hosts.append(host)
            aliases[str(spec)] = host.name
        return cls(hosts, aliases)

    def __getitem__(self, name: str) -> SceneHost:
        key = name.strip().lower()
        host = self._hosts.get(self._aliases.get(key, key))
        if host is None:
            raise not_found("scene", name, self.names())
        return host

    def names(self) -> list[str]:
        return [host.name for host in self._hosts.values()]

    def __iter__(self) -> Any:
        return iter(self._hosts.values())
