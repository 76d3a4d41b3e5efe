"""An order said with its place first and its verb last, as learners whose languages put the verb at the end
and operators' notes write it: *Garage chair first sit, then office keyboard.*, *Dining room's chairs, both
of them you will visit.*, *bed check*, *sink chk -> LR couch*, *First the teddy bear in the living room you
go to.*

Each clause of the sentence (between commas, *then*, arrows and semicolons) that is only a place (a phrase
naming a room or object of the scene, after *then* / *and* / *first* at most), then at most *first* / *too*,
*you* with *will* / *must* / *should* / *can*, and one verb of :data:`_VERBS` closing the clause (with its
particle: *go to*, *sit on*) is read with the verb first (*sit on garage chair first*); the words keep their
places in the text, so that refusals quote them. A clause with anything else after the verb, a verb that is
no order (*the kitchen is ...*), a place opening with *every* / *each* / *no* / *any* (*every kit visit =>
DR after*: a rule), and a sentence whose clauses are joined by bare commas (*DR tbl wipe, kit, DR tbl wipe
again*: in which order?) are left as they are.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline.syntax.noun_slot import names_scene, place_phrase
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.text import Tok

_VERBS = {"check": (), "visit": (), "water": (), "wipe": (), "dust": (), "touch": (), "see": (),
          "take": (), "grab": (), "sit": ("on",), "go": ("to",), "look": ("at",)}
"""Verbs read after their place, with the particle they take before it when none is said (not *clean*, a
state as well: *kitchen clean* may say the kitchen is clean)."""
_LEADS = frozenset({"then", "and", "first", "please", "also"})
_AFTER_PLACE = frozenset({"first", "too", "also", "again"})
_AUXILIARIES = frozenset({"will", "must", "should", "can"})
_PARTICLES = frozenset({"to", "on", "at", "in", "into"})
_BOUNDARIES = frozenset({",", ";", ":", "then", "and", ".", "!", "\u2192", "->"})
_RULE_WORDS = frozenset({"every", "each", "no", "any"})
"""Opening the place, they make it a rule or a choice (*every kit visit => DR after*), not a goal."""


def object_first(r: Reader) -> Reader:
    """``r`` with each clause said place-first and verb-last turned verb-first (see the module docstring)."""
    toks = list(r.toks)
    scope = r.words.index(",") if r.word(0) == "in" and "," in r.words else -1  # "In the kitchen, ..."
    if any(r.word(k) == "," and k != scope and r.word(k + 1) not in ("then", "and") for k in range(len(r))):
        return r  # "DR tbl wipe, kit, DR tbl wipe again": a list of steps in no said order (refused)
    start = 0
    while start < len(r):
        end = next((k for k in range(start, len(r)) if r.word(k) in _BOUNDARIES), len(r))
        said = turned_clause(r, r.skip(start, _LEADS), end)
        if said is not None:
            toks[r.skip(start, _LEADS):end] = said
        start = end + 1
    return replace(r, toks=tuple(toks)) if toks != list(r.toks) else r


def turned_clause(r: Reader, start: int, end: int) -> list[Tok] | None:
    """The tokens of the clause ``[start, end)`` verb-first when it is said place-first and verb-last, or
    ``None``."""
    e = end
    while e > start and r.word(e - 1) in _AFTER_PLACE:
        e -= 1
    after = list(range(e, end))
    particle = e - 1 if r.word(e - 1) in _PARTICLES else None
    e -= particle is not None
    verb = e - 1
    if r.word(verb) not in _VERBS:
        return None
    e = verb - (r.word(verb - 1) in _AUXILIARIES and r.word(verb - 2) == "you")
    e -= r.word(e - 1) == "you"
    while e > start and r.word(e - 1) in _AFTER_PLACE:
        e -= 1
        after.insert(0, e)
    place = place_phrase(replace(r, toks=r.toks[:e]), start, "goal")
    if place is None or place.end != e or r.word(start) in _RULE_WORDS or not names_scene(r, start, e):
        return None
    said = r.toks[verb]
    head = [said, r.toks[particle]] if particle is not None else \
        [said, *(Tok(p, said.start, said.start) for p in _VERBS[r.word(verb)])]
    return head + list(r.toks[start:e]) + [r.toks[k] for k in after]
