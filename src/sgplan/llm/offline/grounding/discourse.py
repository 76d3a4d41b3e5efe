"""The discourse state of grounding: what the mission has named so far, and the context of a phrase.

:class:`Discourse` is the explicit state that back-references read (*it*, *there*, *that bathroom*, *the
other one*, *upstairs* after a goal on another floor): every grounded phrase in the order it was read, the
robot's start floor, the floors the mission stays on, the last step of the previous sentence.
:class:`Where` is the context one phrase is grounded in: its role, the rooms its objects are looked for
in, the floor a verb or a floor move put it on.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass, field

from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.names import Entity, SceneVocabulary
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax.tree import Mode, Role
from sgplan.llm.offline.tasks import Step

_OPTIONAL = re.compile(r"\b(?:optional|optionally)\b", re.IGNORECASE)
"""Words of a remark that make a step optional."""


@dataclass
class Grounded:
    """A grounded noun phrase: the text and span it came from and the entities it denotes.

    ``mode``: ``the`` (exactly one entity), ``any`` (one of them will do), ``all`` (each of them).
    ``room_scoped``: the objects were located through a room (``the sink in the kitchen``, ``the
    kitchen's sink``, or the room of the same step), so reaching them also requires being in that room.
    """

    phrase: str
    start: int
    end: int
    entities: list[Entity]
    mode: Mode
    room_scoped: bool
    role: Role
    count: int | None = None
    """How many entities the phrase said ("the two beds"), if it said so."""
    generic: bool = False
    """The head noun was *room* / *place* (any room): *the one with ...* after it means any room too."""
    alternative: bool = False
    """One alternative of an *or* list (*the kitchen or the bathroom*): a back-reference to it is not
    determined (see :func:`.backref.choice_refusal`)."""
    choice_of: str | None = None
    """A pronoun whose antecedent is a choice: why it is refused if it is made a goal (*put it in Y* only
    carries it)."""
    mentioned: bool = False
    """A pronoun whose antecedent was named only in words set aside (*I think the bottle upstairs is empty, so
    take it to the kitchen*): the thing is not in hand, so it is a goal too."""
    floor: bool = False
    """A floor named as a place (*the top floor*: its rooms); *there* / *up there* / *on that floor* after it
    mean that floor."""


@dataclass
class Discourse:
    """What grounding knows of the mission read so far (see the module docstring)."""

    vocab: SceneVocabulary
    text: str
    start_floor: int | None
    references: list[Grounded] = field(default_factory=list)
    confined: frozenset[int] | None = None
    """The floors the mission stays on (*stay on this floor*): goals are grounded there."""
    last_step: Step = field(default_factory=list)
    """The last step with goals of the previous sentence (what *done that* refers to)."""
    last_steps: int = 0
    """How many steps with goals the previous sentence had."""
    announced: Head | None = None
    """The head noun that announced the list of the sentence being read (*water these plants: the one in
    the office and ...*): what *the one* is when nothing was named before."""

    set_aside: list[str] = field(default_factory=list)
    """Words of the mission set aside unread (context, a list's heading), as typed: said back."""
    mentions: list[Grounded] = field(default_factory=list)
    """The rooms and objects named in words set aside (*Grandpa's napping in the bedroom*): *there* may point
    back to them."""
    done_before: list[Grounded] = field(default_factory=list)
    """Goals said after the goal they come before (*go to Y only after X*: X), which *there* does not point
    back to as the last place (refused: X, named last, or Y, gone to last?)."""
    ordinals_from: int | None = None
    """Where *the first floor* counts from when the translator tries both ways (0: the lowest floor, US
    style; 1: the floor above the ground floor, British style); ``None``: from the text
    (:func:`.floors.british_ordinal`)."""
    kept_until: set[str] = field(default_factory=set)
    """The rooms kept out of until a goal (*don't go into the dining room until you've checked the
    microwave*): *in there* after that goal may mean them (:func:`.places.there_rooms_holding`)."""
    first_said: str | None = None
    """The words of a sentence whose goals come *first* with no goal said before them (*First, go to the
    garage.*, *Garage first:*): the goals of a later sentence must come after them (refused when it does not
    go on from them: its place after them would be lost)."""

    def record(self, phrase: Grounded) -> Grounded:
        """Remember ``phrase`` (a back-reference may point to it) and return it."""
        self.references.append(phrase)
        return phrase

    def put_aside(self, said: str) -> None:
        """Say back ``said`` (words of the mission, as typed) as set aside unread, once; words that make a
        step optional (*..., but that's optional*) are refused instead, as no goal can be optional."""
        if _OPTIONAL.search(said):
            rf.refuse(rf.optional_remark(said))
        if said not in self.set_aside:
            self.set_aside.append(said)

    def fork(self) -> Discourse:
        """A copy to try a reading on, which the original does not see."""
        return Discourse(self.vocab, self.text, self.start_floor, copy.copy(self.references), self.confined,
                         self.last_step, self.last_steps, self.announced, list(self.set_aside),
                         list(self.mentions), list(self.done_before), self.ordinals_from,
                         set(self.kept_until), self.first_said)

    def said(self, start: int, end: int) -> str:
        """The mission text between two character offsets."""
        return self.text[start:end]

    def goals_before(self, start: int | None = None) -> list[Grounded]:
        """The phrases read as goals (with entities), before character ``start`` when given."""
        return [g for g in self.references
                if g.role == "goal" and g.entities and (start is None or g.start < start)]

    def last_goal(self) -> Grounded | None:
        """The goal named last."""
        goals = self.goals_before()
        return max(goals, key=lambda g: g.start) if goals else None


@dataclass(frozen=True)
class FloorReading:
    """The floors some words name, and, when they are counted from the start floor but could be counted from
    where the goal named before them is (*upstairs* after a goal on another floor), that second reading:
    the two must pick the same entities (:func:`.floors.on_floors`). ``unknown``: the words count from a start
    floor that is not known (then ``floors`` are all those they could name, and they are read only where
    they cannot change which entity is meant)."""

    floors: frozenset[int]
    second: frozenset[int] | None = None
    said: str = ""
    after: str = ""
    unknown: bool = False


@dataclass(frozen=True)
class Where:
    """The context a phrase is grounded in.

    ``scope``: the rooms of the step (or of the sentence, *In the kitchen, ...*) its objects are looked for
    in; ``lenient``: elsewhere too when none is there. ``soft_scope``: the rooms of a condition (a definite
    object of its consequent that fits several is the one there). ``floor``: the floor a verb said (*go
    upstairs to ...*: the first phrase only); ``action_floor``: the floors of a floor move (*go upstairs and
    ...*: every goal) and the character offset where that action starts. ``going_back``: *go back there*.
    ``objects``: a pronoun must name objects (after *put* / *bring*). ``revisit``, ``previous``: see the
    fields.
    """

    role: Role
    scope: tuple[Entity, ...] = ()
    lenient: bool = False
    soft_scope: tuple[Entity, ...] = ()
    floor: FloorReading | None = None
    action_floor: tuple[FloorReading, int] | None = None
    going_back: bool = False
    objects: bool = False
    revisit: bool = False
    """*again* / *go back to*: a definite phrase that fits several is the one named before as a goal."""
    rooms: bool = False
    """A pronoun must name a room (*the toilet of it*, *the sink in it*)."""
    previous: tuple[Entity, ...] = ()
    """The one room of the step just before this one (*go to the bedroom with the vase, then check the
    plant*): a definite object that fits several is the one there, when exactly one is."""
    listed_after: tuple[Entity, ...] = ()
    """In a sentence of tasks in no order, the rooms the tasks said before this one go to (*In the lobby
    check the vases, in any order*): an object phrase that fits some but not all of its kind there is
    refused (the ones there, or any?); the tasks being independent, none is looked for there."""
