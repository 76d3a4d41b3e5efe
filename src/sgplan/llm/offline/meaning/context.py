"""The state of reading one sentence into steps and constraints, beside the mission's discourse.

:class:`SentenceContext` holds what one sentence's items pass on to the items after them: the room of the
sentence (*In the kitchen, ...*), the steps of the sentence it continues, a pending *only after that* or
*on the way*, the rooms of a comma-joined step, and whether it said *last*.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from sgplan.llm.offline.grounding.discourse import Discourse, FloorReading
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.tasks import Step, Task
from sgplan.logic.formula import And, Atom, Formula, atoms
from sgplan.logic.tokens import action_entity


@dataclass
class SentenceContext:
    """See the module docstring. ``start``: the character offset where the sentence starts."""

    disc: Discourse
    start: int
    scope: list[Entity] = field(default_factory=list)
    prior_steps: list[Step] = field(default_factory=list)
    """The steps of the previous sentence when this one continues its sequence (*... Then ...*)."""
    strict_pending: bool = False
    """*only after that* / *only then* was said: the next action is strictly after the step before."""
    waypoint_pending: bool = False
    """*On the way (there),* was said: the next action comes before the goal named last."""
    carried_rooms: list[Entity] = field(default_factory=list)
    """The rooms of the step before a comma that made a sequence (*go to the kitchen, take a bottle, then
    ...*): objects of the next action are looked for there first (elsewhere if none is there)."""
    said_last: bool = False
    """The sentence ended with *last* (*visit the office last*): its last step follows all else."""
    said_first: bool = False
    """A step of the sentence was said *first* with no goal before it (*go to the garage first*): it comes
    before all the goals of the sentences after it too."""
    soft_scope: list[Entity] = field(default_factory=list)
    """The rooms of the condition whose consequent is being read."""
    previous_room: list[Entity] = field(default_factory=list)
    """The one room of the step before the action being read, when that action starts a step of its own
    (:attr:`.Where.previous`)."""
    listed_room: list[Entity] = field(default_factory=list)
    """In a sentence of independent tasks (:attr:`listed`), the rooms the tasks said before the action being
    read in its step go to (:attr:`.Where.listed_after`)."""
    floor_scope: tuple[FloorReading, int] | None = None
    """*While you're upstairs, ...* / *On the top floor, ...* / a list's heading *Top floor tasks*: the floors
    of the sentence's goals (and places to avoid), and where the sentence starts."""
    listed: bool = False
    """The sentence is a list announced before a colon (*three things: A, B and C*): its actions are
    independent tasks, an object of one is not looked for in the room of another."""

    def step_rooms(self, step: Step) -> list[Entity]:
        """The rooms ``step`` sends the robot to, and the sentence's room: where the objects named next in
        the same step are looked for."""
        keys = [a.name[len("enter("):-1] for t in step for m in t.members
                for a in (m.args if isinstance(m, And) else (m,))
                if isinstance(a, Atom) and a.name.startswith("enter(")]
        return [self.disc.vocab.by_key[k] for k in dict.fromkeys(keys)] + self.scope

    def rooms_of(self, members: list[Formula]) -> list[Entity]:
        """The rooms that the state formulas ``members`` put the robot in (their own or their objects')."""
        keys = [action_entity(a) for m in members for a in atoms(m)]
        by_key = self.disc.vocab.by_key
        return [by_key[k] for k in dict.fromkeys(by_key[k].room_key for k in keys if k in by_key)]

    def task_is_in(self, task: Task, room: Formula) -> bool:
        """Whether doing ``task`` means being in ``room`` (an ``enter(...)`` atom): each of its members is
        that room or an object in it (an object is reached only from its room)."""
        if not isinstance(room, Atom) or not room.name.startswith("enter("):
            return False
        key = room.name[len("enter("):-1]

        def inside(member: Formula) -> bool:
            names = [a.name for a in (member.args if isinstance(member, And) else (member,))
                     if isinstance(a, Atom)]
            return any(n == room.name or (n.startswith("reach(")
                                          and self.disc.vocab.by_key[n[len("reach("):-1]].room_key == key)
                       for n in names)
        return all(inside(m) for m in task.members)
