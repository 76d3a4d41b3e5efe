"""An order about the place a statement just named: *the ground-floor bathroom is being cleaned, so keep out
of it*, *the kitchen floor is still wet, so don't go in there*.

The statement is set aside (:mod:`.context`); its pronoun is bound here, in the syntax, to the one room or
object the statement names, so that it cannot be read as the goal named last in the sentences before
(*Go to the office. The lobby is wet, so stay out of there.*: the lobby). The binding is made only where no
careful reader could take the pronoun otherwise: the order follows the statement in the same sentence,
after *so* (the statement is its reason); the statement names exactly one room or object of the scene; the
order holds exactly one *it*, *them* or *there*, which agrees with it (*it* one thing, *them* several,
*there* a room); *it* and *them* only when the place is the statement's subject or the speaker is (*I've just
mopped the kitchen, so keep out of it*; not *the cat is asleep in the lounge, so leave it alone*: the cat?).
Anything else is left as it was: read when nothing was named before, else refused.
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
    """The order (the token indexes ``order`` of ``r``, its joiner first) with its pronoun replaced by the
    words of the one phrase ``named`` in the statements set aside right before it (the last of which starts
    at ``subject``); ``None`` when the binding is not certain (see the module docstring)."""
    if not order or r.word(order[0]) != "so" or len(named) != 1:
        return None
    place = named[0]
    said = [k for k in order if r.word(k) in BOUND_PRONOUNS]
    if not isinstance(place, Described) or not isinstance(place.head, Head) or len(said) != 1:
        return None
    k = said[0]
    w, head = r.word(k), place.head
    agrees = (head.kind == "room" if w == "there" else head.plural == (w in lx.PLURAL_PRONOUNS))
    if not agrees or r.word(k - 1) in ("up", "down") or r.word(k + 1) == "'s":
        return None  # "up there" may be the floor; "it's": a statement, not the pronoun of an order
    if w != "there" and r.word(subject) not in lx.PEOPLE and r.toks[subject].start != place.span.start:
        return None  # "the cat is asleep in the lounge, so leave it alone": the cat, or the lounge?
    words = tuple(t for t in r.toks if place.span.start <= t.start and t.end <= place.span.end)
    toks = [t for j in order[1:] for t in (words if j == k else (r.toks[j],))]
    return replace(r, toks=tuple(toks))
