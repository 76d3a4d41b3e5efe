"""Shortest paths through an automaton and the "remaining mission" of a state.

An automaton path is a sequence of states linked by letters; its cost is the number of letters (unit
weights) or the sum of per-letter weights. Self-loops never shorten a path and are ignored.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sgplan.errors import AutomatonError
from sgplan.logic.automaton import Automaton


@dataclass(frozen=True)
class AutomatonPath:
    """``states[0] -labels[0]-> states[1] -> ... -> states[-1]`` (accepting), total ``cost``."""

    states: tuple[int, ...]
    labels: tuple[int, ...]
    cost: float


@dataclass(frozen=True)
class MissionStep:
    """One transition of a shortest path to acceptance.

    ``must_hold``/``must_not_hold``: the propositions true / false in every label that takes
    ``state`` to ``next_state``.
    """

    state: int
    next_state: int
    must_hold: frozenset[str]
    must_not_hold: frozenset[str]


@dataclass(frozen=True)
class RemainingMission:
    """What is left to do from a state, read off a shortest path to acceptance.

    ``to_keep_false``: the propositions that lead to a dead state, whatever else holds, from every state
    of that path (e.g. the rooms to avoid). A proposition that is merely false on the path's transitions
    -- a room the robot is not in because it is entering another -- is not in it.
    """

    steps: tuple[MissionStep, ...]
    to_keep_false: frozenset[str] = frozenset()

    @property
    def to_make_true(self) -> tuple[frozenset[str], ...]:
        """Per step, in order, the propositions that must become true (empty sets dropped)."""
        return tuple(s.must_hold for s in self.steps if s.must_hold)


def _weights(a: Automaton, weights: np.ndarray | None) -> np.ndarray:
    if weights is None:
        return np.ones((a.num_states, a.num_labels))
    w = np.asarray(weights, dtype=np.float64)
    if w.shape == (a.num_labels,):
        w = np.broadcast_to(w, (a.num_states, a.num_labels))
    if w.shape != (a.num_states, a.num_labels):
        raise AutomatonError(
            f"weights have shape {w.shape}; expected ({a.num_labels},) or ({a.num_states}, {a.num_labels})"
        )
    if np.isnan(w).any() or (w < 0).any():
        raise AutomatonError("automaton path weights must be non-negative numbers")
    return w


def _cheapest_edges(a: Automaton, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """For each distinct non-self-loop edge (q, r): q, r, min weight, and the label achieving it."""
    n, num_labels = a.table.shape
    src = np.repeat(np.arange(n), num_labels)
    dst = a.table.ravel().astype(np.int64)
    lab = np.tile(np.arange(num_labels), n)
    cost = w.ravel()
    keep = src != dst
    src, dst, lab, cost = src[keep], dst[keep], lab[keep], cost[keep]
    order = np.lexsort((lab, cost, src * n + dst))
    _, first = np.unique((src * n + dst)[order], return_index=True)
    pick = order[first]
    return src[pick], dst[pick], cost[pick], lab[pick]


def distances_to_accept(a: Automaton, weights: np.ndarray | None = None) -> np.ndarray:
    """``(n,)`` float: the cost of a cheapest path from each state to an accepting state.

    ``weights`` is the cost of reading each label, shape ``(num_labels,)`` or ``(num_states,
    num_labels)``, non-negative; default 1 per letter. Accepting states get 0, sinks ``inf``.
    """
    return _to_accept(a, _weights(a, weights))[0]


def _to_accept(a: Automaton, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, dict[tuple[int, int], int]]:
    n = a.num_states
    acc = np.flatnonzero(a.accepting)
    if acc.size == 0:
        return np.full(n, np.inf), np.full(n, -9999), {}
    src, dst, cost, lab = _cheapest_edges(a, w)
    # Dijkstra from the accepting states on the reversed graph: predecessors there are next states here.
    from scipy.sparse import csr_matrix  # scipy.sparse is slow to import: only when used
    from scipy.sparse.csgraph import dijkstra

    reverse = csr_matrix((cost, (dst, src)), shape=(n, n))
    dist, pred, _ = dijkstra(reverse, directed=True, indices=acc, min_only=True, return_predecessors=True)
    best_label = {(int(s), int(d)): int(a) for s, d, a in zip(src, dst, lab)}
    return dist, pred, best_label


def shortest_path(a: Automaton, source: int | None = None, weights: np.ndarray | None = None
                  ) -> AutomatonPath | None:
    """A cheapest path from ``source`` (default: the initial state) to an accepting state.

    Returns ``None`` when ``source`` is a sink; a zero-step path when it is accepting.
    """
    w = _weights(a, weights)
    dist, pred, best_label = _to_accept(a, w)
    q = a.initial if source is None else int(source)
    if not np.isfinite(dist[q]):
        return None
    states, labels = [q], []
    while not a.accepting[q]:
        r = int(pred[q])
        labels.append(best_label[(q, r)])
        states.append(r)
        q = r
    return AutomatonPath(tuple(states), tuple(labels), float(dist[states[0]]))


def remaining_mission(a: Automaton, state: int, weights: np.ndarray | None = None) -> RemainingMission | None:
    """The propositions to make true (in order) and to keep false from ``state`` to acceptance.

    Read off a shortest path (unit weights, or ``weights`` per label as in :func:`distances_to_accept`,
    e.g. to steer clear of labels the scene makes implausible); for each of its transitions, the
    propositions true (false) in every label that takes it; see :class:`RemainingMission` for
    ``to_keep_false``. ``None`` if ``state`` is a sink; no steps if it is accepting.
    """
    path = shortest_path(a, state, weights)
    if path is None:
        return None
    steps = []
    full = (1 << len(a.aps)) - 1
    for q, r in zip(path.states, path.states[1:]):
        members = np.flatnonzero(a.table[q] == r)
        always_on = int(np.bitwise_and.reduce(members)) if members.size else 0
        always_off = full & ~int(np.bitwise_or.reduce(members)) if members.size else 0
        steps.append(MissionStep(q, r, a.props_of(always_on), a.props_of(always_off)))
    return RemainingMission(tuple(steps), _forbidden(a, path.states[:-1] or path.states))


def _forbidden(a: Automaton, states: tuple[int, ...]) -> frozenset[str]:
    """Propositions whose every label leads to a dead state from each of ``states``."""
    live = a.live_states()
    labels = np.arange(a.num_labels)
    keep = np.ones(len(a.aps), dtype=bool)
    for s in states:
        dead = ~live[a.table[s]]
        for i in np.flatnonzero(keep):
            keep[i] = bool(dead[(labels >> i) & 1 == 1].all())
    return frozenset(a.aps[i] for i in np.flatnonzero(keep))
