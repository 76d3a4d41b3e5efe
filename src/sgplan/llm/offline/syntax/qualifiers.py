"""Syntax rules for what follows a head noun: *on floor 1*, *in the kitchen*, *'s room*, *with the bed*,
*where the book is*, *next to the kitchen*, *except the one on floor 0*, *there*, an apposition (*, the one
upstairs*) and asides (*, which is in the living room*).

The rules of :data:`QUALIFIERS` are tried in order after the head and after each qualifier read; a rule
sees the phrase so far (:class:`NounSoFar`): its current head (a possessive changes it), its role and
whether it is already located in a room.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Literal

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.nouns import Head, Kind
from sgplan.llm.offline.syntax.floors import floor_count, floor_offset, floor_words
from sgplan.llm.offline.syntax.noun_slot import count_word, exact_count, foreign_word, head_noun, noun_phrase
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal
from sgplan.llm.offline.syntax.rules import RuleSet
from sgplan.llm.offline.syntax.tree import (
    Attachment,
    Between,
    ByUnlisted,
    Contains,
    Described,
    Determiner,
    Except,
    Holds,
    InRoom,
    KeyHead,
    Lacks,
    NextTo,
    NounPhrase,
    OneHead,
    OnFloor,
    Possessive,
    Qualifier,
    RelativeFloor,
    Role,
    SameFloor,
    ShortStay,
    StartFloor,
    There,
    UpThere,
)


@dataclass(frozen=True)
class Skipped:
    """Words of a phrase that say nothing (an aside's *which is*, *in the house*)."""


@dataclass(frozen=True)
class NounSoFar:
    """The phrase read so far (``noun``, from token ``first``), its current head's kind (``None``: *the
    one*, whose kind the context decides), role, and whether it is located in a room already."""

    first: int
    noun: Described
    kind: Kind | None
    role: Role
    room_scoped: bool


QUALIFIERS: RuleSet[Qualifier | Skipped] = RuleSet("qualifier")


def finish(r: Reader, first: int, i: int, noun: Described, role: Role, room_scoped: bool) -> Parse[Described]:
    """Read the qualifiers of ``noun`` (which starts at token ``first``) from ``i``, then an apposition and
    whether a choice remark follows."""
    kind = head_kind(noun)
    while True:
        so_far = NounSoFar(first, replace(noun, span=r.span(first, i)), kind, role, room_scoped)
        found = QUALIFIERS.first(r, i, so_far)
        if not isinstance(found, Match):
            if found is not None:
                return found
            break
        i = found.end
        if isinstance(found.node, Skipped):
            continue
        noun = replace(noun, qualifiers=(*noun.qualifiers, found.node))
        if isinstance(found.node, ByUnlisted):  # "the bowl on the counter": the scene decides which bowl
            noun = replace(noun, descriptive=(*noun.descriptive, found.node.words))
        if isinstance(found.node, Possessive):
            kind, room_scoped = found.node.head.kind, room_scoped or found.node.head.kind == "object"
            noun = replace(noun, determiner=replace(noun.determiner,
                                                     mode="all" if found.node.head.plural else "the"))
        room_scoped = room_scoped or isinstance(found.node, InRoom) or (
            isinstance(found.node, There) and kind == "object")
    excludes = r.at(i, ",", "not", "the")  # "the other bathroom, not the one with the vase"
    appositive = apposition(r, i + (1 if excludes else 0), noun, role)
    if isinstance(appositive, Refusal):
        return appositive
    if appositive is not None and listed_on(r, appositive.end) and not excludes:
        # "the plant in the bedroom, the one in the office, and the one in the hall": which plant, or the
        # next item of a list? The scene decides (:class:`.tree.Attachment`)
        if r.decided(i) is False:
            appositive = None
        elif r.decided(i) is None:
            noun = replace(noun, qualifiers=(*noun.qualifiers, Attachment(
                i, "apposition", noun, appositive.node, r.span(first, appositive.end), False)))
    if appositive is not None:
        noun, i = replace(noun, apposition=appositive.node, apposition_excludes=excludes), appositive.end
    remark = remark_ahead(r, i)
    return Match(replace(noun, span=r.span(first, i), remark_follows=remark is not None,
                         either_remark="either" in (remark or ())), i)


def head_kind(noun: Described) -> Kind | None:
    """The kind of the phrase's head as the words say it (``None`` for *the one* from the context)."""
    if noun.compound is not None:
        return "object"
    if isinstance(noun.head, Head):
        return noun.head.kind
    if isinstance(noun.head, KeyHead):
        return "room" if noun.head.key.startswith("room_") else "object"
    return noun.head.given.kind if noun.head.given is not None else None


def current_head(noun: Described) -> Head | None:
    """The head the phrase is about now (the last possessive's, else its own), when the words say it."""
    for q in reversed(noun.qualifiers):
        if isinstance(q, Possessive):
            return q.head
    if noun.compound is not None:
        return noun.compound
    return noun.head if isinstance(noun.head, Head) else noun.head.given if isinstance(noun.head, OneHead) \
        else None


def remark_ahead(r: Reader, i: int) -> tuple[str, ...] | None:
    """The words of ``(,) either one is fine`` / ``, any one will do`` / ``, whichever`` / ``, just one of
    them`` / ``, any of the three`` at ``i`` (remarks that the choice is the robot's, one after another), or
    ``None``; a polite word before it (*an apple for me, either one is fine*) is part of it."""
    lead = r.phrase(i, lx.BEFORE_REMARK) or ()
    said = one_remark(r, i + len(lead))
    k = i + len(lead) + len(said) if said is not None else i
    while said is not None and (more := one_remark(r, k)) is not None:
        said, k = said + more, k + len(more)  # "just one of them, any is fine"
    return None if said is None else lead + said


def one_remark(r: Reader, i: int) -> tuple[str, ...] | None:
    """One choice remark at ``i`` (see :func:`remark_ahead`), after a comma or two (*the vases, uh, any one of
    them*: the sound is dropped, its commas stay)."""
    comma = 2 if r.at(i, ",", ",") else 1 if r.word(i) == "," else 0
    suffices = r.phrase(i + comma, lx.ONE_SUFFICES)
    after = i + comma + len(suffices or ())
    if suffices is not None and (r.word(after) in lx.CLAUSE_ENDS or one_remark(r, after) is not None):
        return (",",) * comma + suffices
    w, of, the, n = (r.word(i + comma + k) for k in range(4))
    if w in lx.CHOOSING_OF and of == "of" and the in ("the", "all") and (n in lx.NUMBER_WORDS or n.isdigit()):
        return (",",) * comma + (w, of, the, n)  # "a TV in the office, any of the three"
    said = r.phrase(i + comma, lx.CHOICE_AFFIRMATIONS)
    if said is not None and (any_one_located(r, i + comma) or the_one_said_more(r, i + comma, said)):
        return None  # "a vase, any one in the living room": which ones, not a remark
    if said is None and comma and r.word(i + 1) in lx.BARE_CHOOSERS and r.word(i + 2) in lx.CLAUSE_ENDS:
        said = (r.word(i + 1),)  # "LR tv (either)", "DR vase, any": no noun follows, so a remark
    time = r.phrase(i + comma, lx.TIME_FILLERS)  # "whichever first" is about the order
    if said is None or (time is not None and len(time) >= len(said)):
        return None
    return (",",) * comma + said


def the_one_said_more(r: Reader, i: int, said: tuple[str, ...]) -> bool:
    """Whether the remark ``said`` at ``i`` is *the one you like* and words other than a clause's end follow
    it (*the chair, the one you like in the office*: which one, not a free choice)."""
    after = i + len(said)
    placed = r.word(after) == "," and (r.word(after + 1) in lx.LOCATIVE
                                       or r.word(after + 1) in lx.RELATIVE_FLOORS)
    return said[0] == "the" and (r.word(after) not in lx.CLAUSE_ENDS or placed)  # (", in the office")


def any_one_located(r: Reader, i: int) -> bool:
    """Whether *any one* at ``i`` is a phrase of the kind named last, located (*then any one in the office*,
    *a vase, any one upstairs*), not the remark *(, any one)* closing a choice."""
    located = r.word(i + 2) in (*lx.SCOPE_IN, "on") or r.word(i + 2) in lx.RELATIVE_FLOORS
    return r.at(i, "any", "one") and located


def apposition(r: Reader, i: int, noun: Described, role: Role) -> Parse[Described]:
    """*the bathroom, the one upstairs*: a phrase about *the one* that says which (at ``i``: the comma, or
    *not* in *, not the one with the vase*)."""
    head = current_head(noun)
    one = r.descriptive_end(i + 2)  # "the bathroom, the (big) one upstairs"
    if (noun.determiner.mode != "the" or head is None or head.plural
            or not (head.categories or noun.determiner.pointer in lx.OWNERS)  # "his room, the one with X"
            or not isinstance(noun.head, Head) or r.word(i) not in (",", "not")
            or r.word(i + 1) != "the"
            or r.word(one) != "one" or r.phrase(one, lx.CHOICE_AFFIRMATIONS)
            or one_remark(r, i) is not None):  # "the TV, the one you like": a remark
        return None
    if role == "qualifier" and head.kind != "room":
        return None
    which = noun_phrase(r, i + 1, "qualifier", Head(head.kind, head.categories, False, 1))
    if isinstance(which, Match) and not isinstance(which.node, Described):
        return None
    if role == "qualifier" and isinstance(which, Match) and not says_contents(which.node):
        return None  # "the toilet in the bathroom, the one upstairs": the toilet's, or the bathroom's?
    return which  # type: ignore[return-value]


def listed_on(r: Reader, i: int) -> bool:
    """Whether a list goes on at ``i`` with *and* / *or* and a noun phrase (*, and the one in the hall*)."""
    k = i + (1 if r.word(i) == "," else 0)
    return r.word(k) in ("and", "or") and r.np_starts(k + 1)


def says_contents(which: NounPhrase) -> bool:
    """Whether an apposition says only what a room holds (*the one with the vase*, *not the one that has two
    sinks*): inside a room qualifier of an object (*the toilet in the other bathroom, not the one with the
    vase*) it can only be about the room, as no object holds another."""
    return (isinstance(which, Described) and bool(which.qualifiers)
            and all(isinstance(q, Holds | Contains | Lacks) for q in which.qualifiers))


def skip_in_it(r: Reader, i: int) -> int:
    """After a room's contents: the trailing *in it* (*the bedroom that only has a bed in it*), or *inside*
    ending the phrase (*which has only the bed inside*)."""
    if r.word(i) == "inside" and not r.np_starts(i + 1):
        return i + 1
    return i + 2 if r.word(i) in lx.IN_IT and r.word(i + 1) in ("it", "there") else i


def contents_end(r: Reader, i: int) -> tuple[int, bool]:
    """After a room's contents at ``i``: where they end (after a trailing *in it*) and whether *and nothing
    else* says the room holds nothing else (*where is only one bed and nothing else*)."""
    i = skip_in_it(r, i)
    said = r.phrase(i, lx.NOTHING_ELSE)
    return (i + len(said), True) if said is not None else (i, False)


@QUALIFIERS.rule("aside")
def aside(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the couch, which is in the living room*: read as the qualifier it states."""
    said = r.phrase(i, lx.ASIDE)
    return Match(Skipped(), i + len(said)) if said and r.word(i + len(said)) in lx.ASIDE_QUALIFIERS else None


@QUALIFIERS.rule("possessive")
def possessive(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the teddy bear's room* (the room holding it), *the kitchen's sink* (the sink in it)."""
    if r.word(i) != "'s" or noun.kind is None or r.head(i + 1) is None:
        return None  # not "the oven's off": there 's is "is"
    head = head_noun(r, i + 1, None)
    if not isinstance(head, Match):
        return head
    assert isinstance(head.node, Head)
    said = r.quote(noun.first, head.end)
    if noun.kind == "object" and head.node.kind != "room":
        return Refusal(rf.only_a_room_holds(said))
    if noun.kind == "room" and head.node.kind != "object":
        return Refusal(rf.only_objects_belong(said))
    return Match(Possessive(head.node, r.span(noun.first, head.end)), head.end)


@QUALIFIERS.rule("object room")
def object_room(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the teddy bear room*, *the TV room*: the room holding it, as *the teddy bear's room*; with a kind of
    room (*back to the plant bedroom*, *into the teddy bear room*) only after *the* and a word that leads to
    a room (in notes *bowl kitchen* may be two goals, and after *grab the bowl kitchen* the bowl may be
    meant)."""
    head = r.head(i)
    if (noun.kind != "object" or noun.room_scoped or head is None or head.kind != "room" or head.plural
            or r.head(i + head.words) is not None):
        return None
    named_room = r.word(noun.first) == "the" and r.word(noun.first - 1) in lx.INTO_A_ROOM
    if r.word(i) not in lx.GENERIC_ROOM_WORDS and not named_room:
        return None
    return Match(Possessive(head, r.span(noun.first, i + head.words)), i + head.words)


def anaphoric_one(r: Reader, i: int) -> bool:
    """Whether *one(s)* at ``i`` is a noun (*the living room one*, *the upstairs one*), not a number (*one of
    them*, *one after another*, *one floor up*)."""
    return r.word(i) in lx.ANAPHORIC_ONE and r.word(i + 1) not in lx.ONE_NOT_A_NOUN


@QUALIFIERS.rule("floor")
def on_floor(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*on floor 1*, *on the second floor*, *upstairs*, *, one floor down*, *up there*, *on the same floor
    (as X)*, *on that floor*; not *in the ground floor bathroom* (a room named with its floor)."""
    w = r.word(i)
    if w in lx.RELATIVE_FLOORS:
        return Match(OnFloor(RelativeFloor(w)), i + 1)
    k = i + 1 + (1 if r.word(i + 1) == "the" else 0)
    if (w in lx.FLOOR_PREPOSITIONS and r.word(k) in lx.RELATIVE_FLOORS and r.head(k + 1) is None
            and not anaphoric_one(r, k + 1)):  # not "the sink in the upstairs one": a room
        return Match(OnFloor(RelativeFloor(r.word(k))), k + 1)  # "the bathroom of the upstairs" (learners)
    comma = 1 if w == "," else 0
    if floor_count(r, i + comma) is not None and r.word(i + comma + 1) in lx.FLOOR_PLURALS:
        offset = floor_offset(r, i + comma)  # "the kitchen (,) one floor down"
        if offset is not None:
            return Match(OnFloor(offset.node), offset.end)
    if w in lx.BACK_THERE and r.word(i + 1) == "there":
        return Match(OnFloor(UpThere(w)), i + 2)
    if w not in lx.FLOOR_PREPOSITIONS:
        return None
    if r.at(i + 1, "the", "same") and r.word(i + 3) in lx.FLOOR_WORDS:
        return same_floor(r, i + 4)
    if r.word(i + 1) == "that" and r.word(i + 2) in lx.FLOOR_WORDS:
        return same_floor(r, i + 3)
    if r.at(i + 1, "that", "same") and r.word(i + 3) in lx.FLOOR_WORDS:
        return same_floor(r, i + 4)  # "on that same floor": no fresh floor, the one named last
    if r.word(i + 1) == "same" and r.word(i + 2) in lx.FLOOR_WORDS:
        return same_floor(r, i + 3)  # "the bathroom of same floor", the article left out as learners do
    said = floor_words(r, i + (2 if r.word(i + 1) == "the" else 1))
    if said is None or r.head(said.end) is not None or anaphoric_one(r, said.end):
        return None  # none, or "in the ground floor bathroom / one": a room named with its floor
    return Match(OnFloor(said.node), said.end)


@QUALIFIERS.rule("floor without a preposition")
def floor_after(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*bathrm top flr*, *the bathroom floor 0*, *bathroom (floor 1)*, *bathroom (upstairs)*: the floor said
    right after the noun, as notes are written (not *the bathroom top floor bedroom*: a floor before another
    noun names that one)."""
    if noun.kind == "room" and r.word(i) in _NOTE_DIRECTIONS and note_ends(r, i + 1):
        return Match(OnFloor(RelativeFloor(_NOTE_DIRECTIONS[r.word(i)])), i + 1)  # "bthrm dn (toilet)"
    aside = r.word(i) == "," and r.word(i + 1) != ","
    k = i + (1 if aside else 0)
    if aside and r.word(k) in lx.RELATIVE_FLOORS and r.word(k + 1) in lx.CLAUSE_ENDS:
        return Match(OnFloor(RelativeFloor(r.word(k))), k + 1)
    said = floor_words(r, k)
    if (said is None or isinstance(said.node, StartFloor) or r.head(said.end) is not None
            or (aside and r.word(said.end) not in lx.CLAUSE_ENDS)):
        return None
    return Match(OnFloor(said.node), said.end)


_NOTE_DIRECTIONS = {"up": "upstairs", "down": "downstairs", "dn": "downstairs"}
"""After a room in a note (*bthrm dn: toilet*, *bthrm up (bottle)*): the floor above / below."""


def note_ends(r: Reader, k: int) -> bool:
    """Whether an item of a note ends at ``k``: its end, a colon, an arrow, or a bracket opening (*bthrm dn
    (toilet)*); not a comma (*the bottle from the bathroom up, then ...*: carried up?)."""
    if k >= len(r) or r.word(k) == ":":
        return True
    typed = r.text[r.toks[k - 1].end:r.toks[k].end]  # (an arrow is read as "then")
    return any(mark in typed for mark in ("(", "->", ">", "\u2192"))


def same_floor(r: Reader, i: int) -> Parse[Qualifier | Skipped]:
    """After *on the same floor* / *on that floor* (at ``i``): *as X* when said."""
    if r.word(i) == "as" and r.np_starts(i + 1):
        other = noun_phrase(r, i + 1, "qualifier")
        if not isinstance(other, Match):
            return other
        return Match(OnFloor(SameFloor(other.node)), other.end)
    return Match(OnFloor(SameFloor(None)), i)


@QUALIFIERS.rule("in the house")
def whole_building(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*in the house* / *in this building* / *anywhere in the home* (not *in the home office*, a room):
    the whole building, which restricts nothing."""
    k = 2 if r.at(i, "anywhere", "in") else 1 if r.word(i) in lx.WHOLE_BUILDING_PREPOSITIONS else 0
    if (not k or r.word(i + k) not in lx.WHOLE_BUILDING_DETERMINERS
            or r.word(i + k + 1) not in lx.WHOLE_BUILDING or r.head(i + k + 1) is not None):
        return None
    return Match(Skipped(), i + k + 2)


@QUALIFIERS.rule("in a room")
def in_room(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the sink in / of / inside the kitchen*: the objects in that room; *every plant in the office and
    the kitchen*, *all the vases in A and B*: those of each room (a phrase about each of several objects);
    *a chair in (either) A or (in) B*: those of either room (the choice is of rooms, as people mean it)."""
    if r.word(i) in lx.DIRECTION_BEFORE_IN and r.word(i + 1) in lx.SCOPE_IN and not carried(r, noun):
        i += 1  # "the one up in the bedroom": the room says where, the direction adds nothing
    if r.at(i, "out", "of") and noun.kind == "object" and r.word(noun.first - 1) in lx.TAKING_OUT_VERBS:
        i += 1  # "grab the bottle out of the bathroom": where it is taken from
    back = noun.role == "qualifier" and r.word(i + 1) in ("it", "there")
    if r.word(i) == "on" and noun.kind == "object" and room_on(r, i + 1):
        pass  # "touch the vase on dining room", "the TV on the living room": in it, as learners say it
    elif (r.word(i) not in lx.QUAL_IN or not r.np_starts(i + 1) or r.phrase(i, lx.ORDER_MODIFIERS)
            or r.phrase(i, lx.TIME_FILLERS) or back):
        return None
    rooms: list[NounPhrase] = []
    either = r.at(i + 1, "either") and r.np_starts(i + 2)
    j = i + (1 if either else 0)
    while not rooms or (k := more_rooms(r, j, noun)):
        start = j + (k if rooms else 1)
        room = noun_phrase(r, start, "qualifier")
        if rooms and not (isinstance(room, Match) and names_rooms(room.node)):
            break  # "every plant in the office and the couch": the couch is another goal
        if not isinstance(room, Match):
            return room
        if not rooms and names_objects(room.node) and noun.kind == "room":
            return None  # "put the cup from the hall in the sink": a room is in no object
        if not rooms and names_objects(room.node) and r.word(i) in lx.CARRY_DESTINATION_WORDS:
            goes = goes_there(r, noun, i, room.end)  # "put the cup in the sink": where it goes
            if goes is not False:
                return goes
        rooms.append(room.node)
        j = room.end
    # "in either A or B", and "the toilet in either bathroom": one room of a choice
    choice = (len(rooms) > 1 or either) and noun.noun.determiner.mode != "all"
    return Match(InRoom(tuple(rooms), r.span(noun.first, j), choice), j)


def room_on(r: Reader, i: int) -> bool:
    """Whether a phrase naming rooms only, and no floor, starts at ``i`` after *on* (*on dining room*; not *on
    the table*, *on the top floor*, *on the way*)."""
    if not r.np_starts(i) or any(r.word(k) in lx.FLOOR_WORDS for k in range(i, min(len(r), i + 4))):
        return False
    said = noun_phrase(r, i, "qualifier")
    return isinstance(said, Match) and names_rooms(said.node) and not names_objects(said.node)


def more_rooms(r: Reader, j: int, noun: NounSoFar) -> int:
    """How many words join another room to the rooms of an object at ``j``: *or (in)*, or *and* after a
    phrase about each of several objects (*every plant in A and B*); 0 if none does."""
    k = 2 if r.word(j) == "or" and r.word(j + 1) in lx.QUAL_IN else 1
    joined = r.word(j) == "or" or (noun.noun.determiner.mode == "all" and r.word(j) == "and")
    return k if joined and r.np_starts(j + k) else 0


@QUALIFIERS.rule("there")
def there(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*a bathroom there* (on the floor named last), *grab a bottle there* / *out there* / *over there* (in
    the room of the place named last)."""
    if r.word(i) in lx.THERE_POINTING and r.word(i + 1) == "there" and noun.kind == "object":
        i += 1  # "the cup in the hallway and both plants out there": in the hallway
    if r.word(i) != "there" or r.word(i + 1) in lx.STATEMENT_LINKS:
        return None
    if noun.kind == "room" or (noun.kind is None) or (
            noun.kind == "object" and noun.role in ("goal", "avoid") and not noun.room_scoped):
        return Match(There(), i + 1)
    return None


@QUALIFIERS.rule("here")
def here(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bathroom here*: on the floor where the speaker and the robot are, as *on this floor* (the start
    floor; *up here* / *down here* are read as *on this floor* before parsing, `lexicon.PHRASE_ALIASES`); not
    after a carry verb (*bring the bowl here*: where it goes)."""
    if r.word(i) != "here" or carried(r, noun):
        return None
    return Match(OnFloor(StartFloor("here")), i + 1)


@QUALIFIERS.rule("where is X")
def where_is(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bedroom where is the book* (as learners write *where the book is*): the rooms holding it; *where
    is only the bed*: holding nothing else."""
    if noun.kind == "object" or r.word(i) != "where" or r.word(i + 1) not in lx.RELATIVE_BE:
        return None
    k = i + 2 + (1 if r.word(i + 2) in lx.ONLY_WORDS else 0)
    count = count_word(r, k)  # "where are two beds": exactly two
    k += 1 if count is not None else 0
    if not r.np_starts(k) or r.word(k) == "there":
        return None
    thing = noun_phrase(r, k, "qualifier")
    if not isinstance(thing, Match):
        return thing
    end, nothing_else = contents_end(r, thing.end)
    only = (r.word(i + 2) in lx.ONLY_WORDS and count is None) or nothing_else
    return Match(Contains(thing.node, r.span(noun.first, thing.end), count, only), end)


@QUALIFIERS.rule("that is X")
def relative_be(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bathroom that is near (of) the bedrooms*, *the bedroom which is upstairs*: the qualifier the
    relative clause states."""
    said = r.phrase(i, lx.RELATIVE_THAT)
    return Match(Skipped(), i + len(said)) if said and r.word(i + len(said)) in lx.ASIDE_QUALIFIERS else None


@QUALIFIERS.rule("where X is")
def holds(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the room where the book is (kept)*, *the room (that) the book is in*, *the room in which the book
    is*."""
    if noun.kind == "object":
        return None
    tail: tuple[str, ...]
    if r.word(i) == "where" and r.np_starts(i + 1) and r.word(i + 1) != "there":
        start, tail = i + 1, ()
    elif r.at(i, "in", "which") and r.np_starts(i + 2):
        start, tail = i + 2, ()
    elif r.word(i) in ("that", "which") and r.np_starts(i + 1):
        start, tail = i + 1, ("in",)
    elif r.np_starts(i) and not r.word(i).startswith(("room_", "object_")):
        start, tail = i, ("in",)
    else:
        return None
    thing = noun_phrase(r, start, "qualifier")
    if isinstance(thing, Refusal):
        return None if tail else thing  # "the room the ...": maybe not a relative clause at all
    assert thing is not None
    also: list[NounPhrase] = []
    while not tail and r.word(thing.end) == "and" and r.np_starts(thing.end + 1):
        more = noun_phrase(r, thing.end + 1, "qualifier")  # "where the book and the vase are"
        if not isinstance(more, Match):
            return more
        also.append(more.node)
        thing = Match(thing.node, more.end)
    if also and r.word(thing.end) not in lx.PLURAL_BE:
        return Refusal(rf.where_after_a_room(r.rest(thing.end)))
    if r.word(thing.end) not in lx.RELATIVE_BE:
        return None if tail else Refusal(rf.where_after_a_room(r.rest(thing.end)))
    end = thing.end + 1
    end += 1 if r.word(end) in lx.RELATIVE_PARTICIPLES else 0
    if not r.at(end, *tail):
        return None if tail else Refusal(rf.where_after_a_room(r.rest(end)))
    return Match(Holds(thing.node, tuple(also)), end + len(tail))


@QUALIFIERS.rule("without")
def without(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bedroom without a potted plant*: which bedroom, when the plant tells the rooms apart (the scene
    decides, :class:`.tree.Attachment`); otherwise *without* is what to avoid, after the phrase."""
    if noun.kind == "object" or r.word(i) != "without" or not r.np_starts(i + 1):
        return None
    return attachment(r, i, noun, "without")


def attachment(r: Reader, i: int, noun: NounSoFar,
               kind: Literal["without", "and-contents"]) -> Parse[Qualifier]:
    """The attachment of the words at ``i`` (*without X* / *and X*) to ``noun``, unless it was decided
    against, or X does not name objects (then the words are read after the phrase)."""
    if r.decided(i) is False:
        return None
    thing = noun_phrase(r, i + 1, "qualifier")
    if not isinstance(thing, Match) or not names_objects(thing.node):
        return None
    node = Attachment(i, kind, noun.noun, thing.node, r.span(noun.first, thing.end), r.decided(i) is True)
    return Match(node, skip_in_it(r, thing.end))


def names_rooms(phrase: object) -> bool:
    """Whether a phrase's words name rooms (*the kitchen*, *room_4*)."""
    return isinstance(phrase, Described) and head_kind(phrase) == "room" and not phrase.compound and not any(
        isinstance(q, Possessive) for q in phrase.qualifiers)


def names_objects(phrase: object) -> bool:
    """Whether a phrase's words name objects (so that it may describe a room's contents)."""
    if not isinstance(phrase, Described):
        return False
    kind = head_kind(phrase)
    for q in phrase.qualifiers:
        kind = q.head.kind if isinstance(q, Possessive) else kind
    return kind == "object"


@QUALIFIERS.rule("that has no")
def lacks(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bedroom that doesn't have a book* / *with no teddy bear*: the rooms holding none."""
    said = r.phrase(i, lx.QUAL_LACKS)
    if said is None or not r.np_starts(i + len(said)):
        return None
    thing = noun_phrase(r, i + len(said), "qualifier")
    if not isinstance(thing, Match):
        return thing
    return Match(Lacks(thing.node, r.span(noun.first, thing.end)), skip_in_it(r, thing.end))


@QUALIFIERS.rule("with")
def contains(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bedroom with / that has / containing (only) (two) beds (in it)*."""
    said = r.phrase(i, lx.QUAL_CONTAINS)
    if said is None:
        return None
    count, start = exact_count(r, i + len(said))  # "where there is only one sink"
    of_them = count is not None and r.at(start, "of", "them")
    # "either sink in the bathroom that has two of them": two of the object named last
    counted = named_before(r, i) if of_them else counted_before(r, i) if count is not None else None
    if counted is not None and start == i + len(said) + 1:
        # "the one with one sink first, then the one with two": two of what was counted last
        end = start + (2 if of_them else 0)
        thing_said = Described(r.span(start - 1, end), r.word(start - 1), Determiner("all", None), None, None,
                               None, counted, None, (), None, False)
        return Match(Contains(thing_said, r.span(noun.first, end), count, False), end)
    if not r.np_starts(start):
        return None
    thing = noun_phrase(r, start, "qualifier")
    if not isinstance(thing, Match):
        return thing
    end, nothing_else = contents_end(r, thing.end)
    trailing = r.word(end) == "only" and r.word(end + 1) not in lx.ONLY_FOLLOWERS  # "bdrm w/ bed only"
    # "with only / just the bed": nothing else; "with only / just one bed": exactly one
    only = ((bool(set(said) & lx.ONLY_WORDS) or trailing) and count is None) or nothing_else
    said_as = Contains(thing.node, r.span(noun.first, thing.end), count, only)
    return Match(said_as, end + (1 if trailing else 0))


def counted_before(r: Reader, i: int) -> Head | None:
    """The object counted last in a room's contents before ``i`` (*one sink* in *the one with one sink
    first, then the one with two*) when the contents at ``i`` end with a count and no noun; ``None`` when a
    noun follows or no contents were counted (*sit on one chair, then the bedroom with two*: two what?)."""
    said = r.phrase(i, lx.QUAL_CONTAINS)
    end = i + len(said or ()) + 1
    if r.np_starts(end) or r.head(end) is not None:
        return None
    for j in range(i - 1, 0, -1):
        head = r.head(j + 1) if count_word(r, j) is not None else None
        if head is not None and head.kind == "object" and (r.word(j - 1) in lx.CONTENTS_BEFORE_COUNT):
            return replace(head, plural=True)
    return None


def named_before(r: Reader, i: int) -> Head | None:
    """The object head named last before ``i`` (*them* in *either sink in the bathroom that has two of
    them*), or ``None``."""
    heads = (r.head(j) for j in range(i - 1, -1, -1))
    return next((replace(h, plural=True) for h in heads if h is not None and h.kind == "object"), None)


@QUALIFIERS.rule("relative have")
def relative_have(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """A room's contents said by a relative clause in any form of *have* that the phrases of *with* do not
    list: *which is having a vase*, *that has got two sinks*, *which had just the one sink*, *that is not
    having a vase*, *which hasn't got a plant* (the rooms holding none)."""
    k = i + (1 if r.word(i) == "," else 0)
    pronoun = r.word(k) in lx.RELATIVE_PRONOUNS or r.word(k) in lx.LEARNERS_RELATIVES
    if noun.kind == "object" or not pronoun:
        return None
    k += 1 + (1 if r.word(k + 1) in lx.RELATIVE_ADVERBS else 0)  # "that also has a vase"
    k += 1 if r.word(k) in lx.ONLY_WORDS else 0
    only = r.word(k - 1) in lx.ONLY_WORDS
    negated = r.word(k) in lx.HAVE_AUXILIARIES and r.word(k + 1) == "not"
    k += 2 if negated else 1 if r.word(k) in lx.HAVE_AUXILIARIES and r.word(k + 1) in lx.HAVE_FORMS else 0
    if r.word(k) not in lx.HAVE_FORMS and not (negated and r.word(k - 1) in lx.HAVE_FORMS):
        return None  # "the room that is in ..." / "that was cleaned": no contents
    k += 1 if r.word(k) in lx.HAVE_FORMS else 0
    k += 1 if r.word(k) == "got" else 0  # "that has got", "which hasn't got"
    only = only or r.word(k) in lx.ONLY_WORDS or r.at(k, "nothing", "but")
    k += 2 if r.at(k, "nothing", "but") else 1 if r.word(k) in lx.ONLY_WORDS else 0  # "has nothing but a bed"
    count, start = exact_count(r, k)
    if not r.np_starts(start):
        return None
    if negated and (only or count is not None):
        return Refusal(rf.negated_count(r.quote(i, start)))
    thing = noun_phrase(r, start, "qualifier")
    if not isinstance(thing, Match):
        return thing
    if negated:
        return Match(Lacks(thing.node, r.span(noun.first, thing.end)), skip_in_it(r, thing.end))
    end, nothing_else = contents_end(r, thing.end)
    only = (only and count is None) or nothing_else
    said_as = Contains(thing.node, r.span(noun.first, thing.end), count, only)
    return Match(said_as, end)


@QUALIFIERS.rule("and more contents")
def more_contents(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """After *the bedroom with the book*: *and the vase* may say more of its contents, or name another goal
    (the scene decides, :class:`.tree.Attachment`); closed by *in it* (*with the vase and the plant in it*),
    it says more of the contents."""
    said = noun.noun.qualifiers
    if (not said or not isinstance(said[-1], Contains) or r.word(i) != "and" or not r.np_starts(i + 1)
            or r.word(i + 1) in lx.PRONOUNS):
        return None
    thing = noun_phrase(r, i + 1, "qualifier")
    if isinstance(thing, Match) and r.at(thing.end, "in", "it"):
        return Match(Contains(thing.node, r.span(noun.first, thing.end), None, False), thing.end + 2)
    return attachment(r, i, noun, "and-contents")


@QUALIFIERS.rule("next to")
def next_to(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*next to / adjacent to / attached to / outside / just off the kitchen*, *next to it*."""
    said = r.phrase(i, lx.QUAL_NEXT)
    if said is None or not r.np_starts(i + len(said)):
        return None
    start, relation = i + len(said), " ".join(said)
    if r.word(start) == "it":
        it = NextTo(None, r.span(noun.first, start + 1), r.span(start, start + 1), relation)
        return Match(it, start + 1)
    thing = noun_phrase(r, start, "qualifier")
    if not isinstance(thing, Match):
        return thing
    if noun.kind == "object" and said in lx.CARRY_BESIDE and names_objects(thing.node):
        goes = goes_there(r, noun, i + len(said) - 1, thing.end)  # "put the cup by the keyboard"
        if goes is not False:
            return goes
    return Match(NextTo(thing.node, r.span(noun.first, thing.end), None, relation), thing.end)


@QUALIFIERS.rule("next door")
def next_door(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bathroom next door*: next to the room of the place named last; *next door to X* is *next to X*."""
    said = r.phrase(i, lx.NEXT_DOOR)
    if said is None:
        return None
    end = i + len(said)
    if r.word(end) == "to" and r.word(end + 1) == "it":
        it = r.span(end + 1, end + 2)
        return Match(NextTo(None, r.span(noun.first, end + 2), it, "next door to"), end + 2)
    if r.word(end) == "to" and r.np_starts(end + 1):
        thing = noun_phrase(r, end + 1, "qualifier")
        if not isinstance(thing, Match):
            return thing
        return Match(NextTo(thing.node, r.span(noun.first, thing.end), None, "next door to"), thing.end)
    return Match(NextTo(None, r.span(noun.first, end), r.span(i, end), " ".join(said)), end)


@QUALIFIERS.rule("between")
def between(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bathroom between the bedrooms*, *the hall between the kitchen and the office*: a room connected
    to each of them (:func:`..grounding.described.between`)."""
    if r.word(i) != "between" or noun.kind != "room" or not r.np_starts(i + 1):
        return None
    things, j = [], i + 1
    while True:
        thing = noun_phrase(r, j, "qualifier")
        if not isinstance(thing, Match):
            return thing
        things.append(thing.node)
        if r.word(thing.end) != "and" or not r.np_starts(thing.end + 1):
            return Match(Between(tuple(things), r.span(noun.first, thing.end)), thing.end)
        j = thing.end + 1


@QUALIFIERS.rule("at an object")
def at_an_object(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the chair at the dining table*, *a vase on the table*, *the book under the bed*, *the bowl on it*: an
    object placed by another object, read as one in that object's room (grounding decides, :func:`next_to`'s
    node); not after a carry verb (*put the cup on the table*: where it is carried, read by the action)."""
    if noun.kind != "object" or r.word(i) not in lx.OBJECT_PLACING:
        return None
    if r.word(i + 1) == "it" and r.word(i + 2) in lx.CLAUSE_ENDS and not carried(r, noun):
        return Match(NextTo(None, r.span(noun.first, i + 2), r.span(i + 1, i + 2), r.word(i)), i + 2)
    k = i + 1 + (1 if r.word(i + 1) in lx.DETERMINERS else 0)
    head = r.head(k)
    if head is None or head.kind != "object":
        return None
    thing = noun_phrase(r, i + 1, "qualifier")
    if not isinstance(thing, Match):
        return thing
    goes = goes_there(r, noun, i, thing.end)
    if goes is not False:
        return goes
    return Match(NextTo(thing.node, r.span(noun.first, thing.end), None, r.word(i)), thing.end)


@QUALIFIERS.rule("by a thing not in the scene")
def by_unlisted(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the bowl on the counter*, *the book on the shelf in the office*: an object placed by one word the
    scene does not hold (no misspelt name of it, :func:`.noun_slot.foreign_word`), at the end of the phrase;
    a description of the object (:func:`finish` adds the words to its descriptive words: read only where
    the scene leaves one such object). Not after a carry verb (*put the cup on the shelf*: where it goes,
    which the scene cannot hold)."""
    if noun.kind != "object" or r.word(i) not in lx.OBJECT_PLACING or carried(r, noun):
        return None
    k = i + 2 if r.word(i + 1) in lx.DETERMINERS else i + 1
    if k == i + 1 or not foreign_word(r, k) or r.spelling is None or r.spelling.is_known(r.word(k)):
        return None
    if r.word(k + 1).isalpha() and r.word(k + 1) not in lx.AFTER_UNLISTED_THING:
        return None  # "on the side of the couch", "on the counter top": more than one word said it
    return Match(ByUnlisted(" ".join(r.words[i:k + 1]), r.span(i, k + 1)), k + 1)


def carried(r: Reader, noun: NounSoFar) -> bool:
    """Whether a carry verb just before the phrase may take it somewhere (*put the cup by the keyboard*)."""
    return any(w in lx.CARRY_VERBS for w in r.words[max(0, noun.first - 3):noun.first])


def goes_there(r: Reader, noun: NounSoFar, i: int, end: int) -> Refusal | Literal[False] | None:
    """After a carried object, the object phrase from ``i`` to ``end`` (*on the table*, *by the couch*):
    ``False`` when it says which object is carried (not carried, or a destination follows: *bring the bowl on
    the table to the couch*); ``None`` when it is where the object goes (after *put / place / drop ...*, or
    when the object's room was said; read by the action); a refusal when it could be either (*bring the bowl
    by the couch*)."""
    if not carried(r, noun) or r.word(end) in lx.DESTINATION_WORDS:
        return False
    if noun.room_scoped or any(w in lx.PLACING_VERBS for w in r.words[max(0, noun.first - 3):noun.first]):
        return None  # "bring the bottle from the bathroom in the sink": its room said, this is where it goes
    return Refusal(rf.placed_or_where_it_is(r.quote(noun.first, end), r.quote(i + 1, end)))


@QUALIFIERS.rule("short stay")
def short_stay(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*sit on the couch for a bit*, *look at the TV for a few minutes*: how long to stay, closing the clause
    (read where the phrase is a goal, :func:`..grounding.described.short_stay`)."""
    said = r.phrase(i, lx.SHORT_STAYS)
    if said is None or noun.role == "qualifier" or r.word(i + len(said)) not in (*lx.CLAUSE_ENDS, "then"):
        return None  # (inside a qualifier, the stay is at the phrase it qualifies)
    start = max((k + 1 for k in range(i) if r.word(k) == ","), default=0)
    if any(r.phrase(k, table) for k in range(start, i) for table in (lx.CONDITION_WORDS, lx.WHENEVER)) or set(
            r.words[start:i]) & lx.STAY_TIMED_CLAUSES:  # "if you sit on the couch for a bit, ..."
        return Refusal(rf.short_stay_not_a_goal(" ".join(said), r.quote(noun.first, i)))
    return Match(ShortStay(r.span(i, i + len(said))), i + len(said))


@QUALIFIERS.rule("contact clause")
def contact_clause(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*the chair you want in the dining room*, *the bowl I left in the kitchen*: a relative clause without
    *that*, about the thing; read as a clause of its own it would make *in the dining room* another goal, so
    it is refused, naming the words."""
    nxt = r.word(i + 1)
    if (r.word(i) not in lx.CONTACT_SUBJECTS or not nxt.isalpha() or nxt in lx.STATEMENT_VERBS
            or r.phrase(i, lx.POLITE) is not None  # "... the kitchen I want you to check ...": an order
            or r.phrase(i, lx.CORRECTIONS) is not None):  # "the bowl i mean the oven": a correction
        return None
    return Refusal(rf.contact_clause(r.quote(noun.first, min(len(r), i + 2))))


@QUALIFIERS.rule("except")
def except_for(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier | Skipped]:
    """*all the corridors except (for) the one on floor 0*, *every room but not the kitchen*."""
    comma = 1 if r.word(i) == "," else 0
    said = r.phrase(i + comma, lx.QUAL_EXCEPT)
    if said is None or not r.np_starts(i + comma + len(said)):
        return None
    j, things = i + comma + len(said), []
    given = current_head(noun.noun)
    while True:
        thing = noun_phrase(r, j, "qualifier", given)
        if not isinstance(thing, Match):
            return thing
        things.append(thing.node)
        j = thing.end
        if not (r.word(j) in ("and", "or", ",") and r.np_starts(j + 1)):
            break
        j += 1
    return Match(Except(tuple(things), " ".join(said), r.quote(noun.first, i)), j)
