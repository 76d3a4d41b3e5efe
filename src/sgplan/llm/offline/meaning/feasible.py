"""A mission no walk through the scene's rooms can do: refused, naming the parts that cannot hold together.

*Stay out of the kitchen, and don't go into the lobby until you've checked the fridge; finish in the lobby*
(the fridge is in the kitchen), *never use the corridor; go to the bedroom* (the corridor is the only way
in): read word by word, such a text means an impossible formula. Planned, it would only end in "no path";
blind writers mark it as a mission to refuse, and the user is better told which parts clash.

The check walks the scene's door graph (:attr:`.names.SceneVocabulary.adjacent`; a staircase room joins
its floors) from the room of each of the scene's initial positions (those on the robot's start floor when
it is known; every room when the scene has none), reading at each room the letters the room can give:
``enter(room)`` with any subset of the formula's objects in it (an object is reached only from its room).
It runs LTLf progression (:func:`sgplan.logic.progression.progress`) over these walks, so it is exact for
the door graph and generous about the grid (every door wide enough, every object reachable): a pass is not
a promise (the planner's scene check says the rest). The grid may hold a way the door graph lacks (cells of
no room between two rooms: Benevolence's door-less utility room is reached so by a small robot), so the
refusal says what the doors allow. A walk that could end after a letter where the remaining formula holds
at a last position makes the mission possible.

Only a clash the mission's own prohibitions make is refused here: when its goals alone (:func:`goals_only`)
cannot be done either, the scene rules them out (a room with no door: *go to the utility room*), and the
planner's scene check says why in terms of the grid.
"""

from __future__ import annotations

from collections import deque
from itertools import chain, combinations

from sgplan.explain.patterns import pattern_clauses
from sgplan.explain.referents import referents_of
from sgplan.llm.offline import refusals as rf
from sgplan.logic import atoms, to_infix
from sgplan.logic.formula import (
    FALSE,
    TRUE,
    Always,
    And,
    Atom,
    Const,
    Equiv,
    Eventually,
    Formula,
    Implies,
    Next,
    Not,
    Or,
    Release,
    Until,
    WeakNext,
    conjuncts,
)
from sgplan.logic.progression import progress
from sgplan.scene.model import Building

MAX_NODES = 20_000
"""Walk states (remaining formula, room) explored at most; past it the check passes (it never refuses on a
guess)."""
Letter = frozenset[str]


def check_can_be_done(formula: Formula, building: Building, start_floor: int | None) -> None:
    """Refuse ``formula`` when no walk through ``building``'s rooms from a start can satisfy it (see the
    module docstring); the message says the smallest set of its top-level parts that cannot hold together."""
    walks = _Walks(building, formula, start_floor)
    if walks.possible(formula) is not False or walks.possible(goals_only(formula)) is not True:
        return  # possible, or a goal the scene alone rules out (a room without doors): the planner says why
    parts = conjuncts(formula)
    k = 0
    while k < len(parts) and len(parts) > 1:  # drop every part the clash does not need
        rest = parts[:k] + parts[k + 1:]
        if walks.possible(And(tuple(rest)) if len(rest) > 1 else rest[0]) is False:
            parts = rest
        else:
            k += 1
    describe = referents_of(list(dict.fromkeys(chain.from_iterable(atoms(p) for p in parts))), None,
                            building).__getitem__
    said = [c for p in parts for c in (pattern_clauses(p, describe) or [f"'{to_infix(p)}'."])]
    rf.refuse(rf.cannot_be_done(said))


def goals_only(formula: Formula) -> Formula:
    """``formula`` without what it forbids: its top-level ``G`` parts dropped, each top-level ``a U b`` read
    as ``F b`` (``TRUE`` when nothing is left)."""
    kept = [Eventually(p.right) if isinstance(p, Until) else p for p in conjuncts(formula)
            if not isinstance(p, Always)]
    return TRUE if not kept else kept[0] if len(kept) == 1 else And(tuple(kept))


class _Walks:
    """The room walks of one building for the atoms of one formula."""

    def __init__(self, building: Building, formula: Formula, start_floor: int | None) -> None:
        named = set(atoms(formula))
        self.adjacent = {room.key: [f"room_{u}" for u in room.connected_room_uuids]
                         for room in building.rooms()}
        self.letters: dict[str, list[Letter]] = {}
        for room in building.rooms():
            here = [a for a in (f"reach({o.key})" for o in room.objects.values()) if a in named]
            entered = {f"enter({room.key})"} & named
            self.letters[room.key] = [frozenset(entered | set(s)) for n in range(len(here) + 1)
                                      for s in combinations(here, n)]
        self.starts = _start_rooms(building, start_floor)

    def possible(self, formula: Formula) -> bool | None:
        """Whether some walk satisfies ``formula``; ``None`` when the walk states ran past
        :data:`MAX_NODES`."""
        seen: set[tuple[Formula, str]] = set()
        todo: deque[tuple[Formula, str]] = deque()
        for room in self.starts:
            for letter in self.letters[room]:
                if _holds_at_end(formula, letter):
                    return True
                todo.append((progress(formula, [letter], simplify=False), room))
        while todo:
            f, room = todo.popleft()
            if f == FALSE or (f, room) in seen:
                continue
            seen.add((f, room))
            if len(seen) > MAX_NODES:
                return None
            for there in (room, *self.adjacent[room]):
                for letter in self.letters.get(there, ()):
                    if _holds_at_end(f, letter):
                        return True
                    todo.append((progress(f, [letter], simplify=False), there))
        return False


def _start_rooms(building: Building, start_floor: int | None) -> list[str]:
    """The rooms of the scene's initial positions (on ``start_floor`` when given); every room (of that
    floor) when there is none."""
    rooms = [r for r in building.rooms() if start_floor is None or r.floor == start_floor]
    keys = {(r.floor, r.id): r.key for r in rooms}
    starts = [keys.get((floor, int(building.floors[floor].room_map[row, col])))
              for row, col, floor in building.initial_cells if 0 <= floor < building.num_floors
              and building.floors[floor].room_map.size]
    found = list(dict.fromkeys(k for k in starts if k is not None))
    return found or [r.key for r in rooms]


def _holds_at_end(f: Formula, letter: Letter) -> bool:
    """Whether ``f`` holds at the last position of a word whose last letter is ``letter``."""
    if isinstance(f, Const):
        return f == TRUE
    if isinstance(f, Atom):
        return f.name in letter
    if isinstance(f, Not):
        return not _holds_at_end(f.arg, letter)
    if isinstance(f, And):
        return all(_holds_at_end(a, letter) for a in f.args)
    if isinstance(f, Or):
        return any(_holds_at_end(a, letter) for a in f.args)
    if isinstance(f, Implies):
        return not _holds_at_end(f.left, letter) or _holds_at_end(f.right, letter)
    if isinstance(f, Equiv):
        return _holds_at_end(f.left, letter) == _holds_at_end(f.right, letter)
    if isinstance(f, (Eventually, Always)):
        return _holds_at_end(f.arg, letter)
    if isinstance(f, (Until, Release)):
        return _holds_at_end(f.right, letter)
    if isinstance(f, Next):
        return False  # strong next: no next position
    if isinstance(f, WeakNext):
        return True
    raise TypeError(f"not a formula: {f!r}")
