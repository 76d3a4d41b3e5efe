"""Demonstrative back-references: *that bathroom*, *this room*, *those bedrooms*, *the same sink*; and
references to a choice (*a vase ... that vase*), which are refused.

A noun phrase introduced by a demonstrative never describes a fresh set of rooms or objects: it names
again something said before. Read as a fresh description (*the toilets in that bathroom* as the toilets in
any bathroom) it would silently widen the mission, so such a phrase is either resolved to the phrase it
points back to or refused, naming what could not be resolved.

Resolution (:func:`resolve`): among the phrases recorded before it, the one that ends last (ties: the
outermost, so *the bathroom next to the kitchen* is the bathroom, not the kitchen) whose entities fit the
head: same kind and one of the head's categories (any room for *that room*); for a room head, an object
phrase fits through the room(s) holding it (*the TV in the living room ... that room*). What the
demonstrative phrase itself adds (*that bathroom on the top floor*) must agree with it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.discourse import Grounded
from sgplan.llm.offline.names import Entity
from sgplan.llm.offline.nouns import Head


@dataclass(frozen=True)
class Resolved:
    """The entities a demonstrative phrase denotes, from the phrase it refers to."""

    entities: list[Entity]
    mode: Literal["the", "all"]
    """``the`` (one entity) or ``all`` (each of several: *those bedrooms*)."""
    room_scoped: bool
    antecedent: str
    """The text of the phrase referred to (for messages)."""


def is_choice(np: Grounded) -> bool:
    """Whether ``np`` leaves a choice open: one of several (*a vase*, *any bathroom*), or one alternative of
    an *or* list (*the kitchen or the bathroom*), which the robot may not take."""
    return np.alternative or (np.mode == "any" and len(np.entities) > 1)


def choice_refusal(said: str, np: Grounded, places: int) -> str | None:
    """The refusal for ``said`` pointing back to ``np`` when ``np`` is a choice and the reference would
    denote ``places`` > 1 different things (rooms for *there*, floors for *up there*) or one alternative
    of an *or* list: which one depends on the choice the robot makes, and reading it as any of them
    would silently allow another one than the one chosen. None when the reference is determined."""
    if not is_choice(np) or (places <= 1 and not np.alternative):
        return None
    return rf.choice_back_reference(said, np.phrase, np.alternative)


def _fitting(np: Grounded, head: Head, by_key: dict[str, Entity]) -> list[Entity] | None:
    """The entities of ``np`` as seen by ``head``, or None when ``np`` does not fit it."""
    if not np.entities:
        return None
    if all(e.kind == head.kind for e in np.entities):
        ents = np.entities
    elif head.kind == "room" and all(e.kind == "object" for e in np.entities):
        ents = list({e.room_key: by_key[e.room_key] for e in np.entities}.values())
    else:
        return None
    if head.categories and any(e.category not in head.categories for e in ents):
        return None
    return ents


def last_fitting(head: Head, named: Sequence[Grounded], before: int,
                 by_key: dict[str, Entity]) -> Grounded | None:
    """The phrase of ``named`` ending last before character ``before`` that ``head`` may point back to."""
    fits = [np for np in named if np.end <= before and np.phrase.lower() not in _PRONOUN_PHRASES
            and _fitting(np, head, by_key) is not None]
    return max(fits, key=lambda np: (np.end, -np.start), default=None)


def resolve(said: str, head: Head, plural: bool, described: list[Entity], references: Sequence[Grounded],
            before: int, by_key: dict[str, Entity], goal: bool = False) -> Resolved | str:
    """The phrase ``said`` (a demonstrative with ``head``, starting at character ``before``) resolved
    against the phrases recorded before it; ``described``: what the rest of the phrase allows (all of the
    head's entities narrowed by its qualifiers). Returns the entities, or the reason for a refusal.

    ``goal``: the phrase is a place to go to. *then back to that room* / *the same room* after two rooms
    (the room just visited, or the one before?) is refused there; *the sink in that room* is in the last."""
    earlier = [np for np in references if np.end <= before and np.phrase.lower() not in _PRONOUN_PHRASES]
    earlier.sort(key=lambda np: (np.end, -np.start), reverse=True)
    fitting = [(np, ents) for np in earlier if (ents := _fitting(np, head, by_key)) is not None]
    if goal and not head.categories and len({tuple(e.key for e in ents) for _, ents in fitting}) > 1:
        named = ", ".join(dict.fromkeys(f"'{np.phrase}'" for np, _ in fitting))
        return rf.which_room_again(said, named)
    for np, ents in fitting:
        keys = {e.key for e in described}
        if any(e.key not in keys for e in ents):
            return rf.demonstrative_disagrees(said, np.phrase, ", ".join(e.key for e in ents))
        several = len(ents) > 1
        if (choice := choice_refusal(said, np, len(ents))) is not None:
            return choice
        if several and not plural:
            return rf.demonstrative_of_several(said, np.phrase, ", ".join(e.key for e in ents))
        if plural and not several:  # "those bedrooms" after one bedroom: not what was named
            return rf.demonstrative_of_one(said, np.phrase, ents[0].key)
        scoped = np.room_scoped and all(e.kind == "object" for e in ents)
        return Resolved(list(ents), "all" if several else "the", scoped, np.phrase)
    return rf.demonstrative_of_nothing(said, "room" if head.kind == "room" else "object")


_PRONOUN_PHRASES = (*lx.PRONOUNS, "there")
