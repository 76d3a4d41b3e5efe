"""The noun-phrase slot of the grammar: its rule set, the entry that tries it, and the words every noun
phrase rule reads first (the head noun, a number).

The rules of the slot are registered by :mod:`.phrases`; the qualifiers (:mod:`.qualifiers`), which nest a
noun phrase after their preposition (*the bathroom next to the bedroom*), read it here, so that the
recursion of the grammar (a noun phrase holds qualifiers, a qualifier holds a noun phrase) is no import
cycle between the two modules of rules.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal, unreadable
from sgplan.llm.offline.syntax.rules import RuleSet
from sgplan.llm.offline.syntax.tree import HeadRef, NounPhrase, OneHead, Role
from sgplan.llm.offline.text import is_clock_time

NOUN_PHRASES: RuleSet[NounPhrase] = RuleSet("noun phrase")


def noun_phrase(r: Reader, i: int, role: Role, given: Head | None = None) -> Parse[NounPhrase]:
    """One noun phrase at ``i`` (``role``: where it occurs); ``given``: what *the one* means here (an
    apposition's or an exception's head)."""
    if i >= len(r):
        return Refusal(rf.expected_phrase_at_end())
    return NOUN_PHRASES.first(r, i, role, given)


def place_phrase(r: Reader, i: int, role: Role) -> Match[NounPhrase] | None:
    """The noun phrase at ``i`` when one starts there and it is no pronoun (*the kitchen*, *office chair*):
    a place said first, before its verb (:mod:`.fronted`, :mod:`.object_first`, :mod:`.needs`)."""
    said = noun_phrase(r, i, role) if r.np_starts(i) and r.word(i) not in lx.PRONOUNS else None
    return said if isinstance(said, Match) else None


def names_scene(r: Reader, start: int, end: int) -> bool:
    """Whether a head noun of the scene (a room or object) starts within the words ``[start, end)``."""
    return any(r.head(j) is not None for j in range(start, end))


def count_word(r: Reader, i: int) -> int | None:
    """The number said at ``i`` (*two*, *3*; not *one of*), or ``None``."""
    w = r.word(i)
    if w in lx.NUMBER_WORDS and (w != "one" or r.word(i + 1) != "of"):
        return lx.NUMBER_WORDS[w]
    return int(w) if w.isdigit() else None


def exact_count(r: Reader, i: int) -> tuple[int | None, int]:
    """The number of things a room's contents say at ``i`` (*two*, *only one*, *a single*, *just the one*)
    and where the noun starts, or ``None`` and ``i``."""
    single = r.phrase(i, lx.SINGLE_COUNT)
    if single is not None and r.head(i + len(single)) is not None:
        return 1, i + len(single)
    k = i + (1 if r.word(i) in lx.ONLY_WORDS else 0)  # "where there is only one sink": exactly one
    count = count_word(r, k)
    return (count, k + 1) if count is not None else (None, i)


def head_noun(r: Reader, i: int, one: OneHead | None) -> Parse[HeadRef]:
    """The head noun at ``i``: a category of the scene (or a synonym), *one(s)* (``one`` says of what),
    or a refusal naming the word."""
    w = r.word(i)
    if w in lx.ANAPHORIC_ONE:
        if one is None or (one.given is None and not one.from_context):
            return Refusal(rf.one_without_kind(w))
        return Match(replace(one, plural=w == "ones"), i + 1)
    if one is not None and one.from_context and w in lx.ORDINAL_ALONE_BEFORE:
        return Match(one, i)  # "back to the first": an ordinal alone, of the kind named last
    if w in lx.REFUSED_WORDS:
        return Refusal(rf.cannot_understand(lx.REFUSED_WORDS[w]))
    if w in lx.FLOOR_ORDINALS or w in lx.FLOOR_NAMED or w in lx.FLOOR_TOP:
        return Refusal(rf.ordinal_not_of_a_floor(w))
    head = r.head(i)
    if head is None and i >= len(r):
        return Refusal(rf.expected_phrase_after(r.word(i - 1)))
    if head is None and (not w[:1].isalpha() or is_clock_time(w)):
        return unreadable(r, i)
    if head is None:
        return Refusal(rf.unknown_noun(w, r.nouns.category_names("room"), r.nouns.category_names("object")))
    return Match(head, i + head.words)


def foreign_word(r: Reader, i: int) -> bool:
    """Whether the word at ``i`` may name a thing the scene does not hold: a word, no head noun of the
    scene, no word of the grammar, and not a misspelt name of the scene (*the vse on the table* is refused,
    never read as the table)."""
    w = r.word(i)
    return (w.isalpha() and r.head(i) is None and w not in lx.THING_STOPS
            and (r.spelling is None or not r.spelling.may_be_a_misspelt_name(w)))


def superlative(word: str) -> bool:
    """Whether ``word`` compares things (*heaviest*, *ripest*, *cleanest*, *most*): no scene says which."""
    if word in lx.SUPERLATIVES:
        return True
    return len(word) > 5 and word.endswith("est") and word not in lx.NOT_SUPERLATIVE
