"""A group restated member by member: *both potted plants, the one by the couch and the one in the office*.

The phrases after the group say again, one by one, what the group named; read as the group, they would be
refused as named twice. They are read in its place only when they restate it exactly: each is *the one(s)
...*, each names members of the group only, no two name the same member, and together they name every
member. Anything else is left to the caller's refusal (named twice: it is not clear what is meant).
"""

from __future__ import annotations

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.grounding.discourse import Grounded


def members_restated(phrases: list[Grounded]) -> list[Grounded]:
    """``phrases`` with a group dropped when the phrases right after it restate it member by member (see the
    module docstring); ``phrases`` unchanged otherwise."""
    for n, group in enumerate(phrases):
        members = {e.key for e in group.entities}
        if group.mode != "all" or len(members) < 2:
            continue
        named: set[str] = set()
        k = n + 1
        while k < len(phrases) and named != members and restates_one(phrases[k], members, named):
            named |= {e.key for e in phrases[k].entities}
            k += 1
        if k > n + 2 and named == members:
            return [*phrases[:n], *phrases[n + 1:]]
    return phrases


def restates_one(phrase: Grounded, members: set[str], named: set[str]) -> bool:
    """Whether ``phrase`` is *the one(s) ...* naming members of the group not named yet."""
    words = phrase.phrase.lower().split()
    keys = {e.key for e in phrase.entities}
    return (len(words) > 1 and words[0] == "the" and words[1] in lx.ANAPHORIC_ONE and bool(keys)
            and keys <= members and not keys & named)
