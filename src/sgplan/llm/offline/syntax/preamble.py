"""What a mission says before its first order: chit-chat (*Hi!*, *Okay, here's the plan.*, *I'm hungry, go
to the fridge.*) and where the robot is (*I'm downstairs right now.*).

People often open a mission with a sentence or a clause that asks nothing of the robot. Such leading
words are skipped only when they carry nothing the grammar could read: no room or object (nor an ID), no
verb of going or acting, no word with a role in the grammar (order, negation, conditions, floors,
quantities, references). Anything else is left to the parser, which reads it or refuses it; so a
skipped clause can never hold a goal, a place to avoid or a condition.
"""

from __future__ import annotations

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.floors import floor_words
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.syntax.tree import FloorSpec, RelativeFloor, StatedStart


def is_chitchat(r: Reader, start: int, end: int) -> bool:
    """Whether the words ``[start, end)`` carry no mission content: they start with a greeting, an
    interjection or the speaker (:data:`.lexicon.OPENERS`), and have no room or object noun of the scene,
    no ID, no verb the grammar reads as an action or refuses, no upstairs / downstairs, no word with a role
    in the grammar, and no article before anything but a word of talk or of a list (*the plan*, *the
    route*)."""
    if end <= start or r.word(start) not in lx.OPENERS:
        return False
    k = start
    while k < end:
        w, closing = r.word(k), r.phrase(k, lx.CLOSING)
        if r.at(k, "one", "more") and k > start:  # "Sorry, one more: ...": another request follows
            closing = ("one", "more")
        if r.at(k, "wake", "up") and k + 2 == end:  # "Robot, wake up.": the robot is called, nothing asked
            closing = ("wake", "up")
        if closing is not None or w == "," or (w == "there" and k > start and r.word(k - 1) in lx.GREETINGS):
            k += len(closing) if closing is not None else 1  # "Hi there, quick one": nothing said either
            continue
        if w in lx.ARTICLES:
            if k + 1 < end and (r.word(k + 1) in lx.TALK_NOUNS or r.word(k + 1) in lx.LIST_NOUNS):
                k += 1
                continue
            return False
        if (w.startswith(("room_", "object_")) or w in lx.POSITIVE_VERBS or w in lx.REFUSED_WORDS
                or w in lx.RELATIVE_FLOORS or (w in lx.STRUCTURAL and w not in lx.AUXILIARIES) or w.isdigit()
                or r.head(k) is not None):
            return False
        k += 1
    return True


def leading_clause(r: Reader) -> int:
    """How many words of a sentence's leading clauses (each up to and including its comma, or a spaced dash)
    are chit-chat to skip (*I'm hungry, go to the fridge*, *Alexa, sorry, robot, go ...*, *Quick favour - go
    to ...*); 0 if none or if nothing would be left."""
    start = 0
    while comma := next((k for k in range(start, len(r)) if r.word(k) in (",", "\u2014")), 0):
        if comma == start or comma == len(r) - 1 or not is_chitchat(r, start, comma):
            break
        start = comma + 1
    return start


def stated_start(r: Reader) -> StatedStart | None:
    """A sentence that only says where the robot is (*I'm downstairs right now*, *we are on the ground
    floor*, *you're upstairs*), or ``None``."""
    subject = r.phrase(0, lx.STATED_SUBJECTS)
    if subject is None:
        return None
    k = len(subject) + (1 if r.word(len(subject)) in lx.STATED_NOW else 0)
    floor: FloorSpec
    if r.word(k) in lx.RELATIVE_FLOORS:
        floor, end, said = RelativeFloor(r.word(k)), k + 1, r.word(k)
    else:
        j = k + (1 if r.word(k) in ("on", "at") else 0)
        j += 1 if r.word(j) == "the" else 0
        found = floor_words(r, j) if j > k else None
        if found is None:
            return None
        floor, end, said = found.node, found.end, " ".join(r.words[k : found.end])
    now = r.phrase(end, lx.NOW)
    end += len(now) if now else 0
    return StatedStart(floor, said) if end == len(r) else None
