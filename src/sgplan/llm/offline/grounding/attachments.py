"""Deciding, against the scene, the attachments the words leave open (:class:`.syntax.tree.Attachment`).

- *the bedroom without a potted plant*: a description of the bedroom when several rooms are in question
  and the plant tells them apart (some hold one, some not); otherwise *without* is what to avoid.
- *the bedroom with the book and the vase*: more of its contents when the rooms with the book are several
  and the vase narrows them; when one room is left and it holds the vase too, it could also be another
  goal, which is refused; otherwise the vase is another goal.
- *the plant in the bedroom, the one in the office, and ...*: an apposition (which plant) when it names one
  the phrase does; otherwise (no plant is in both) the next item of the list.

The decision reads the phrase itself (its head and the qualifiers before the open words) and what was
named before the sentence, on a copy of the discourse: deciding records nothing.
"""

from __future__ import annotations

from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.grounding.discourse import Discourse, Where
from sgplan.llm.offline.grounding.phrases import ground_phrase
from sgplan.llm.offline.syntax.tree import Attachment


def describes(attachment: Attachment, disc: Discourse) -> bool:
    """Whether the open words of ``attachment`` describe its phrase (else they are read after it).

    Raises
    ------
    MissionError
        both readings fit (*the bedroom with the book and the vase* where one bedroom has both).
    """
    trial = disc.fork()
    rooms = ground_phrase(attachment.prefix, Where("qualifier"), trial).entities
    thing = ground_phrase(attachment.thing, Where("qualifier"), trial)
    if attachment.kind == "apposition":
        return bool(set(rooms) & set(thing.entities))
    if any(e.kind != "object" for e in thing.entities):
        return False
    if attachment.kind == "without":
        left = disc.vocab.lacking(rooms, thing.entities)
        return len(rooms) >= 2 and 0 < len(left) < len(rooms)
    holders = disc.vocab.containing(rooms, thing.entities, None)
    if len(rooms) > 1 and 0 < len(holders) < len(rooms):
        return True
    if len(rooms) == 1 and holders:
        said = disc.said(attachment.span.start, attachment.span.end)
        rf.refuse(rf.both_contents_or_goal(said, thing.phrase))
    return False
