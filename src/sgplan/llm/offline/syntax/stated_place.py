"""An order about the place a statement just named: *the ground-floor bathroom is being cleaned, so keep out
of it*, *the kitchen floor is still wet, so don't go in there*.

The statement is set aside (:mod:`.context`); its pronoun is bound here, in the syntax, to the one room or
object the statement names, so that it cannot be read as the goal named last in the sentences before
(*Go to the office. The lobby is wet, so stay out of there.*: the lobby). The binding is made only where no
careful reader could take the pronoun otherwise: the order follows the statement in the same sentence,
after *so* or a comma (the statement is its reason: *the lobby is wet, please stay out of there*); the
statement names exactly one room or object of the scene; the order holds exactly one *it*, *them* or
*there*, with no room or object named before it, and it agrees with the place (*it* one thing, *them*
several, *there* a room); *it* and *them* only when the place is the statement's subject or the speaker is
(*I've just mopped the kitchen, so keep out of it*; not *the cat is asleep in the lounge, so leave it
alone*: the cat?). Anything else is left as it was: read when nothing was named before, else refused.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.syntax.tree import Described, NounPhrase

BOUND_PRONOUNS = ("it", "them", "there")
"""The pronouns of an order that may point back to what the statement before it names."""


def bind_statement_pronoun(r: Reader, subject: int, order: list[int],
                           named: tuple[NounPhrase, ...]) -> Reader | None:
    """The order (the token indexes ``order`` of ``r``, its joiner *so* or its first word first) with its
    pronoun replaced by the words of the one phrase ``named`` in the statements set aside right before it (the
    last of which starts at ``subject``); ``None`` when the binding is not certain (see the module
    docstring)."""
    if not order or (r.word(order[0]) != "so" and r.word(order[0] - 1) != ",") or len(named) != 1:
        return None
    body = order[1:] if r.word(order[0]) == "so" else list(dict.fromkeys(order))
    place = named[0]
    said = [k for k in body if r.word(k) in BOUND_PRONOUNS]
    if not isinstance(place, Described) or not isinstance(place.head, Head) or len(said) != 1:
        return None
    k = said[0]
    w, head = r.word(k), place.head
    agrees = (head.kind == "room" if w == "there" else head.plural == (w in lx.PLURAL_PRONOUNS))
    if any(r.head(j) is not None for j in body if j < k):
        return None  # "..., go to the kitchen and avoid it": the kitchen, or what the statement named?
    if not agrees or r.word(k - 1) in ("up", "down") or r.word(k + 1) == "'s":
        return None  # "up there" may be the floor; "it's": a statement, not the pronoun of an order
    if w != "there" and r.word(subject) not in lx.PEOPLE and r.toks[subject].start != place.span.start:
        return None  # "the cat is asleep in the lounge, so leave it alone": the cat, or the lounge?
    words = tuple(t for t in r.toks if place.span.start <= t.start and t.end <= place.span.end)
    toks = [t for j in body for t in (words if j == k else (r.toks[j],))]
    return replace(r, toks=tuple(toks))
