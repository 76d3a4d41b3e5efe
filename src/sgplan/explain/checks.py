"""Scene-aware checks of a mission, run before any search and reported in words.

Everything here is computed from the label sets that actually occur on the free cells of the scene's
occupancy grid (:mod:`sgplan.explain.scene_labels`): rooms are exclusive and an object is reached only
from the cells of its reach region (:mod:`sgplan.scene.reach`). :func:`check_mission_in_scene` finds

- ``unsatisfiable``: no path anywhere in the scene satisfies the mission, whatever the start; the
  smallest set of top-level parts that cannot hold together is named ("Go to the kitchen. Never enter
  the kitchen.");
- ``unsatisfiable-from-start``: the start cell's own label already makes the mission impossible;
- ``unreachable-from-start``: a place the mission needs cannot be reached from the start at all, with the
  cause in words (no door to it, a way in too narrow for this robot and the largest radius that gets
  through, or no way at any radius: :mod:`sgplan.explain.causes`);
- ``blocked-by-forbidden``: what the mission needs can be reached from the start only through rooms it
  forbids (those rooms are named);
- ``impossible-part`` / ``vacuous`` / ``object-outside-room``: a state condition of the formula that no
  cell of the scene meets, a negated place the scene makes redundant ("and not in the kitchen" while in
  the bathroom), an object to reach from a room it is not in;
- ``satisfied-at-start``: the start already satisfies the mission (the optimal plan is to stay).

The first four are errors (:meth:`SceneCheck.raise_errors`), the next three warnings, the last a note.
An unsatisfiable mission names why its places cannot be used too (no room for the robot in them, no
door).
"""

from __future__ import annotations

import itertools
import logging
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from sgplan.errors import PlanningError, SgplanError, UnsatisfiableMissionError
from sgplan.explain.causes import (
    component_of,
    components_without,
    missing_from_start,
    why_no_free_cell,
    why_unreachable,
)
from sgplan.explain.patterns import condition_text, pattern_clauses
from sgplan.explain.referents import Referent, referents_of
from sgplan.explain.scene_labels import occurring_labels
from sgplan.explain.stages import forbidden_bits, restricted
from sgplan.logic.automaton import Automaton
from sgplan.logic.formula import (
    MAX_NESTING,
    And,
    Atom,
    Const,
    Equiv,
    Formula,
    Implies,
    Not,
    Or,
    atoms,
    conjuncts,
    depth,
    is_temporal,
    to_infix,
    walk,
)
from sgplan.logic.ltlf import ltlf_to_dfa
from sgplan.mission import Mission
from sgplan.planning.setups import reach_model_for
from sgplan.scene.grid import OccupancyGrid
from sgplan.scene.model import Building

log = logging.getLogger("sgplan")

FindingKind = Literal[
    "unsatisfiable", "unsatisfiable-from-start", "unreachable-from-start", "blocked-by-forbidden",
    "impossible-part", "vacuous", "object-outside-room", "satisfied-at-start",
]
ERRORS = ("unsatisfiable", "unsatisfiable-from-start", "unreachable-from-start", "blocked-by-forbidden")
NOTES = ("satisfied-at-start",)
MAX_CONFLICT_PARTS = 3
"""The largest set of top-level parts searched for a named conflict (beyond it: "the parts together")."""


@dataclass(frozen=True)
class Finding:
    """One result of the checks: its ``kind`` (see the module docstring) and a plain-English message."""

    kind: FindingKind
    message: str

    @property
    def severity(self) -> Literal["error", "warning", "note"]:
        return "error" if self.kind in ERRORS else "note" if self.kind in NOTES else "warning"


@dataclass(frozen=True)
class SceneCheck:
    """The findings of :func:`check_mission_in_scene`, errors first."""

    findings: tuple[Finding, ...]

    def of(self, severity: str) -> list[Finding]:
        return [f for f in self.findings if f.severity == severity]

    def raise_errors(self) -> None:
        """Raise for the first error finding, if any.

        Raises
        ------
        UnsatisfiableMissionError
            ``unsatisfiable`` (status ``"unsatisfiable"``, exit code 4).
        PlanningError
            ``unsatisfiable-from-start`` (status ``"invalid-start"``), ``unreachable-from-start`` or
            ``blocked-by-forbidden`` (status ``"infeasible"``).
        """
        for finding in self.of("error"):
            if finding.kind == "unsatisfiable":
                raise UnsatisfiableMissionError(finding.message)
            status = "invalid-start" if finding.kind == "unsatisfiable-from-start" else "infeasible"
            raise PlanningError(finding.message, status=status)

    def report(self, *, stop: bool = True) -> None:
        """Say the findings on the ``sgplan`` logger: a warning at WARNING (``warning: ...``), a note at
        INFO (``note: ...``); then, with ``stop``, raise the first error (:meth:`raise_errors`), else log
        each error as a warning that the mission cannot be planned.

        Raises
        ------
        PlanningError
            With ``stop``, as :meth:`raise_errors`.
        """
        for finding in self.findings:
            if finding.severity == "warning":
                log.warning(f"warning: {finding.message}")
            elif finding.severity == "note":
                log.info(f"note: {finding.message}")
            elif not stop:
                log.warning(f"warning: it cannot be planned: {finding.message}")
        if stop:
            self.raise_errors()

    def to_dict(self) -> list[dict[str, Any]]:
        """JSON-ready ``[{"kind", "severity", "message"}, ...]``."""
        return [{"kind": f.kind, "severity": f.severity, "message": f.message} for f in self.findings]


def check_mission_in_scene(
    mission: Mission,
    building: Building,
    start: tuple[int, int, int] | None = None,
    *,
    grid: OccupancyGrid | None = None,
    labels: np.ndarray | None = None,
    profile: str = "ltlf",
    robot_radius_m: float | None = None,
    reach_radius_m: float | None = None,
    reach_model: str | None = None,
) -> SceneCheck:
    """Check ``mission`` against ``building`` (and ``start``) before planning; see the module docstring.

    Parameters
    ----------
    mission, building:
        the mission and its scene (every proposition must name an entity of the building).
    start:
        ``(row, col, floor)``; without it only the start-independent checks run.
    grid, labels:
        the occupancy grid and label raster the plan will use (e.g. from
        :func:`sgplan.assembly.make_problem`); built from the radii when not given.
    profile:
        ``"ltlf"`` reads the start cell's label, ``"authors"`` does not.
    robot_radius_m, reach_radius_m:
        radii in metres for building ``grid`` / ``labels`` (default: the scene's).
    reach_model:
        where an object counts as reached (``"visible"`` or ``"box"``; default the profile's), for
        building ``labels`` and for saying why an object is reached from another room.

    Returns
    -------
    SceneCheck
        cheap: a few array passes over the grid (no search).
    """
    model = reach_model_for(profile, reach_model)
    if grid is None or labels is None:
        from sgplan.radii import resolve_radii
        from sgplan.scene.grid import build_occupancy_grid

        radii = resolve_radii(building, robot_radius_m, reach_radius_m)
        grid = build_occupancy_grid(building, radii.robot_m) if grid is None else grid
        labels = mission.labels(building, radii.reach_m, model) if labels is None else labels
    automaton = mission.automaton
    realizable = occurring_labels(labels, grid.traversable, automaton.num_labels)
    if not realizable.any():
        return SceneCheck(())
    entities = referents_of(list(automaton.aps), mission.propositions, building)
    context = _Context(mission, building, grid, labels, entities, realizable, model)
    # The part analysis recurses over the formula as written: a deeper one (a 500-term conjunction as
    # nested pairs) gets only the whole-mission checks below, which work on the automaton (_readable).
    findings = context.part_findings()
    whole = restricted(automaton, realizable)
    if not whole.live_states()[whole.initial]:
        findings.insert(0, Finding("unsatisfiable", context.conflict()))
    elif start is not None:
        findings[:0] = context.start_findings(whole, start, profile)
    return SceneCheck(tuple(sorted(findings, key=lambda f: ("error", "warning", "note").index(f.severity))))


@dataclass
class _Context:
    mission: Mission
    building: Building
    grid: OccupancyGrid
    labels: np.ndarray
    entities: dict[str, Referent]
    realizable: np.ndarray
    reach_model: str

    def describe(self, name: str) -> Referent:
        return self.entities[name]

    def cond(self, f: Formula) -> str:
        return condition_text(f, self.describe)

    def label_words(self, label: int) -> str:
        aps = self.mission.automaton.aps
        true = [Atom(p) for i, p in enumerate(aps) if label >> i & 1]
        if not true:
            return "in none of the mission's places"
        return self.cond(true[0] if len(true) == 1 else And(tuple(true)))

    # -- state conditions the scene makes impossible or redundant --------------------------------------
    def _readable(self) -> bool:
        """Whether the parts of the formula as written can be read: it names only the automaton's
        propositions and nests no deeper than automata are built for (the reading recurses)."""
        formula, aps = self.mission.formula, self.mission.automaton.aps
        return formula is not None and depth(formula) <= MAX_NESTING and all(p in aps for p in atoms(formula))

    def part_findings(self) -> list[Finding]:
        formula = self.mission.formula
        aps = self.mission.automaton.aps
        if formula is None or not self._readable():
            return []
        present = np.flatnonzero(self.realizable)
        index = {p: i for i, p in enumerate(aps)}
        findings: list[Finding] = []
        inner: set[int] = set()
        for node in walk(formula):
            if not isinstance(node, And) or is_temporal(node) or id(node) in inner:
                continue
            parts = conjuncts(node)
            inner.update(id(n) for n in walk(node) if n is not node)
            findings += self._and_findings(node, parts, present, index)
        return findings

    def _and_findings(self, node: And, parts: list[Formula], present: np.ndarray,
                      index: dict[str, int]) -> list[Finding]:
        value = _evaluate(node, present, index)
        outside = self._objects_outside_rooms(parts)
        if not value.any():
            why = f" ({'; '.join(outside)})" if outside else ""
            return [Finding("impossible-part", f"no place in this scene is {self.cond(node)}{why}")]
        # Seen from another room, an object is reached through a door (in sight) or, in the authors'
        # window, through a wall.
        through = "a wall" if self.reach_model == "box" else "a door, in sight of it"
        findings = [
            Finding("object-outside-room", f"{o}: it is reached from there only through {through}")
            for o in outside
        ]
        for k, part in enumerate(parts):
            # Only a negated place can be a misreading ("... and not in the kitchen" while in the bathroom);
            # a redundant positive one ("the sink, in the bathroom") is just precise.
            if not (isinstance(part, Not) and isinstance(part.arg, Atom)):
                continue
            if not _evaluate(part.arg, present, index).any():  # a place no robot position is in
                findings.append(Finding("vacuous", f"'{self.cond(part)}' changes nothing: no place of this "
                                        f"scene the robot can be at is {self.cond(part.arg)}"))
                continue
            others = parts[:k] + parts[k + 1:]
            rest = others[0] if len(others) == 1 else And(tuple(others))
            if not (_evaluate(rest, present, index) & ~_evaluate(part, present, index)).any():
                findings.append(
                    Finding(
                        "vacuous",
                        f"'{self.cond(part)}' changes nothing in '{self.cond(node)}': every place of this "
                        "scene that "
                        f"is {self.cond(rest)} already is (one room at a time; an object is reached only "
                        "near it)",
                    )
                )
        return findings

    def _objects_outside_rooms(self, parts: list[Formula]) -> list[str]:
        rooms = [
            self.describe(p.name)
            for p in parts
            if isinstance(p, Atom) and self.describe(p.name).kind == "room"
        ]
        objects = [self.describe(p.name) for p in parts
                   if isinstance(p, Atom) and self.describe(p.name).kind == "object"]
        return [f"{o.phrase()} is not in {r.phrase()}" for r in rooms for o in objects if o.room_key != r.key]

    # -- the whole mission -------------------------------------------------------------------------------
    def conflict(self) -> str:
        """Why no path of the scene satisfies the mission: the smallest set of parts that cannot hold."""
        head = f"no path in scene {self.building.name!r} satisfies the mission, from any start"
        formula = self.mission.formula
        aps = self.mission.automaton.aps
        if formula is None or not self._readable():
            return f"{head}: its automaton accepts no path of places this scene has"
        parts = conjuncts(formula)
        rooms = [p for p in aps if self.describe(p).kind == "room"]
        for size in range(1, min(len(parts), MAX_CONFLICT_PARTS) + 1):
            for subset in itertools.combinations(parts, size):
                sub = subset[0] if size == 1 else And(subset)
                dfa = ltlf_to_dfa(sub, aps=aps, exclusive=[rooms] if len(rooms) > 1 else ())
                small = restricted(dfa, self.realizable)
                if not small.live_states()[small.initial]:
                    said = " ".join(self._sentences(subset))
                    which = "this part cannot hold" if size == 1 else "these parts cannot all hold"
                    return f"{head}: {which} in this scene: {said}{self._absent_causes(subset)}"
        return f"{head}: its parts together cannot hold in this scene{self._absent_causes([formula])}"

    def _absent_causes(self, parts: Sequence[Formula]) -> str:
        """`` Why: ...`` for each place of ``parts`` that holds on no free cell of the scene (nothing when
        every one does: the conflict is then in the parts themselves)."""
        aps = list(self.mission.automaton.aps)
        present = int(np.bitwise_or.reduce(np.flatnonzero(self.realizable))) if self.realizable.any() else 0
        named = {a for part in parts for a in atoms(part)}
        causes = [
            why_no_free_cell(self.building, self.grid, self.describe(p), (self.labels >> i & 1).astype(bool))
            for i, p in enumerate(aps)
            if p in named and not present >> i & 1 and self.describe(p).kind != "unknown"
        ]
        return "".join(f" Why: {cause}." for cause in causes)

    def _sentences(self, parts: Sequence[Formula]) -> list[str]:
        out = []
        for part in parts:
            clauses = pattern_clauses(part, self.describe)
            out += clauses if clauses is not None else [f"'{to_infix(part)}'."]
        return out

    def start_findings(self, whole: Automaton, start: tuple[int, int, int], profile: str) -> list[Finding]:
        row, col, floor = start
        floors, rows, cols = self.grid.shape
        if (
            not (0 <= floor < floors and 0 <= row < rows and 0 <= col < cols)
            or not self.grid.traversable[floor, row, col]
        ):
            return []  # the planner says why the start cannot be used
        label = int(self.labels[floor, row, col])
        q0 = int(whole.table[whole.initial, label]) if profile == "ltlf" else whole.initial
        where = f"start (row {row}, col {col}, floor {floor}), {self.label_words(label)},"
        live = whole.live_states()
        if not live[q0]:
            return [
                Finding(
                    "unsatisfiable-from-start",
                    f"{where} violates the mission: from there no path can satisfy it; start elsewhere",
                )
            ]
        if whole.accepting[q0]:
            return [
                Finding(
                    "satisfied-at-start",
                    f"{where} already satisfies the mission: the optimal plan is to stay there (0 m)",
                )
            ]
        blocked = self._blocked(whole, start, label, profile)
        return [blocked] if blocked is not None else []

    def _blocked(
        self, whole: Automaton, start: tuple[int, int, int], label: int, profile: str
    ) -> Finding | None:
        """Whether avoiding the forbidden rooms cuts the start off from what the mission needs (or, when
        the start is cut off from it anyway, why: :func:`unreachable_finding`)."""
        aps = self.mission.automaton.aps
        forbidden = [i for i in forbidden_bits(whole, np.flatnonzero(self.realizable))
                     if self.describe(aps[i]).kind == "room"]
        if not forbidden:
            return None
        room_ids = [self.building.room(uuid=self.mission.propositions[aps[i]].uuid).id for i in forbidden]

        def reachable_labels(blocked_ids: list[int]) -> np.ndarray:
            area = component_of(components_without(self.grid, blocked_ids), start)
            return occurring_labels(self.labels, area, self.mission.automaton.num_labels)

        def live_on(labels: np.ndarray) -> bool:
            local = restricted(self.mission.automaton, labels)
            return bool(local.live_states()[int(local.table[local.initial, label]) if profile == "ltlf"
                                            else local.initial])

        near = reachable_labels(room_ids)
        if live_on(near):
            return None
        if not live_on(reachable_labels([])):  # cut off with every room open: the rooms are not the cause
            return unreachable_finding(self.mission, self.building, self.grid, self.labels, start)
        present = np.bitwise_or.reduce(np.flatnonzero(self.realizable))
        near_bits = np.bitwise_or.reduce(np.flatnonzero(near))
        missing = [
            aps[i]
            for i in range(len(aps))
            if present >> i & 1 and not near_bits >> i & 1 and i not in forbidden
        ]
        culprits = [
            aps[i]
            for i, rid in zip(forbidden, room_ids)
            if np.bitwise_or.reduce(np.flatnonzero(reachable_labels([r for r in room_ids if r != rid])))
            & ~near_bits
        ]
        goals = "; ".join(self.describe(p).phrase() for p in missing) or "what the mission needs"
        rooms = "; ".join(self.describe(p).phrase() for p in (culprits or [aps[i] for i in forbidden]))
        return Finding(
            "blocked-by-forbidden",
            f"from start {start}, {goals} can be reached only through rooms the mission forbids: {rooms}",
        )


def unreachable_finding(mission: Mission, building: Building, grid: OccupancyGrid, labels: np.ndarray,
                        start: tuple[int, int, int]) -> Finding | None:
    """``unreachable-from-start``, naming why each place the mission needs (not one it forbids) that holds
    on some free cell but on none reachable from ``start`` cannot be reached (:mod:`sgplan.explain.causes`);
    ``None`` when there is no such place (the mission fails for another reason)."""
    automaton = mission.automaton
    realizable = occurring_labels(labels, grid.traversable, automaton.num_labels)
    forbidden = set(forbidden_bits(restricted(automaton, realizable), np.flatnonzero(realizable)))
    entities = referents_of(list(automaton.aps), mission.propositions, building)
    needed = [i for i in missing_from_start(grid, labels, start, automaton.aps)
              if i not in forbidden and entities[automaton.aps[i]].kind != "unknown"]
    if not needed:
        return None
    causes = [why_unreachable(building, grid, start, entities[automaton.aps[i]],
                              (labels >> i & 1).astype(bool)) for i in needed]
    return Finding("unreachable-from-start",
                   f"no path from start {start} satisfies the mission: {'; and '.join(causes)}")



def _evaluate(f: Formula, labels: np.ndarray, index: dict[str, int]) -> np.ndarray:
    """The truth of the state condition ``f`` on each label of ``labels`` (bool array)."""
    ops: dict[type, Callable[..., np.ndarray]] = {
        Not: lambda a: ~a, Implies: lambda a, b: ~a | b, Equiv: lambda a, b: a == b,
    }
    if isinstance(f, Atom):
        return (labels >> index[f.name]) & 1 == 1
    if isinstance(f, Const):
        return np.full(labels.shape, f.value)
    values = [_evaluate(c, labels, index) for c in f.children()]
    if isinstance(f, And):
        return np.logical_and.reduce(values)
    if isinstance(f, Or):
        return np.logical_or.reduce(values)
    if type(f) in ops:
        return ops[type(f)](*values)
    raise SgplanError(f"internal error: {to_infix(f)} is not a state condition")
