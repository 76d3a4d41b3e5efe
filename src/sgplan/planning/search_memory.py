"""The search's memory (:class:`sgplan.planning._search.SearchState`): made for a domain, grown on demand.

The state records live in a pool of pages reserved once and lazily committed (only the pages a search
touches cost memory); the heaps (one per queue) and the INCONS list double when the compiled search asks
for room (:data:`sgplan.planning._search.GROW`). See :mod:`sgplan.planning._search` for the layout.
"""

from __future__ import annotations

import numpy as np

from sgplan.planning import _search
from sgplan.planning._memory import sparse_zeros
from sgplan.planning._search import SearchState
from sgplan.planning.domain import PlanningDomain


def new_state(domain: PlanningDomain, num_queues: int, pages: int | None = None) -> SearchState:
    """Fresh search memory with the start state in INCONS (so the first iteration opens it).

    The pool has ``pages`` page slots, grown on demand; by default a slot for every (automaton state,
    block) pair, or as many as the operating system lets us map (:func:`pool_buffer`). The reservation
    is lazily committed, so the slots a search never uses cost no memory, and a pool that never grows is
    never copied: each doubling writes and page-faults the used part again, and at its peak holds both
    copies."""
    num_q = domain.num_states
    blocks = -(-domain.graph.num_cells // _search.PAGE)
    pool = pool_buffer(num_q * blocks if pages is None else pages)
    capacity = int(min(domain.graph.num_cells * num_q + 16, 1 << 20))
    hbuf = sparse_zeros(num_queues * capacity * _search.HREC, np.int64)
    state = SearchState(
        ptab=np.full((num_q, blocks), -1, dtype=np.int32),
        pool=pool,
        poolf=pool.view(np.float64),
        hbuf=hbuf,
        hbuff=hbuf.view(np.float64),
        hsize=np.zeros(num_queues, dtype=np.int64),
        incons=np.empty(capacity, dtype=np.int64),
        fscal=np.array([np.inf, 1.0, 1.0]),
        iscal=np.array([-1, 1, 1, 0, 0, 0, 0], dtype=np.int64),
        expansions=np.zeros(num_queues, dtype=np.int64),
        h_evals=np.zeros(domain.klogic.h_ready.shape[0], dtype=np.int64),
    )
    _search.init_start(state.ptab, state.pool, state.poolf, state.iscal, state.incons,
                       domain.start_cell, domain.q_start)
    return state


def pool_buffer(pages: int) -> np.ndarray:
    """A lazily committed pool of ``pages`` page slots, or of as many as can be mapped (halving on
    MemoryError, down to one; the search grows it later if it needs more)."""
    while True:
        try:
            return sparse_zeros(pages * _search.PAGE * _search.REC, np.int64)
        except MemoryError:
            if pages <= 1:
                raise
            pages //= 2


def reserve(state: SearchState, capacity: int, free_pages: int = 0) -> SearchState:
    """``state`` with heaps and INCONS able to hold at least ``capacity`` entries each, and at least
    ``free_pages`` unused page slots in the pool (each grown by doubling, contents kept)."""
    rec = _search.HREC
    num_queues = state.hsize.shape[0]
    old_cap = state.hbuf.shape[0] // (rec * num_queues)
    new = old_cap
    while new < capacity:
        new *= 2
    if new != old_cap:
        hbuf = sparse_zeros(num_queues * new * rec, np.int64)
        for i in range(num_queues):  # heap i moves from entry offset i * old_cap to i * new
            size, to, at = int(state.hsize[i]) * rec, i * new * rec, i * old_cap * rec
            hbuf[to : to + size] = state.hbuf[at : at + size]
        state = state._replace(hbuf=hbuf, hbuff=hbuf.view(np.float64))
    if state.incons.shape[0] < capacity:
        incons = np.empty(max(capacity, 2 * state.incons.shape[0]), dtype=np.int64)
        incons[: state.iscal[2]] = state.incons[: state.iscal[2]]
        state = state._replace(incons=incons)
    page_words = _search.PAGE * _search.REC
    used, slots = int(state.iscal[_search.I_PAGES]), state.pool.shape[0] // page_words
    if used + free_pages > slots:
        pool = sparse_zeros(max(2 * slots, used + free_pages) * page_words, np.int64)
        pool[: used * page_words] = state.pool[: used * page_words]
        state = state._replace(pool=pool, poolf=pool.view(np.float64))
    return state


def state_bytes(state: SearchState) -> int:
    """Bytes of search memory that can be committed: used pool pages, page table, heap and INCONS
    entries in use (the rest of the lazily committed buffers is never touched)."""
    used = int(state.iscal[_search.I_PAGES]) * _search.PAGE * _search.REC * 8
    heaps = int(state.hsize.sum()) * _search.HREC * 8
    return used + state.ptab.nbytes + heaps + int(state.iscal[2]) * 8
