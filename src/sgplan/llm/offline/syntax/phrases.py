"""Syntax rules for noun phrases and lists of them: *the sink in the kitchen*, *both bedrooms*, *it*,
*there*, *the kitchen or the dining room*, *neither A nor B*.

A phrase is read from its words and the scene's head nouns only; its qualifiers are the rules of
:mod:`.qualifiers`. Grounding it (which rooms or objects, refusals of what matches nothing or several) is
:mod:`..grounding.phrases`.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax import qualifiers
from sgplan.llm.offline.syntax.floors import floor_words
from sgplan.llm.offline.syntax.links import closing_at
from sgplan.llm.offline.syntax.noun_slot import (
    NOUN_PHRASES,
    count_word,
    foreign_word,
    head_noun,
    noun_phrase,
    superlative,
)
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal
from sgplan.llm.offline.syntax.tree import (
    Described,
    Determiner,
    FloorNumber,
    FloorPlace,
    FloorSpec,
    GroupRepeat,
    HandledAt,
    HeadRef,
    InRoom,
    Its,
    KeyHead,
    Mode,
    NounPhrase,
    OneHead,
    OnFloor,
    PhraseList,
    Pronoun,
    Role,
    SameRoom,
    Span,
    ThereNP,
    TopFloor,
)


@NOUN_PHRASES.rule("there")
def there_place(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*get there*: the last place named as a goal."""
    return Match(ThereNP(r.span(i, i + 1)), i + 1) if r.word(i) == "there" else None


@NOUN_PHRASES.rule("all of them")
def group_repeat(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*all of them*, *both of them*, *all three of them*, *all three*, *the two of them*, *both* closing its
    clause (a goal): the group named before; *one / any / either of them*: one of it."""
    if role == "goal" and r.word(i) in lx.CHOOSING_OF and r.at(i + 1, "of", "them"):
        return Match(GroupRepeat(r.span(i, i + 3), None, choice=True), i + 3)
    if (role == "goal" and r.word(i) == "both" and r.word(i + 1) in ("", ",", "and", "then")
            and (r.word(i - 1) == "," or r.word(i - 1) in lx.POSITIVE_VERBS)):
        return Match(GroupRepeat(r.span(i, i + 1), 2), i + 1)  # "the plants, both, then ...": both of them
    n = 1 if r.word(i) in ("all", "both", "each", "every") else 0
    n = 1 if r.word(i) == "the" and count_word(r, i + 1) and r.at(i + 2, "of", "them") else n
    said = lx.NUMBER_WORDS.get(r.word(i + n)) if n else None
    k = i + n + (1 if said else 0)
    if role != "goal" or not n or (not r.at(k, "of", "them") and not (said and r.word(k) in ("", ","))):
        return None
    end = k + (2 if r.at(k, "of", "them") else 0)
    return Match(GroupRepeat(r.span(i, end), 2 if r.word(i) == "both" else said), end)


@NOUN_PHRASES.rule("the same room")
def same_room(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*the sink in the same room*: the room of the place named last (inside a qualifier only)."""
    if role != "qualifier" or not r.at(i, "the", "same") or r.word(i + 2) not in ("room", "place"):
        return None
    return Match(SameRoom(r.span(i, i + 3), r.word(i + 2)), i + 3)


@NOUN_PHRASES.rule("its")
def its(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*its sink*: in the room named just before; *one of its chairs* (any), *both / all of its sinks*."""
    k = i
    mode_said: Mode | None = None
    if r.word(i + 1) == "of" and r.word(i + 2) == "its":
        mode_said = "any" if r.word(i) in lx.CHOOSING_OF else "all" if r.word(i) in lx.UNIVERSAL else None
        if mode_said is None:
            return None
        k = i + 2
    if r.word(k) != "its" or r.head(k + 1) is None:
        return None
    head = head_noun(r, k + 1, None)
    if not isinstance(head, Match):
        return head
    assert isinstance(head.node, Head)
    return Match(Its(r.span(i, head.end), head.node, mode_said), head.end)


@NOUN_PHRASES.rule("pronoun")
def pronoun(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*it*, *them*, *they*: the phrase named last that agrees in number."""
    return Match(Pronoun(r.span(i, i + 1), r.word(i)), i + 1) if r.word(i) in lx.PRONOUNS else None


@NOUN_PHRASES.rule("that first")
def that_first(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*check that first, then ...*: *that* is the thing named last (as *it*), *first* an order word, not an
    ordinal (*that first bedroom*); read only with *then* after it, so that the order is said in words."""
    if r.word(i) != "that" or r.word(i + 1) != "first" or "then" not in r.words[i + 2:i + 5]:
        return None
    return Match(Pronoun(r.span(i, i + 1), "that"), i + 1)


@NOUN_PHRASES.rule("the two in X")
def counted_ones(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*the two in the lounge* after *the plant in the bedroom*: the ones of the kind named last (as *the
    ones in the lounge*), and there must be that many."""
    n = count_word(r, i + 1) if r.word(i) == "the" and given is None else None
    if n is None or n < 2 or r.word(i + 2) not in lx.QUAL_IN or r.word(i + 2) == "of":
        return None  # not "the two of the vases" / "the two of them" (both)
    if not r.np_starts(i + 3):
        return None
    ones, det = OneHead(True, None, True), Determiner("all", n)
    noun = Described(r.span(i, i + 2), "the", det, None, None, None, ones, None, (), None, False)
    return qualifiers.finish(r, i, i + 2, noun, role, False)


@NOUN_PHRASES.rule("a thing handled at an object")
def handled_at(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*rinse the watering can (out) at the kitchen sink*, *fill a glass at the sink*, *heat my leftovers in
    the microwave*: a thing the scene does not hold, handled at one of its objects, which is the goal (the
    thing is said back as set aside); after a verb that fetches or carries it (*put my keys on the table*)
    the robot would have to find it: refused, saying so."""
    if role != "goal" or given is not None or r.word(i) not in lx.DETERMINERS:
        return None
    j = i + 1
    while j < i + 4 and foreign_word(r, j):
        j += 1
    k = j + (1 if r.word(j) in lx.PARTICLES and r.word(j + 1) in lx.HANDLED_AT else 0)
    if j == i + 1 or r.word(k) not in lx.HANDLED_AT or not r.np_starts(k + 1):
        return None
    at = noun_phrase(r, k + 1, role)
    if not isinstance(at, Match) or not qualifiers.names_objects(at.node):
        return None
    if set(r.words[max(0, i - 2):i]) & lx.FETCH_VERBS:
        return Refusal(rf.thing_to_find(r.quote(i + 1, j), r.quote(i, at.end)))
    return Match(HandledAt(r.span(i, at.end), r.span(i, j), at.node), at.end)


@NOUN_PHRASES.rule("start floor")
def start_floor_place(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """*this floor* / *my floor* named as a place (*come back to this floor and check the couch*), as *the top
    floor* is; not before a room's noun or *one* (*this floor's bathroom*, *the this floor one*)."""
    if r.word(i) not in lx.START_FLOOR_WORDS:
        return None
    floor = floor_words(r, i)
    if floor is None or r.head(floor.end) is not None or qualifiers.anaphoric_one(r, floor.end):
        return None
    return Match(FloorPlace(r.span(i, floor.end), floor.node, "any"), floor.end)


@NOUN_PHRASES.rule("described")
def described(r: Reader, i: int, role: Role, given: Head | None) -> Parse[NounPhrase]:
    """A determiner, floor words, a head noun and its qualifiers (*the ground floor bathroom with the
    sink*), or a floor named as a place (*the top floor*)."""
    first = i
    one_from_context = given is None and ones_of_context(r, i)
    other = r.at(i, "the", "other") and other_of_a_head(r, i + 2)
    if r.at(i, "the", "other", "one"):  # "the bedroom with the book, then the other one"
        one_from_context, other = given is None, True  # (given: "the kitchen, no wait, the other one")
    bare_other = r.word(i) == "other" and r.head(i + 1) is not None  # "then other bdrm", as notes say it
    other = other or bare_other
    ordinal, counted_one = named_ordinal(r, i, given)
    one_from_context = one_from_context or counted_one
    det = determiner(r, i if bare_other or not other else i + 1, other)
    if not isinstance(det, Match):
        return det
    if ordinal is not None:
        det = Match(replace(det.node, ordinal=ordinal + 1), det.end + 1)
    start = det.end + (1 if other and r.word(det.end) == "other" else 0)  # "the other upstairs bedroom"
    i = description_end(r, start)
    said = r.words[start:i]
    if given is None and (one := room_one(r, first, i, role, replace(det.node, descriptive=said))):
        return one
    relative = r.word(i) if r.word(i) in lx.RELATIVE_FLOORS else None
    floor_before = None if relative else floor_words(r, i) or floor_without_floor(r, i)
    if relative:
        i += 1
    elif floor_before is not None:
        i = floor_before.end
        if r.head(i) is None and not qualifiers.anaphoric_one(r, i):  # "the top floor": a place
            return floor_place(r, first, i, floor_before.node, det.node)
    described_as = (*said, *r.words[i : r.descriptive_end(i)])  # "the big (upstairs) couch"
    # "the downstairs one", "the top floor one": of the kind named last, on that floor
    floor_one = (bool(relative or floor_before) and given is None
                 and qualifiers.anaphoric_one(r, r.descriptive_end(i)))
    return noun_with_head(r, first, r.descriptive_end(i), role, replace(det.node, descriptive=described_as),
                          relative, None if floor_before is None else floor_before.node,
                          OneHead(False, given, one_from_context or floor_one))


def floor_without_floor(r: Reader, i: int) -> Match[FloorSpec] | None:
    """*the top bathroom*, *the bottom bedroom*: a room on the top / lowest floor, as *the top floor bathroom*
    (the word *floor* left out); only before a room's noun, and only the words that name one floor in any
    building (*upper*, *lower* could be any floor above or below another: refused)."""
    w, room = r.word(i), r.head(i + 1)
    if room is None or room.kind != "room" or w not in lx.FLOOR_ENDS_ALONE:
        return None
    spec: FloorSpec = TopFloor(w) if w in lx.FLOOR_TOP else FloorNumber(lx.FLOOR_NAMED[w], w)
    return Match(spec, i + 1)


def named_ordinal(r: Reader, i: int, given: Head | None) -> tuple[int | None, bool]:
    """*the first / second ...* at ``i`` counting what was named before (*back to the first bedroom*), and
    whether it is of the kind named last (*the first one*, *back to the first (again)*); ``None`` for a
    floor (*the first floor*: :func:`.floors.floor_words`)."""
    ordinal = lx.FLOOR_ORDINALS.get(r.word(i + 1)) if r.word(i) == "the" and given is None else None
    one = r.word(i + 2) in lx.ANAPHORIC_ONE or r.word(i + 2) in lx.ORDINAL_ALONE_BEFORE
    if ordinal is None or not (one or r.head(i + 2) is not None):
        return None, False
    return ordinal, one


def other_of_a_head(r: Reader, i: int) -> bool:
    """Whether a head noun follows *other* (at ``i``), after floor words if any (*the other upstairs
    bedroom*, *the other top-floor bathroom*)."""
    if r.word(i) in lx.RELATIVE_FLOORS:
        i += 1
    elif (floor := floor_words(r, i)) is not None:
        i = floor.end
    return r.head(i) is not None


def ones_of_context(r: Reader, i: int) -> bool:
    """Whether *the (big) one(s)* (also after *either / one / both of*) or *any one* starts at ``i``: of the
    kind named last (*the ones in the living room*, *either of the ones in the living room*, *then any one
    in the office*; *any in the office* is read as that, `lexicon.PHRASE_ALIASES`)."""
    lead = 2 if r.word(i) in (*lx.CHOOSING_OF, *lx.UNIVERSAL) and r.at(i + 1, "of", "the") else 0
    if qualifiers.any_one_located(r, i):
        return True
    return r.word(i + lead) in ("the", "a") and r.word(r.descriptive_end(i + lead + 1)) in lx.ANAPHORIC_ONE


def description_end(r: Reader, i: int) -> int:
    """Where the words describing the thing end at ``i``: the lexicon's descriptive words (*big*, *comfy*)
    and words neither the scene nor the lexicon knows right before a head noun (*the paperback book*, *the
    fruit bowl*), which describe it as those do (read only where they cannot change which entity is meant,
    :func:`..grounding.described.ground_described`); ``i`` when no head noun follows them."""
    j = r.descriptive_end(i)
    k = j
    while k < j + 3 and describing_word(r, k):
        k += 1  # "the old paperback book": the lexicon's words and unknown ones, mixed
    if k == j or (r.descriptive_end(k) == k and r.head(k) is None):
        return j
    return description_end(r, k)


def describing_word(r: Reader, i: int) -> bool:
    """Whether the word at ``i`` may describe a head noun that follows: a descriptive word of the lexicon that
    names nothing of the scene (*old*), or a word neither the scene nor the lexicon knows (*paperback*; a word
    of the grammar, *upstairs*, *dining*, *other*, is never a mere description; nor is a word of one or two
    letters, *x*, *w*: operators' shorthand, as in *x kitchen*)."""
    w = r.word(i)
    if w in lx.DESCRIPTIVE:
        return not r.nouns.names_word(w) and r.head(i) is None
    return len(w) > 2 and foreign_word(r, i) and r.spelling is not None and not r.spelling.is_known(w)


def room_one(r: Reader, first: int, i: int, role: Role, det: Determiner) -> Parse[NounPhrase]:
    """*the living room one*, *the office ones* (at ``i``, the room's head): the kind named last, in that
    room, as *the one in the living room*; ``None`` when no room and *one* are at ``i``."""
    room = r.head(i) if not det.other and det.pointer is None else None
    if room is None or room.kind != "room" or room.plural or not qualifiers.anaphoric_one(r, i + room.words):
        return None
    end = i + room.words
    room_np = Described(r.span(i, end), r.word(i), Determiner("the", None), None, None, None, room, None, (),
                        None, False)
    plural = r.word(end) == "ones"
    mode = ("all" if plural else "the") if det.mode is None else ("all" if det.mode == "the" and plural
                                                                   else det.mode)
    noun = Described(r.span(first, end + 1), r.word(first), replace(det, mode=mode, descriptive=()), None,
                     None, None, OneHead(plural, None, True), None,
                     (InRoom((room_np,), r.span(first, end + 1)),), None, False, det.descriptive)
    return qualifiers.finish(r, first, end + 1, noun, role, True)


def noun_with_head(r: Reader, first: int, i: int, role: Role, det: Determiner, relative: str | None,
                   floor_before: FloorSpec | None, one: OneHead) -> Parse[NounPhrase]:
    """The rest of :func:`described` from the head noun on: head, compound, qualifiers, apposition."""
    modifier = None
    if r.word(i).startswith(("room_", "object_")):
        head: Parse[HeadRef] = Match(KeyHead(r.word(i)), i + 1)
        mode: Mode | None = "the"
    else:
        modifier = r.nouns.room_modifier(r.words, i)
        head = head_noun(r, i + (1 if modifier else 0), one)
        mode = det.mode
    if not isinstance(head, Match):
        return head
    i, ref = head.end, head.node
    plural = ref.plural if isinstance(ref, Head | OneHead) else False
    mode = ("all" if plural else "the") if mode is None else ("all" if mode == "the" and plural else mode)
    compound = None
    kind = ref.kind if isinstance(ref, Head) else "room" if isinstance(ref, KeyHead) and \
        ref.key.startswith("room_") else None
    floor_then = floor_words(r, i) if kind == "room" and floor_before is None else None
    if floor_then is not None and (after := r.head(floor_then.end)) is not None and after.kind == "object":
        floor_before, i = floor_then.node, floor_then.end  # "the bathrm mid flr sink": that floor's bathroom
    if kind == "room" and (after := r.head(i)) is not None and after.kind == "object":
        compound, i = after, i + after.words  # "the kitchen sink": the sink in the kitchen
        mode = "all" if after.plural and mode == "the" else mode
    noun = Described(r.span(first, i), r.word(first), replace(det, mode=mode, descriptive=()), relative,
                     floor_before, modifier, ref, compound, (), None, False, det.descriptive)
    found = qualifiers.finish(r, first, i, noun, role, compound is not None or modifier is not None)
    return chosen_inside(r, found) if isinstance(found, Match) else found


def chosen_inside(r: Reader, found: Match[Described]) -> Match[Described]:
    """*the bathroom on the middle floor, either sink is fine*: a remark choosing an object of the room just
    named makes the phrase such an object in it, as *the bathroom sink* (any of them when they lie in one
    room, refused when they lie in several); ``found`` unchanged otherwise (a remark about the room itself
    is read where choices are)."""
    noun, i = found.node, found.end
    k = i + (1 if r.word(i) == "," else 0)
    head = r.head(k + 1) if r.word(k) in lx.CHOOSERS_OF_KIND else None
    if (head is None or head.kind != "object" or not isinstance(noun.head, Head) or noun.head.kind != "room"
            or noun.head.plural or noun.compound is not None or noun.determiner.mode != "the"
            or not all(isinstance(q, OnFloor) for q in noun.qualifiers)):  # the room's contents: of it
        return found
    fine = r.phrase(k + 1 + head.words, lx.REMARK_FINE)
    end = k + 1 + head.words + len(fine or ())
    if fine is None or r.word(end) not in lx.CLAUSE_ENDS:
        return found
    return Match(replace(noun, span=Span(noun.span.start, r.span(k, end).end), compound=head), end)


def determiner(r: Reader, i: int, other: bool) -> Parse[Determiner]:
    """The words before the noun: a demonstrative (*that*, *those two*, *the same*), or a quantifier
    (*the*, *a*, *any*, *all*, *one of the two*, *every*, *my*), possibly followed by a demonstrative
    (*one of those*)."""
    demo = demonstrative(r, i)
    if demo:  # "that bathroom", "those two bedrooms", "the same sink": resolved later, never fresh
        count = count_word(r, i + demo)
        end = i + demo + (1 if count else 0)
        return Match(Determiner("all" if count else "the", count, pointer=r.word(i), other=other), end)
    if r.word(i) in lx.OWNERS and r.head(i + 1) is not None:
        return Match(Determiner("the", None, pointer=r.word(i), other=other), i + 1)  # "her room", "his bed"
    owned = persons_possessive(r, i)
    if owned:  # "the baby's teddy bear": the teddy bear; "my son's room": whose room? (grounding)
        return Match(Determiner("the", None, other=other, owner=r.quote(i, i + owned)), i + owned)
    quant = quantifier(r, i)
    if not isinstance(quant, Match):
        return quant
    det, i = quant.node, quant.end
    demo = demonstrative(r, i) if det.mode is not None else 0
    if demo:  # "one of those bedrooms": chosen among them
        count = det.count if det.count is not None else count_word(r, i + demo)
        end = i + demo + (1 if count is not None and det.count is None else 0)
        return Match(Determiner(det.mode, count, r.word(i), det.mode, other), end)
    compared = next((w for w in r.words[i:description_end(r, i)] if superlative(w)), None)
    if compared is not None:  # "the heaviest bottle", "the ripest apple": a comparison the scene cannot make
        return Refusal(rf.superlative(compared))
    return Match(replace(det, other=other), i)


def quantifier(r: Reader, i: int) -> Parse[Determiner]:
    """Determiners -> the mode they ask for and the count they say; ``None`` mode: the head's number
    decides."""
    w = r.word(i)
    mode: Mode | None = None
    count: int | None = None
    chosen_from = False
    if (w in lx.CHOOSING_OF or w in lx.ONE_SAID) and r.word(i + 1) == "of":
        i, mode = i + 2, "any"
        chosen_from = r.word(i) in ("the", "these", "those")  # "one of the two bathrooms"
    elif w in lx.INDEFINITE:
        i, mode = i + 1, "any"
    elif w in ("each", "every") and (r.at(i + 1, "one", "of") or r.at(i + 1, "single", "one", "of")):
        i, mode = i + (3 if r.word(i + 1) == "one" else 4), "all"  # "every (single) one of the vases"
    elif w in lx.UNIVERSAL or (w == "the" and r.word(i + 1) == "both"):
        # "the both bedrooms", as learners write it (the article of their language): both
        i += 1 if w == "the" else 0
        i, mode, count = i + 1, "all", (2 if r.word(i) == "both" else None)
        i += 1 if r.word(i) == "of" else 0
    elif w in lx.DEMONSTRATIVES and r.word(i + 1) not in lx.FLOOR_WORDS:
        # only the demonstrative path may read "that ..." / "this ...": never a fresh description
        return Refusal(rf.demonstrative_not_before_noun(w, r.word(i + 1)))
    elif w in lx.DEFINITE or w in lx.POSSESSIVES:
        i, mode = i + 1, "the"
    i += 1 if r.word(i) == "the" and mode is not None else 0
    n = count_word(r, i) if mode == "the" and r.at(i + 1, "of", "the") else None
    if n is not None:
        return Match(Determiner("all", n), i + 3)  # "the two of the vases": both
    noun_next = ((r.np_starts(i + 1) and r.word(i + 1) not in lx.RELATIVE_PRONOUNS)  # not "the one that is"
                 or r.head(i + 1) or r.nouns.room_modifier(r.words, i + 1))
    n = count_word(r, i) if noun_next else None  # "all three (dining) chairs"
    if n is not None and chosen_from:
        return Match(Determiner(mode, n), i + 1)  # one of them, and there must be n
    if n == 1 and (mode == "any" or (mode is None and r.word(i) in lx.ONE_SAID)):
        return Match(Determiner("any", None), i + 1)  # "sit on one chair", "see any one vase": any
    if n is not None:
        if mode in (None, "any"):
            return Refusal(rf.choosing_a_number(r.word(i)))
        return Match(Determiner("all", n), i + 1)
    return Match(Determiner(mode, count), i)


def persons_possessive(r: Reader, i: int) -> int:
    """How many words of a person's possessive start the phrase at ``i`` before a room or object noun
    (*the baby's*, *my son's*, *Lily's*, *the kids'*: a word for a person, or a capitalised name that is no
    word of the grammar or the scene, then *'s* or the plural's apostrophe); 0 if none. Names are taken
    only when typed with a capital, so that a word the translator does not know is never dropped as
    someone's name."""
    k = i + (1 if r.word(i) in lx.ARTICLES or r.word(i) in lx.POSSESSIVES else 0)
    if k >= len(r):
        return 0
    who, typed = r.word(k), r.quote(k, k + 1)
    # "the kids' bedroom": the plural's apostrophe is only in the text, after the word "kids"
    apostrophe = r.text[r.toks[k].end:r.toks[k].end + 1] in ("'", "\u2019")
    end = k + 2 if r.word(k + 1) == "'s" else k + 1 if apostrophe else k
    if end == k or r.head(k) is not None or r.head(end) is None:
        return 0  # "the children's room" is a room's name
    named = k == i and who.isalpha() and who not in lx.LEXICON_WORDS and typed[:1].isupper()
    if who not in lx.owners("their") and not named:
        return 0
    return end - i


def thing_in_room(r: Reader, items: list[NounPhrase], i: int, role: Role) -> Match[Described] | None:
    """*kitchen - microwave* (a room alone before the dash, a thing after it that ends the list): the
    thing in that room, as *the microwave in the kitchen* (grounding refuses it when the room holds none);
    ``None`` otherwise (a dash between two rooms or two things stays unclear: a route, or a set?)."""
    room = items[0] if len(items) == 1 else None
    if not isinstance(room, Described) or not isinstance(room.head, Head) or room.head.kind != "room":
        return None
    thing = noun_phrase(r, i, role)
    if (not isinstance(thing, Match) or not isinstance(thing.node, Described)
            or not isinstance(thing.node.head, Head) or thing.node.head.kind != "object"
            or r.word(thing.end) not in lx.CLAUSE_ENDS or r.word(thing.end) in ("and", "but")):
        return None
    located = InRoom((room,), room.span)
    return Match(replace(thing.node, qualifiers=(*thing.node.qualifiers, located)), thing.end)


def demonstrative(r: Reader, i: int) -> int:
    """How many words of a back-pointing determiner start the phrase at ``i`` (*that*, *those*, *the
    same*, *that same* before a room or object noun, with or without a number); 0 if none."""
    w, nxt = r.word(i), r.word(i + 1)
    n = 2 if w in ("the", "that", "this") and nxt == "same" else 1 if w in lx.DEMONSTRATIVES else 0
    if not n:
        return 0
    k = i + n + (1 if r.word(i + n) in lx.NUMBER_WORDS or r.word(i + n).isdigit() else 0)
    if r.word(k) in lx.FLOOR_WORDS or r.word(k) in lx.ANAPHORIC_ONE:
        return 0  # "this floor": the start floor; "that one" is refused
    return n


def restated_choice(r: Reader, i: int, before: NounPhrase) -> bool:
    """Whether *either / any <noun>* at ``i`` names again the kind of ``before`` (*a bed in the bedroom -
    either bed -*): the choice said again, not another goal (:func:`.meaning.actions.first_of_list`)."""
    head = r.head(i + 1)
    return (r.word(i) in lx.RESTATED_CHOOSERS and head is not None and isinstance(before, Described)
            and isinstance(before.head, Head) and head.categories == before.head.categories)


def phrase_list(r: Reader, i: int, role: Role) -> Parse[PhraseList]:
    """``A, B and C`` (each), ``A or B`` / ``either A or B`` / ``either to A or to B`` (one of them),
    ``neither A nor B`` (each, to avoid)."""
    first = i
    either = r.word(i) == "either" and r.word(i + 1) in lx.DETERMINERS
    # "go either to the couch or to the bed": the preposition is repeated after each conjunction
    repeated = (r.word(i) in ("either", "both") and r.word(i + 1) in lx.LIST_PREPOSITIONS
                and r.np_starts(i + 2))
    preposition = r.word(i + 1) if repeated else None
    either = either or (preposition is not None and r.word(i) == "either")
    i += 1 if either or (r.word(i) == "both" and r.word(i + 1) in lx.DETERMINERS) else 0
    i += 1 if preposition is not None else 0
    item = noun_phrase(r, i, role)
    if not isinstance(item, Match):
        return item
    items, joiners, i = [item.node], set[str](), item.end
    # "keep away from the kitchen and from the lobby": the preposition before the list said again
    again = preposition or (r.word(first - 1) if r.word(first - 1) in lx.REPEATED_PREPOSITIONS else None)
    while (joined := list_joiner(r, i, again)) is not None:
        restates = ((r.word(joined[1]) in lx.ARTICLES and r.word(joined[1] + 1) in lx.ANAPHORIC_ONE)
                    or isinstance(group_repeat(r, joined[1], role, None), Match)  # "the vases - all four"
                    or restated_choice(r, joined[1], items[-1]))  # "a bed in the bedroom - either bed -"
        if not joined[0] and not restates and r.text[r.toks[i].start:r.toks[i].end].strip() in lx.DASHES:
            located = thing_in_room(r, items, joined[1], role)
            if located is not None:  # "kitchen - microwave": the microwave in the kitchen
                items, i = [located.node], located.end
                continue
            # "kitchen - office - couch": a route, or a set? (a dash between asides is read as a comma)
            return Refusal(rf.dash_between_goals(r.quote(first, min(len(r), joined[1] + 2))))
        joiner, i = joined
        joiners |= {joiner} if joiner else set()
        item = noun_phrase(r, i, role)
        if not isinstance(item, Match):
            return item
        items.append(item.node)
        i = item.end
    said = r.quote(first, i)
    if "nor" in joiners and (role != "avoid" or len(joiners) > 1):
        return Refusal(rf.nor_outside_negation(said))
    if joiners == {"and", "or"}:
        return Refusal(rf.mixes_and_or(said))
    return Match(PhraseList(r.span(first, i), tuple(items), frozenset(joiners), either,
                            len(items) > 1 and not joiners and not either), i)


def there_then_verb(r: Reader, i: int) -> bool:
    """*there* at ``i`` before a verb (*go to the kitchen and there take the bowl*): the place of the next
    action, not an item of the list."""
    nxt = r.word(i + 1)
    return (r.word(i) == "there" and nxt.isalpha() and not r.np_starts(i + 1)
            and nxt not in lx.STATEMENT_LINKS and nxt not in lx.STRUCTURAL)


def list_joiner(r: Reader, i: int, preposition: str | None) -> tuple[str, int] | None:
    """The conjunction (``""`` for a bare comma) before a further item of a list at ``i`` and where that
    item starts; ``None`` when the list ends here."""
    w, nxt = r.word(i), r.word(i + 1)
    if preposition is not None and w in ("and", "or") and nxt == preposition and r.np_starts(i + 2):
        return w, i + 2
    if closing_at(r, i + (1 if w == "," else 0)):
        return None  # "the couch, and that's it": a sign-off, not an item
    if w == "," and nxt in ("and", "or") and r.np_starts(i + 2):
        return nxt, i + 2
    if (w == "," and r.np_starts(i + 1) and not r.phrase(i + 1, lx.NEG_STARTS) and not closing_at(r, i + 1)
            and not r.phrase(i + 1, lx.TIME_FILLERS) and qualifiers.remark_ahead(r, i) is None):
        return "", i + 1
    if w in ("and", "or", "nor") and r.np_starts(i + 1) and not there_then_verb(r, i + 1):
        return w, i + 1
    if r.at(i, ",", "nor") and r.np_starts(i + 2):
        return "nor", i + 2
    if r.at(i, "as", "well", "as") and r.np_starts(i + 3):
        return "and", i + 3
    return None


def floor_place(r: Reader, first: int, end: int, floor: FloorSpec, det: Determiner) -> Parse[NounPhrase]:
    """A floor named as a place, ``[first, end)`` (*the top floor*); refused when counted as things (*(both
    top floor btw)*) or named right after another floor (:func:`floor_just_said`)."""
    if det.count is not None:
        return Refusal(rf.counted_floor(r.quote(first, end)))
    if floor_just_said(r, first):  # "the corridor on floor 1 er the middle floor": said again
        return Refusal(rf.floor_said_twice(r.quote(max(0, first - 2), end)))
    return Match(FloorPlace(r.span(first, end), floor, det.mode), end)


def floor_just_said(r: Reader, i: int) -> bool:
    """Whether a floor is named right before ``i``, with no word between (*on floor 1 the middle floor*,
    *upstairs the top floor*): a floor named at ``i`` says it again, or corrects it; never a goal of its
    own."""
    before = r.word(i - 1)
    return (before in lx.FLOOR_WORDS or before in lx.RELATIVE_FLOORS
            or (before.isdigit() and r.word(i - 2) in lx.FLOOR_WORDS))
