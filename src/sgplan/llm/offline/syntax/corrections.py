"""Self-corrections: *go to the kitchen, no wait, the dining room*, *the chair in the office, sorry, I mean
the chair in the bedroom*.

A speaker who takes back a place right after naming it, with a correction word (:data:`.lexicon.CORRECTIONS`)
between the old and the new noun phrase, means the new one in the old one's place. The sentence is read
with the new phrase only; the old phrase and the correction words are set aside and said back (*not part of
the mission*). Only that shape is read: when the words after the correction are not one noun phrase closing
the clause, or no noun phrase ends right before it, the correction stays in the sentence and is refused
(which part stands is not known). The old place may be denied in the same words before the new one (*the
kitchen, no sorry, not the kitchen, the living room*), and then the clause may have been broken off after
*and* before the correction (*go to the kitchen and... no sorry, not the kitchen, the living room*).

A clause broken off after a word that cannot end one (*the*, *to*, *into*), at a dash or a pause (a comma,
*uh*), and started again
with the same first word (*don't take the- don't go through the living room*), or with the words before
the dash (*the plant in the- the plant in the office*), is a restart: the broken words are set aside and said
back, and the sentence is read from the restart. So is a clause broken off inside a word that the words after
it say whole (*grab the mic- er, check the microwave*), whatever they start with.

A correction followed by a whole order said again (*robot go to the lobby actually scratch that go to the
dining room*, *go check the fridge and then wait no first check the TV and then the fridge*, *alexa I mean
robot go to the garage*) takes back what came before it in the sentence: the sentence is read from the new
order, the words before set aside and said back. Only when the words taken back name at most one room or
object (with several, which of them is taken back is not known) and, when the new order says an order
(*first*, *last*, *before*), it names that one again (else it may only move it: refused).

Corrections may follow one another (*the microwave no the oven wait no microwave*): each is read in turn. A
*yeah* / *yes* followed by the words that end the noun phrase before it (*... microwave yeah microwave*) only
confirms it: set aside and said back. A denial may run into the new phrase unpunctuated (*no wait not the
office the bedroom*), and so may an apposition (*the bedroom the one with the teddy bear* is *the bedroom,
the one with the teddy bear*). A correction followed by the whole order said again may name several places
when it names the same ones again (*the empty room then the lobby no wait lobby first then the empty
room*: which is taken back is then no question), and a group of two or more words said twice in a row is
a stutter, said once (*lobby first lobby first*).

A sentence that is a correction and a whole order said again (*Actually no, go down to the lobby.*) after
one that names at most one place takes that sentence back: the two are read joined, as one sentence (an
object and its room, *the kitchen sink*, *the sink in the kitchen*, are one place). So does a sentence that
is only a correction and a phrase (*No, just the one with the plant.*) after one whose only phrase it ends
with (*Check one of the TVs in the living room.*); *the one* after a plural is one of that kind (a TV), and
*just* / *only* before the new phrase narrow what was taken back. When an object was taken back and the new
order names a room without going into it (*the kitchen sink first... no, start with the bathroom, then the
kitchen sink*), the room may stand for its object: refused.

A sentence that is only *the one(s) ...* right after one that ends with a noun phrase says which one that
is (*water the plant. the one in the living room.*): it is read as an apposition of that phrase (*the plant,
the one in the living room*).

A sentence opening with words it says again at the end of its next clause (*floor one, the office on floor
one, check ...*; *kitchen, go to the kitchen*) is a restatement: the first saying is set aside and said back.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import Literal

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.phrases import Phrases
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.qualifiers import head_kind
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.syntax.tree import Described, NounPhrase
from sgplan.llm.offline.text import Tok

_AROUND = frozenset({",", "sorry"})
"""Words between the old phrase, the correction and the new phrase (*the office, sorry, I mean ...*)."""
_JUST = frozenset({"just", "only"})
"""Before the phrase said instead, narrowing what was taken back (*the bedrooms, no, just the one ...*)."""
_CLAUSE_ENDS = ("", ",", "and", "then")
_INSTEAD = frozenset({"no", "sorry", "i", "actually", "wait", "oops", "oh"})
"""First words of a correction that says a phrase instead (*No wait, ...*, *Sorry, I mean ...*), unlike
*scratch that*, *forget the ...*."""
_WITHIN = ("in", "on", "inside", "at", "of")
"""Before a place said again inside the phrase that restates it (*the office on floor one*)."""
_PAUSED_AFTER = frozenset({"the", "a", "an", "to", "into", "of", "through", "from"})
"""Words after which a comma is a pause, never the end of a clause (*go to the... kitchen*); not *in*, *on*
(particles end clauses: *go in, then ...*), nor *her*, *that* (*bless her, ...*, *check that, then ...*)."""
_SEQUENCE_LEAD = frozenset({"then", "and", "next", ","})
"""Opening a sentence that is a next step, kept when the order in it is said again (*Then go to the corridor,
no, to the living room.*)."""
_YES = frozenset({"yeah", "yes", "yep", "yup", "sorry"})
"""Before the words of a phrase said again to confirm it (*the microwave yeah microwave*, *no the living room
sorry the living room*)."""
_OPENING = lx.HESITATIONS | lx.GREETINGS | frozenset({",", "okay", "ok", "robot"})
"""Words before what a sentence restates (*um okay floor one, the office on floor one*)."""


def corrected(r: Reader, earlier: Sequence[Reader] = ()) -> list[Reader]:
    """``r`` with each self-correction applied (the sentence to read, then the words set aside), or ``[r]``
    when it has none that can be read; ``earlier``: the sentences of the mission read before it."""
    restart = restarted(r) or restated(r) or stuttered(r) or confirmed(r)
    if restart is not None:
        return [*corrected(restart[0], earlier), restart[1]]
    r = apposition_marked(unpaused(r))
    for k in range(1, len(r)):
        said = r.phrase(k, lx.CORRECTIONS)
        if r.word(k) == "sorry" and r.word(k - 1) == "," and k + 1 == len(r):  # "..., the microwave, sorry."
            return [*corrected(replace(r, toks=r.toks[:k - 1]), earlier),
                    replace(r, toks=r.toks[k:], aside=True)]
        if said is not None:
            fixed = replaced(r, k, k + len(said)) or order_said_again(r, k, k + len(said), earlier)
            if fixed is not None and other_than_taken_back(*fixed):  # "the X with a vase, no wait, the other"
                return [fixed[1], *corrected(fixed[0], earlier)]
            return [r] if fixed is None else [*corrected(fixed[0], earlier), fixed[1]]
    return [r]


def other_than_taken_back(kept: Reader, taken_back: Reader) -> bool:
    """Whether the new phrase of a correction is *the other one* / *the other X* of the phrase taken back (its
    words set aside as ``taken_back``) and no *it* / *them* follows it: then the phrase taken back is said
    before the sentence, so that *other* is read against it (the X not named: refused when that is not one).
    A place pointed back to after it (*there*, *up there*, *that room*) is the new phrase, the goal named
    after the phrase taken back; *it* is refused, never bound to what was taken back."""
    start = next(k for k, t in enumerate(kept.toks) if t.start >= taken_back.toks[-1].end)
    return (kept.word(start) in lx.DETERMINERS and kept.word(start + 1) == "other"
            and not any(w in lx.PRONOUNS for w in kept.words[start:]))


def joined_appositions(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each sentence that is only *the one(s) ...*, or only a correction and the phrase said
    instead (:func:`takes_back_last`), joined to the sentence before it, after a comma (see the module
    docstring)."""
    out: list[Reader] = []
    for r in continued_corrections([instead_dropped(r) for r in readers]):
        before = out[-1] if out else None
        if (before is not None and not before.aside and not r.aside and r.marker is None
                and joins_before(r, before)):
            out[-1] = joined(before, r)
            continue
        out.append(r)
    return out


def joined(before: Reader, r: Reader) -> Reader:
    """The sentence ``before`` and the sentence ``r`` after it, read as one, after a comma."""
    comma = Tok(",", before.toks[-1].end, before.toks[-1].end)
    return replace(before, toks=(*before.toks, comma, *r.toks[r.skip(0, (",",)):]))


def continued_corrections(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each sentence that opens with *then* joined to a sentence before it that opens with a
    correction saying something instead (*Go to the kitchen. No wait, the dining room first. Then the
    kitchen.*), when only the two together take back the sentence before them (:func:`joins_before`): the
    order said again runs on over both (*Sorry, I mean the office. Then the couch.*: the office alone takes
    back the kitchen, and the couch comes after it)."""
    out: list[Reader] = []
    for r in readers:
        if len(out) > 1 and r.word(0) == "then" and r.marker is None and not r.aside:
            first, before = out[-2], out[-1]
            if (not before.aside and not first.aside and said_instead(before) is not None
                    and not joins_before(before, first) and joins_before(both := joined(before, r), first)):
                out[-1] = both
                continue
        out.append(r)
    return out


def instead_dropped(r: Reader) -> Reader:
    """``r`` without an *instead* closing a clause after a correction (*get the bowl, no wait, the oven
    instead*): the correction already says the new phrase stands instead of the old (*instead of X* is
    kept)."""
    k = next((k for k in range(len(r)) if r.phrase(k, lx.CORRECTIONS) is not None), None)
    cut = {j for j in range(k + 1, len(r)) if r.word(j) == "instead" and r.word(j + 1) in _CLAUSE_ENDS
           } if k is not None else set()
    return replace(r, toks=tuple(t for j, t in enumerate(r.toks) if j not in cut)) if cut else r


def joins_before(r: Reader, before: Reader) -> bool:
    """Whether the sentence ``r`` is read joined to the sentence ``before`` it (see
    :func:`joined_appositions`): a correction that says which phrase it takes back, by denying it or saying
    its preposition again, takes back the phrase ``before`` ends with, unless that phrase was said earlier in
    it too (which one?)."""
    final = final_phrase(before)
    if final is None:
        return takes_back_order(r, before) and len(goal_heads(before, 0, len(before))) <= 1
    said, preposition = before.words[final:phrase_end(before, len(before))], before.word(final - 1)
    last = takes_back_last(r, said, preposition)
    if last == "preposition" and preposition in before.words[:final - 1]:
        return False  # "go to the kitchen, but don't go to the bathroom. No, to the living room": which?
    if last in ("denied", "preposition"):  # "... Actually no, not the TV, ...", "... No, to the couch."
        return not _said_in(before.words[:final], said)
    if takes_back_order(r, before):
        return len(goal_heads(before, 0, len(before))) <= 1
    k = r.skip(0, (",",))  # "Uh, the one with the plant in it." (the sound removed before)
    apposition = (r.word(k) == "the" and r.word(k + 1) in lx.ANAPHORIC_ONE and len(r) > k + 2
                  and isinstance(noun_phrase(r, k, "goal"), Match))
    # "Go to one of the TVs in the living room. No, the one in the bedroom.": the one phrase it names
    return apposition or (last == "last" and not named_heads(before, 0, final))


def takes_back_last(r: Reader, said: Sequence[str], preposition: str) -> TakenBack | None:
    """How the sentence ``r`` takes back the words ``said`` that the sentence before it ends with (after
    ``preposition``), when it is only a correction and the phrase said instead (*No wait, the microwave,
    sorry.*): ``"denied"`` (*Actually no, not the TV, the vase.*), ``"preposition"`` said again (*... take it
    to the table. No, to the couch.*, *... the vase in the living room. No, in the dining room.*), ``"last"``
    (neither says which phrase); ``None`` when it is no such sentence."""
    r = unpaused(r)  # "Actually, no, the other one, with the plant."
    start = said_instead(r)
    if start is None:
        return None  # "Scratch the kitchen.": takes it back, says nothing instead
    denial = denial_of(r, start, said)
    new_at = past_preposition(r, denial if denial is not None else start, preposition, said)
    new = noun_phrase(r, new_at, "goal")
    end = len(r) - (2 if r.words[-2:] == (",", "sorry") else 0)
    if not (isinstance(new, Match) and new.end == end and new.end > new_at):
        return None
    return "denied" if denial is not None else "preposition" if new_at > start else "last"


TakenBack = Literal["denied", "preposition", "last"]


def takes_back_order(r: Reader, before: Reader) -> bool:
    """Whether the sentence ``r`` is a correction and a whole order said again (*Actually no, go down to the
    lobby.*), which takes back the sentence ``before`` it. Said without a verb (*No wait, the dining room
    first, then the kitchen.*, *Wait, no, first the plant, then the chair.*), it is one only when it names
    again the place taken back (else it may add a place, not say the order again)."""
    start = said_instead(r)
    if start is None or adds(r, start):
        return False
    i = order_start(r, start)
    if order_verb(r, i):
        return True
    taken_back = {h.categories for h in goal_heads(before, 0, len(before))}
    return ((r.word(i) in lx.FIRST or r.np_starts(i)) and bool(taken_back)
            and taken_back <= {h.categories for h in named_heads(r, i, len(r))})


def order_verb(r: Reader, i: int) -> bool:
    """Whether an order's verb is at ``i``: a verb of the goals, or *do* before a noun phrase (*do the laptop
    first*)."""
    return r.word(i) in lx.POSITIVE_VERBS or (r.word(i) == "do" and r.np_starts(i + 1))


def said_instead(r: Reader) -> int | None:
    """Where what the sentence ``r`` says instead starts, after the correction words it opens with (*No wait,
    ...*, *Sorry, I mean ...*); ``None`` when it opens with none that says something instead."""
    said = r.phrase(0, lx.CORRECTIONS)
    if said is None or said[0] not in _INSTEAD:
        return None
    return r.skip(past_corrections(r, len(said)), _JUST)


def past_corrections(r: Reader, i: int) -> int:
    """Where the words after the correction that ends at ``i`` start, past the correction words that follow
    it (*Sorry, I mean the office.*, *wait, no, first ...*) and *(the) other way round* (*No, other way
    round: ...*)."""
    i = r.skip(i, _AROUND)
    while (more := r.phrase(i, lx.CORRECTIONS) or r.phrase(i, _OTHER_WAY)) is not None:
        i = r.skip(i + len(more), _AROUND)
    return i


_OTHER_WAY = Phrases(tuple((*the, "other", "way", way) for the in ((), ("the",))
                           for way in ("round", "around")))
"""*(the) other way round* right after correction words (*No, other way round: A first, then B.*): only says
that the order is corrected (not after *or*: *A then B, or the other way round* is either order)."""


def adds(r: Reader, start: int) -> bool:
    """Whether the order said from ``start`` adds to what came before rather than replacing it (*actually,
    check the couch too*, *... instead*: refused)."""
    return r.says(lx.TOO, start, len(r)) or "instead" in r.words[start:]


def order_start(r: Reader, i: int) -> int:
    """Where the order said from ``i`` starts, after opening words and a polite wrapper (*uh, I want you to
    go ...*)."""
    i = r.skip(i, _OPENING)
    polite = r.phrase(i, lx.POLITE)
    return i if polite is None else r.skip(i + len(polite), _OPENING)


def final_phrase(r: Reader) -> int | None:
    """Where the noun phrase of a head noun that the sentence ``r`` ends with starts (*water the plant*, *sit
    at the table for me*), or ``None`` when it ends with none."""
    end = phrase_end(r, len(r))
    return next((j for j in range(max(0, end - 8), end) if (r.head(j) is not None
                 or r.word(j) in lx.DETERMINERS or r.word(j) in lx.ANAPHORIC_ONE)
                 and phrase_to(r, j, end) is not None), None)


def phrase_end(r: Reader, end: int) -> int:
    """Where a noun phrase said before ``end`` ends: before the commas and *for me* / *please* said after it
    (*the dining table for me, actually, ...*)."""
    while end > 0 and r.word(end - 1) in _AROUND:
        end -= 1
    end = next((j for j in range(max(0, end - 3), end) if r.phrase(j, lx.BEFORE_REMARK) == r.words[j:end]),
               end)
    while end > 0 and r.word(end - 1) in _AROUND:  # "the dining table, please, actually, ..."
        end -= 1
    return end


def restarted(r: Reader) -> tuple[Reader, Reader] | None:
    """The sentence read from a restart (see the module docstring), and the broken words set aside;
    ``None`` when it has no restart."""
    for cut in range(1, len(r) - 1):
        broken = broken_word(r, cut)
        if (r.word(cut - 1) not in lx.UNFINISHED and not broken) or r.word(cut) != ",":
            continue  # a clause never ends with "the" or "to": a comma (a dash, a pause) after it breaks it
        again = r.skip(cut, (",",))
        start = max((k + 1 for k in range(cut) if r.word(k) in lx.CLAUSE_ENDS and r.word(k)), default=0)
        if broken:  # "grab the mic- er, check the microwave": the clause is said again, whatever its verb
            return (replace(r, toks=r.toks[:start] + r.toks[again:]),
                    replace(r, toks=r.toks[start:again], aside=True))
        # a stutter says again the words broken off: "the plant in the- the plant in the office"
        start = next((k for k in range(start, cut) if r.words[k:cut] == r.words[again:again + cut - k]),
                     start)
        if r.word(start) == r.word(again):
            kept = replace(r, toks=r.toks[:start] + r.toks[again:])
            return kept, replace(r, toks=r.toks[start:again], aside=True)
    return None


def unpaused(r: Reader) -> Reader:
    """``r`` without the commas of a pause right after a word no clause ends with, when the clause goes on
    after it (*go to the... kitchen*, *go to the, uh, kitchen*), or between *the other one* and *with*: a
    pause, not a break."""
    def pause(k: int) -> bool:
        before = next((r.word(j) for j in range(k, -1, -1) if r.word(j) != ","), "")
        after = r.word(r.skip(k, (",",)))
        if r.at(k - 2, "other", "one") and after == "with":
            return True  # "no, the other one, with the plant": what the other one holds
        return after.isalpha() and after not in lx.CLAUSE_ENDS and before in _PAUSED_AFTER
    kept = [t for k, t in enumerate(r.toks) if not (t.text == "," and pause(k))]
    return r if len(kept) == len(r.toks) else replace(r, toks=tuple(kept))


def stuttered(r: Reader) -> tuple[Reader, Reader] | None:
    """The sentence with a group of two or more words said twice in a row said once (*lobby first lobby
    first*), and the second saying set aside; ``None`` when it has none."""
    for size in range(2, len(r) // 2 + 1):
        for k in range(len(r) - 2 * size + 1):
            group = r.words[k:k + size]
            if group == r.words[k + size:k + 2 * size] and all(w.isalpha() for w in group):
                return (replace(r, toks=r.toks[:k + size] + r.toks[k + 2 * size:]),
                        replace(r, toks=r.toks[k + size:k + 2 * size], aside=True))
    return None


def confirmed(r: Reader) -> tuple[Reader, Reader] | None:
    """The sentence without a *yeah* / *yes* and the words after it that say again the end of the noun
    phrase before it (*the microwave yeah microwave*, *the oven, yes, the oven*), those words set aside;
    ``None`` when it has none."""
    for k in range(1, len(r) - 1):
        if r.word(k) not in _YES:
            continue
        end = k - (r.word(k - 1) == ",")
        start = r.skip(k + 1, _AROUND)
        stop = next((j for j in range(start, len(r)) if r.word(j) in _CLAUSE_ENDS), len(r))
        again = tuple(w for w in r.words[start:stop] if w not in lx.ARTICLES)
        phrase_end = end - (1 if r.word(end - 1) == "again" else 0)  # "the oven again yeah the oven again"
        if (again and r.words[end - len(again):end] == again
                and any(phrase_to(r, j, phrase_end) for j in range(max(0, end - 10), phrase_end))):
            return (replace(r, toks=r.toks[:end] + r.toks[stop:]),
                    replace(r, toks=r.toks[end:stop], aside=True))
    return None


def apposition_marked(r: Reader) -> Reader:
    """``r`` with a comma before each unpunctuated *the one(s)* right after a noun phrase (*the bedroom the
    one with the teddy bear*): the apposition it is."""
    cuts = [k for k in range(1, len(r)) if r.word(k) == "the" and r.word(k + 1) in lx.ANAPHORIC_ONE
            and any(phrase_to(r, j, k) for j in range(max(0, k - 10), k))]
    return r.with_commas(cuts)


def broken_word(r: Reader, cut: int) -> bool:
    """Whether the word before the comma at ``cut`` was broken off by a dash (*the mic- er, the microwave*): a
    word no table knows, written onto the dash, that begins a longer word said after it."""
    w, tok = r.word(cut - 1), r.toks[cut - 1]
    return (r.word(cut) == "," and r.text[tok.end:tok.end + 1] == "-" and w.isalpha()
            and w not in lx.LEXICON_WORDS and r.head(cut - 1) is None
            and any(later.startswith(w) and later != w for later in r.words[cut:]))


def restated(r: Reader) -> tuple[Reader, Reader] | None:
    """The sentence without the words it opens with and says again at the end of its next clause (see the
    module docstring), and those words set aside; ``None`` when it opens otherwise."""
    start = r.skip(0, _OPENING)
    if "," not in r.words[start:]:
        return None
    comma = r.words.index(",", start)
    said = r.words[start:comma]
    clause_end = r.words.index(",", comma + 1) if "," in r.words[comma + 1:] else len(r)
    again = clause_end - len(said)
    if not said or comma + 1 > again or r.words[again:clause_end] != said:
        return None
    within = again - (2 if r.word(again - 1) in lx.ARTICLES else 1)
    if not (r.word(within) in _WITHIN or all(w in lx.POSITIVE_VERBS for w in r.words[comma + 1:again])):
        return None  # "bedroom, the bathroom next to the bedroom": two places, not one said again
    if any(w in lx.POSITIVE_VERBS or r.phrase(k, lx.NEG_STARTS) for k, w in enumerate(said, start)):
        return None  # "go to the kitchen, go to the kitchen": a goal said twice, not a place restated
    kept = replace(r, toks=r.toks[:start] + r.toks[comma + 1:])
    return kept, replace(r, toks=r.toks[start:comma + 1], aside=True)


def replaced(r: Reader, k: int, after: int) -> tuple[Reader, Reader] | None:
    """The sentence with the noun phrase ending before the correction words ``[k, after)`` replaced by the
    one after them, and the words taken back set aside; ``None`` when the shape is not that."""
    end = phrase_end(r, k)
    start_new = r.skip(past_corrections(r, after), _JUST)  # "the one upstairs": one of the old phrase's kind
    old = next((found for j in range(max(0, end - 10), end) if (found := phrase_to(r, j, end))), None)
    if old is None and r.word(end - 1) in ("and", "then"):  # "the kitchen and... no sorry, not the kitchen,"
        end -= 1
        old = next((found for j in range(max(0, end - 10), end) if (found := phrase_to(r, j, end))), None)
        if old is None or denied(r, old, start_new) == start_new:
            return None  # broken off after 'and': only a denial of the old place says it is taken back
    if old is None:
        return None
    start = r.toks.index(next(t for t in r.toks if t.start == old.span.start))
    after_denial = denied(r, old, start_new)
    start_new = past_preposition(r, after_denial, r.word(start - 1), r.words[start:end])
    room_said = start_new > after_denial and r.word(after_denial) in _ROOM_OF  # "..., no, in the dining room"
    head = old.head if isinstance(old, Described) and isinstance(old.head, Head) else None
    named, rest = one_named(r, start, end, start_new)
    if not named and any(r.word(j) in lx.ANAPHORIC_ONE for j in range(start_new, start_new + 3)):
        return None  # "the big one": one of the taken-back kind, read by no rule here (never another kind)
    said = replace(r, toks=r.toks[:start_new] + named + r.toks[rest:])  # "the other one": "the other X"
    new = noun_phrase(said, start_new, "goal", head)
    if not isinstance(new, Match) or (said.word(new.end) not in _CLAUSE_ENDS
                                      and said.phrase(new.end, lx.CORRECTIONS) is None
                                      and not said_with_verb(said, start_new, new.end)):
        return None  # (another correction after it: "the microwave no the oven wait no microwave")
    if room_said and said.word(new.end) == "," and said.word(new.end + 1) in lx.POSITIVE_VERBS:
        return None  # "No, in the dining room, check the chair": a place for a new order, or the vase's room?
    kinds = {head_kind(p) for p in (old, new.node) if isinstance(p, Described)} - {None}
    if len(kinds) > 1:
        room_at = room_taken_back(r, start, end, said, start_new, new.end, room_said)
        if room_at is None:
            return None  # "the toilet in the bathroom, no wait, the kitchen": which part is taken back?
        kept = replace(r, toks=r.toks[:room_at] + named + r.toks[rest:])
        return kept, replace(r, toks=r.toks[room_at:start_new], aside=True)
    if room_said or (kinds == {"object"} and rooms_named(r, 0, start)
                     and rooms_named(said, start_new, new.end)):
        return None  # "go to the bedroom and sit on the chair there, no wait, the chair in the office": the
        # bedroom was where that chair is; is it taken back too? ("in" said again: only a room follows it)
    kept = replace(r, toks=r.toks[:start] + named + r.toks[rest:])
    return kept, replace(r, toks=r.toks[start:start_new], aside=True)


def room_taken_back(r: Reader, start: int, end: int, said: Reader, start_new: int, end_new: int,
                    room_said: bool) -> int | None:
    """Where the room of the object phrase ``[start, end)`` starts, when the room phrase ``[start_new,
    end_new)`` of ``said`` corrects only that room (*the toilet in the top-floor bathroom, no wait, the
    bathroom on the middle floor*: the toilet in that bathroom): the old phrase is the object, *in* and a room
    of the new room's kind (*the bed in the bedroom with the plant, wait, no, the other bedroom*), or of any
    kind after *in* said again (``room_said``: *the sink in the kitchen, no, in the bathroom*); ``None``
    otherwise (*the toilet in the bathroom, no wait, the kitchen*: the kitchen instead of the toilet, or the
    toilet's room?)."""
    heads = _heads_at(r, start, end)
    new_heads = _heads_at(said, start_new, end_new)
    if len(heads) < 2 or not new_heads or heads[0][1].kind != "object" or new_heads[0][1].kind != "room":
        return None
    (j, thing), (k, room) = heads[0], heads[1]
    at = j + thing.words
    if r.word(at) not in _ROOM_OF or room.kind != "room" or any(r.head(i) for i in range(at + 1, k)):
        return None
    return at + 1 if room_said or room.categories & new_heads[0][1].categories else None


_ROOM_OF = frozenset({"in", "inside"})
"""Between an object and its room (*the toilet in the top-floor bathroom*)."""


def rooms_named(r: Reader, start: int, end: int) -> bool:
    """Whether a room's noun is said in ``[start, end)``."""
    return any(h.kind == "room" for _, h in _heads_at(r, start, end))


def said_with_verb(r: Reader, start: int, end: int) -> bool:
    """Whether the noun phrase ``[start, end)`` is said again right after it with a verb (*no wait the
    microwave check the microwave*, *the clock look at the clock*): the stutter that :func:`stuttered` then
    says once."""
    size = end - start
    return r.word(end) in lx.POSITIVE_VERBS and any(  # ("look at the clock": after the verb's particle)
        r.words[end + gap:end + gap + size] == r.words[start:end] for gap in (1, 2))


def order_said_again(r: Reader, k: int, after: int,
                     earlier: Sequence[Reader]) -> tuple[Reader, Reader] | None:
    """The sentence read from the whole order said again after the correction words ``[k, after)`` (see the
    module docstring), and the words taken back set aside; ``None`` when the shape is not that, or when the
    new order names a place of an ``earlier`` sentence that it does not take back (*Go to A. Then go to B, no
    wait, go to B first, then A.*: A taken back as well, or A twice?)."""
    start = order_start(r, past_corrections(r, after))
    opening = r.skip(0, _OPENING)
    if opening >= k or r.phrase(opening, lx.CORRECTIONS) is not None:
        return None  # "Actually no, go to the bed", "No, actually, ...": takes back the sentence before
    taken_back = goal_heads(r, opening, k)
    if r.word(start) in _ROOM_OF and any(h.kind == "object" for h in taken_back):
        return None  # "the sink in the kitchen, no wait, in the bathroom": the sink's room (replaced)
    forgot = forgotten(r, start, taken_back)
    start = order_start(r, r.skip(forgot, _AROUND | _JUST | {"and"})) if forgot is not None else start
    said_again = {h.categories for h in named_heads(r, start, len(r))}
    named_again = bool(taken_back) and {h.categories for h in taken_back} <= said_again
    all_again = named_again and {h.categories for h in taken_back} == said_again
    if (not order_verb(r, start) and r.word(start) not in lx.FIRST and r.word(start) != "please"
            and not (named_again and r.np_starts(start))):  # "... no wait, (the) laptop first, then the oven"
        return None
    if len(taken_back) > 1 and not all_again:
        return None  # "the kitchen then the office scratch that go to ...": which is taken back?
    if (taken_back and all(h.kind == "object" and h.categories in said_again for h in taken_back)
            and room_for_its_object(r, start)):
        return None  # "the kitchen sink first... no, start with the bathroom, then the kitchen sink": a sink?
    before = {h.categories for e in earlier if not e.aside for h in named_heads(e, 0, len(e))}
    if (said_again - {h.categories for h in taken_back}) & before or adds(r, start):
        return None
    if any(w in lx.FIRST or w in lx.LAST or w == "before" for w in r.words[start:]) and not (
            taken_back and taken_back[0].categories in said_again):
        return None  # "go to the kitchen wait no go to the office first": only moved, or taken back?
    lead = r.skip(opening, _SEQUENCE_LEAD)
    if lead > opening:  # "Then come back up to the corridor, no, to the living room": still a next step
        kept = replace(r, toks=r.toks[:lead] + r.toks[start:])
        return kept, replace(r, toks=r.toks[lead:start], aside=True)
    return replace(r, toks=r.toks[start:]), replace(r, toks=r.toks[:start], aside=True)


FORGET = Phrases((("forget",), ("forget", "about"), ("never", "mind"), ("skip",), ("scratch",)))
"""Before the phrase a correction takes back, said again (*no, actually, forget the apple, just go ...*); not
*drop*, a verb of putting down (*drop the bowl*)."""


def forgotten(r: Reader, i: int, taken_back: list[Head]) -> int | None:
    """Where the words *forget / never mind / skip X* at ``i`` end when X names again every place taken back
    (*Fetch an apple... no, actually, forget the apple, just go sit on the couch*): they only say what the
    correction takes back; ``None`` otherwise."""
    said = r.phrase(i, FORGET)
    phrase = noun_phrase(r, i + len(said), "goal") if said is not None and taken_back else None
    if not isinstance(phrase, Match) or r.word(phrase.end) not in (",", "and", "just"):
        return None
    named = {h.categories for h in named_heads(r, i, phrase.end)}
    return phrase.end if named and {h.categories for h in taken_back} <= named else None


def named_heads(r: Reader, start: int, end: int) -> list[Head]:
    """The head nouns of the scene named in the words ``[start, end)``, in order."""
    return [head for _, head in _heads_at(r, start, end)]


def goal_heads(r: Reader, start: int, end: int) -> list[Head]:
    """The head nouns of :func:`named_heads`, without the room of an object said with it (*the kitchen
    sink*, *the sink in the kitchen*: one place)."""
    return [head for _, head in _goal_heads_at(r, start, end)]


def room_for_its_object(r: Reader, start: int) -> bool:
    """Whether a room of the goals named from ``start`` is said without a word of going into it (*start with
    the bathroom*, not *go to the bathroom*): after a correction of an object, it may stand for its object."""
    return any(head.kind == "room" and r.word(_before_determiners(r, j)) not in lx.INTO_A_ROOM
               for j, head in _goal_heads_at(r, start, len(r)))


def _goal_heads_at(r: Reader, start: int, end: int) -> list[tuple[int, Head]]:
    found = _heads_at(r, start, end)
    objects_at = {j for j, head in found if head.kind == "object"}

    def within(j: int) -> bool:  # "the sink in the kitchen", "an apple from the kitchen"
        k = _before_determiners(r, j)
        return any(o < k for o in objects_at) and (r.word(k) in _WITHIN or r.word(k) == "from")

    return [(j, head) for j, head in found
            if not (head.kind == "room" and (j + head.words in objects_at or within(j)))]


def _before_determiners(r: Reader, j: int) -> int:
    """The index of the word before the determiners that come before ``j``."""
    k = j - 1
    while k > 0 and r.word(k) in lx.DETERMINERS:
        k -= 1
    return k


def _heads_at(r: Reader, start: int, end: int) -> list[tuple[int, Head]]:
    """Where each head noun of the scene in the words ``[start, end)`` starts, and the head."""
    heads: list[tuple[int, Head]] = []
    j = start
    while j < end:
        head = r.head(j)
        if head is not None:
            heads.append((j, head))
        j += head.words if head is not None else 1
    return heads


def denied(r: Reader, old: NounPhrase, i: int) -> int:
    """Where the new phrase starts after the old one is denied at ``i`` in the same words (*no sorry, not
    the kitchen, the living room*, *not the office the bedroom*), or ``i`` when it is not."""
    said = tuple(t.text for t in r.toks if old.span.start <= t.start and t.end <= old.span.end)
    after = denial_of(r, i, said)
    return i if after is None else after


def denial_of(r: Reader, i: int | None, said: Sequence[str]) -> int | None:
    """Where the words after *not* and the words ``said`` at ``i`` end, past a comma (*not the kitchen, the
    living room*; unpunctuated: *not the office the bedroom*); ``None`` when they are not there."""
    if i is None or r.word(i) != "not" or not said or r.words[i + 1:i + 1 + len(said)] != tuple(said):
        return None
    after = i + 1 + len(said)
    return r.skip(after, _AROUND) if r.word(after) == "," or r.word(after) in lx.DETERMINERS else None


def past_preposition(r: Reader, i: int, before: str, said: Sequence[str]) -> int:
    """Past the preposition at ``i`` when it is ``before``, the one said before the phrase ``said`` taken back
    (*take it to the dining table, no, to the couch*), or the *in* of its room (*the vase in the living room,
    no, in the dining room*), else ``i``."""
    again = r.word(i) == before and before in _SAID_AGAIN_BEFORE
    return i + 1 if again or (r.word(i) in _ROOM_OF and r.word(i) in said) else i


_SAID_AGAIN_BEFORE = frozenset({"to", "into", "on", "at", "in"})
"""Prepositions a correction says again before the new phrase (*..., no, to the couch*)."""


def _said_in(words: Sequence[str], said: Sequence[str]) -> bool:
    """Whether the words ``said`` are said, in a row, in ``words``."""
    return any(tuple(words[k:k + len(said)]) == tuple(said) for k in range(len(words) - len(said) + 1))


def one_named(r: Reader, start: int, end: int, start_new: int) -> tuple[tuple[Tok, ...], int]:
    """The words to read in place of *the one* of a new phrase (the taken-back phrase ``[start, end)``'s
    determiner and head noun: *the bathroom downstairs, no sorry, the one upstairs* is *the bathroom
    upstairs*, *the other one* is *the other bathroom*), and where the new phrase's own words go on; no
    words and ``start_new`` otherwise."""
    one = next((k for k in range(start_new, start_new + 3) if r.word(k) in lx.ANAPHORIC_ONE), None)
    noun = next(((k, h) for k in range(start, end) if (h := r.head(k)) is not None), None)
    said = range(start_new, one or start_new)
    if one is None or noun is None or not all(
            r.word(k) in lx.DETERMINERS or r.word(k) == "other" or r.word(k) in lx.RELATIVE_FLOORS
            or (k > start_new and (h := r.head(k)) is not None and h.kind == "room") for k in said):
        return (), start_new  # "the downstairs one": the downstairs bathroom; "the kitchen one": its chair
    k, head = noun
    at = r.toks[one]  # the head's words where "one" was said, so that the phrase quotes what was said
    if head.plural and r.word(one) == "one":  # "one of the TVs ..., no, the one in the bedroom": a TV
        if len(head.categories) != 1:
            return (), start_new
        head_words = tuple(Tok(w, at.start, at.end) for w in next(iter(head.categories)).split())
    else:
        head_words = tuple(Tok(t.text, at.start, at.end) for t in r.toks[k : k + head.words])
    return (*r.toks[start_new:one], *head_words), one + 1


def phrase_to(r: Reader, i: int, end: int) -> NounPhrase | None:
    """The noun phrase starting at ``i`` when it ends at ``end``, else ``None``."""
    found = noun_phrase(r, i, "goal")
    return found.node if isinstance(found, Match) and found.end == end else None
