"""The offline symbolic guide: move / reach call lists from the room graph, without any language model.

It produces guidance in the LLM's format (reference-algorithm.md §5, §9; the authors'
``llm_heuristic.yaml``): for each room uuid and each non-accepting automaton state, a list of calls
``move(a, b)`` (go from room ``a`` to the connected room ``b``) and ``reach(r, o)`` (reach object ``o``
of room ``r``) that finishes the mission from there.

How: a shortest path in the small product graph of (room, automaton state). Its edges are the calls:
``move(a, b)`` for every connection ``a -> b`` listed by the scene graph, reading the label
``{enter(b)}``; ``reach(a, o)`` for every object ``o`` of room ``a`` whose proposition is in the
automaton, reading ``{enter(a), reach(o)}``. Edge costs are the h_LLM cost model: the 3-D distance
between the centres (room -> room, room -> object). Edges into dead automaton states are dropped, so the
calls never break an "always avoid"; one Dijkstra from all accepting (room, state) pairs over the
reversed graph gives every entry at once. Following the calls from (room, q) runs the automaton into an
accepting state whenever the room graph allows it at all; where it does not (e.g. a room without
connections), the entry is an empty list. The result is deterministic.

Unlike an LLM given the "remaining mission" text, the guide reads the automaton itself, so it keeps the
order of goals and every negative requirement.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import dijkstra

from sgplan.logic.automaton import Automaton
from sgplan.logic.tokens import canonical_action
from sgplan.scene.model import Building

SYMBOLIC_BACKEND = "offline-symbolic"

Guidance = dict[int, dict[int, list[str]]]
"""``{room_uuid: {state: ["move(a, b)", "reach(r, o)", ...]}}``, the llm_heuristic.yaml content."""


@dataclass(frozen=True)
class Call:
    """One guidance call; ``a`` is a room uuid, ``b`` a room uuid (move) or an object uuid (reach)."""

    kind: Literal["move", "reach"]
    a: int
    b: int

    def __str__(self) -> str:
        return f"{self.kind}({self.a}, {self.b})"


class SymbolicGuide:
    """Guidance for every (room, non-accepting state) from the room graph; see the module docstring.

    Example
    -------
    >>> guidance = SymbolicGuide().guide(building, automaton)  # doctest: +SKIP
    >>> guidance[2][0]                                         # doctest: +SKIP
    ['move(2, 9)', 'move(9, 12)', 'reach(12, 40)']
    """

    name = SYMBOLIC_BACKEND

    def guide(self, building: Building, automaton: Automaton,
              ap_actions: Mapping[str, str] | None = None) -> Guidance:
        """Call lists for every room uuid (staircases included) and every non-accepting state.

        Parameters
        ----------
        building:
            the scene; rooms, connections, objects and their centres (``location_m``, metres).
        automaton:
            the mission's complete DFA.
        ap_actions:
            proposition name -> action token (``{"p1": "enter(room_2)"}``, the inverse of an
            ``ap_dict``); by default each proposition is named by its action token. Propositions that
            are not actions of this building are never made true by a call.

        Returns
        -------
        Guidance
            ``{room_uuid: {q: [call strings]}}``; an empty list where no call sequence reaches
            acceptance (dead states, or rooms cut off from what the mission needs).
        """
        graph = _ProductGraph(building, automaton, ap_actions or {})
        return graph.all_entries()


class _ProductGraph:
    """(room, state) nodes, numbered ``room_index * num_states + q``, and their call edges."""

    def __init__(self, building: Building, automaton: Automaton, ap_actions: Mapping[str, str]) -> None:
        self.automaton = automaton
        self.rooms = list(building.rooms())
        self.num_states = automaton.num_states
        bits: dict[str, int] = {}
        for i, ap in enumerate(automaton.aps):
            action = canonical_action(ap_actions.get(ap, ap))
            if action is not None:
                bits[action] = bits.get(action, 0) | (1 << i)
        index = {room.uuid: i for i, room in enumerate(self.rooms)}
        room_label = np.array([bits.get(f"enter({r.key})", 0) for r in self.rooms], dtype=np.int64)
        live = automaton.live_states()
        q = np.arange(self.num_states)
        src: list[np.ndarray] = []
        dst: list[np.ndarray] = []
        cost: list[np.ndarray] = []
        self.calls: list[Call] = []
        call_of: list[np.ndarray] = []

        def add(i: int, j: int, label: int, length_m: float, call: Call, skip_self: bool) -> None:
            nxt = automaton.table[:, label]
            keep = live[nxt] & (nxt != q) if skip_self else live[nxt]
            if keep.any():
                src.append(i * self.num_states + q[keep])
                dst.append(j * self.num_states + nxt[keep])
                cost.append(np.full(int(keep.sum()), length_m))
                call_of.append(np.full(int(keep.sum()), len(self.calls)))
                self.calls.append(call)

        for i, room in enumerate(self.rooms):
            centre = np.asarray(room.location_m, dtype=np.float64)
            for uuid in room.connected_room_uuids:
                j = index.get(uuid)
                if j is not None and j != i:
                    length = float(np.linalg.norm(np.asarray(self.rooms[j].location_m) - centre))
                    add(i, j, int(room_label[j]), length, Call("move", room.uuid, uuid), False)
            for obj in room.objects.values():
                bit = bits.get(f"reach({obj.key})", 0)
                if bit:
                    length = float(np.linalg.norm(np.asarray(obj.location_m) - centre))
                    add(i, i, int(room_label[i]) | bit, length, Call("reach", room.uuid, obj.uuid), True)
        self._graph(src, dst, cost, call_of)

    def _graph(self, src: list[np.ndarray], dst: list[np.ndarray], cost: list[np.ndarray],
               call_of: list[np.ndarray]) -> None:
        n = len(self.rooms) * self.num_states
        if src:
            s, d, c, k = (np.concatenate(x) for x in (src, dst, cost, call_of))
        else:
            s = d = k = np.zeros(0, np.int64)
            c = np.zeros(0)
        # Keep the cheapest call per node pair (ties: the first call built, i.e. scene order).
        order = np.lexsort((k, c, s * n + d))
        _, first = np.unique((s * n + d)[order], return_index=True)
        pick = order[first]
        s, d, c, k = s[pick], d[pick], c[pick], k[pick]
        self.edge_call = {(int(a), int(b)): int(x) for a, b, x in zip(s, d, k)}
        # Zero-length calls (an object at its room's centre) must still count as edges for scipy.
        reverse = csr_matrix((np.maximum(c, 1e-9), (d, s)), shape=(n, n))
        accepting_nodes = np.flatnonzero(np.tile(self.automaton.accepting, len(self.rooms)))
        if accepting_nodes.size:
            self.dist, self.pred = dijkstra(reverse, directed=True, indices=accepting_nodes, min_only=True,
                                            return_predecessors=True)[:2]
        else:
            self.dist, self.pred = np.full(n, np.inf), np.full(n, -9999)

    def entry(self, room_index: int, state: int) -> list[str]:
        node = room_index * self.num_states + state
        if not np.isfinite(self.dist[node]):
            return []
        calls = []
        while not self.automaton.accepting[node % self.num_states]:
            nxt = int(self.pred[node])
            calls.append(str(self.calls[self.edge_call[(node, nxt)]]))
            node = nxt
        return calls

    def all_entries(self) -> Guidance:
        non_accepting = [q for q in range(self.num_states) if not self.automaton.accepting[q]]
        return {room.uuid: {q: self.entry(i, q) for q in non_accepting} for i, room in enumerate(self.rooms)}
