"""Syntax rules for an action: verb words, the phrases acted on, and what follows them in the action.

*visit the kitchen*, *go upstairs to the bathroom*, *take a look at the clock*, *put the bowl in the
sink*, *go to the top floor and check a bathroom*, *the kitchen and the office, the office first*, *the
kitchen twice, with a visit to the office in between*, *go to the kitchen to turn it off*. The verb does
not change the goal (a room means being in it, an object being within reach of it), so any word is
accepted as a verb except the refused ones and the words of the grammar.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.syntax.floors import floor_count, floor_offset
from sgplan.llm.offline.syntax.links import skip_subject
from sgplan.llm.offline.syntax.noun_slot import superlative
from sgplan.llm.offline.syntax.phrases import phrase_list
from sgplan.llm.offline.syntax.qualifiers import remark_ahead
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal, unreadable
from sgplan.llm.offline.syntax.tree import (
    Action,
    Described,
    FloorOffset,
    FloorPlace,
    FloorSpec,
    PhraseList,
    RelativeFloor,
    Repeat,
    Span,
    VerbWords,
)
from sgplan.llm.offline.text import Tok


def action(r: Reader, i: int, in_condition: bool = False) -> Parse[Action]:
    """Verb words and the phrases acted on at ``i`` (``in_condition``: the action of a condition, where
    *end up in X* just means being in X), with its tail (:func:`action_tail`)."""
    start = i
    verbs = verb_words(r, i, in_condition)
    if not isinstance(verbs, Match):
        return verbs
    i = verbs.end
    if (r.word(i) in lx.CHECK_THAT and set(verbs.node.words) & lx.CHECK_VERBS and r.word(i + 1) in lx.ARTICLES
            and set(lx.STATE_VERBS) & set(r.words[i + 2:])):
        i += 1  # "check that the couch is tidy": the couch (its state is seen there); not "check that vase"
    verbs = Match(turned(r, verbs.node, i), i)
    if not r.np_starts(i) and verbs.node.floor is not None and r.word(i) in ("and", ",", "then"):
        moved = moved_action(r, r.skip(i, ("and", ",", "then")), in_condition)  # "go upstairs and check X"
        if not isinstance(moved, Match):
            return moved
        node = Action(r.span(start, moved.end), verbs.node, None, moved.node, in_condition=in_condition)
        return Match(node, moved.end)
    back = went_back(r, verbs.node, i, in_condition)
    if back is not None:
        return back
    if (not r.np_starts(i) and "back" in verbs.node.words and r.word(i) in lx.BACK_TO_START_ENDS
            and set(verbs.node.words) <= lx.FLOOR_MOVE_VERBS | lx.UP_DOWN.keys() | {"back", "here"}):
        return Refusal(rf.back_to_start(r.quote(start, i + (1 if r.word(i) in ("here", "again") else 0))))
    if not r.np_starts(i):
        return Refusal(rf.expected_phrase(" ".join(verbs.node.words), r.rest(i)))
    phrases = phrase_list(r, i, "goal")
    if not isinstance(phrases, Match):
        return phrases
    # "end up in X", "finish at X": X after the rest; not "finish the laptop" (done with it: a goal, no order)
    ends = bool(set(verbs.node.words) & lx.END_VERBS) and not in_condition and not (
        verbs.node.words[-1] in lx.END_VERBS and r.word(verbs.end - 1) in lx.END_VERBS)
    ends = ends or bool(set(verbs.node.words) & lx.CARRY_VERBS and set(verbs.node.words) & lx.CARRIED_ALL)
    carried_on = (r.word(i - 2) in lx.CARRY_ON_VERBS  # "(take X and) bring to Y", not "take a seat on"
                  and r.word(i - 1) in lx.CARRY_DESTINATION_WORDS and len(verbs.node.words) >= 2)
    put_down = r.word(i - 2) in lx.PUT_DOWN_VERBS and r.word(i - 1) in lx.CARRY_DESTINATION_WORDS
    carried_on = carried_on or (put_down and bool(set(r.words[:i - 2]) & lx.TAKING_VERBS))  # "take X, put on"
    node = Action(r.span(start, phrases.end), verbs.node, phrases.node, in_condition=in_condition, last=ends,
                  first=verbs.node.first, repeat=Repeat(True, 1, None) if verbs.node.again else None,
                  carried_on=carried_on)
    moved = floor_move(r, phrases.end, phrases.node, in_condition)
    if moved is not None:
        return moved if isinstance(moved, Refusal) else Match(replace(node, moved=moved.node), moved.end)
    checked = r.word(start) in lx.CHECK_VERBS
    end = given(r, phrases.end) if set(verbs.node.words) & lx.GIVE_VERBS else phrases.end
    if end is None:
        return Refusal(rf.give_without_look(r.quote(start, phrases.end)))
    if end > phrases.end and r.word(phrases.end) in lx.GIVEN_AGAIN:  # "give X another splash": X again
        node = replace(node, repeat=Repeat(True, 1, None))
    return action_tail(r, state_said(r, end) if checked else end, node)


def went_back(r: Reader, verbs: VerbWords, i: int, in_condition: bool) -> Parse[Action]:
    """*go / come back and check the oven (again)*: the action after *and*, with *back* among its verbs (a
    new visit of what was a goal before, as *go back to X*); ``None`` when the verb words do not end with
    *back* before *and* and a verb (not *go back and forth*)."""
    if not verbs.words or verbs.words[-1] not in lx.REVISIT_VERBS or r.word(i) not in ("and", ","):
        return None
    k = r.skip(i, ("and", ","))
    if r.word(k) not in lx.POSITIVE_VERBS:
        return None
    then = action(r, k, in_condition)
    if not isinstance(then, Match):
        return then
    words = replace(then.node.verbs, words=verbs.words + then.node.verbs.words)
    return Match(replace(then.node, verbs=words), then.end)


def given(r: Reader, i: int) -> int | None:
    """The end of what *give X* gives X at ``i`` (*a quick look*; any chore said as one word closing the
    clause, *a flush*, *a good rinse*; *another* one is a new visit of X), or ``None`` if it gives X nothing
    read (*give X some water*, *give X to Y*, *give X a bowl*: a room or object of the scene is given, not a
    chore)."""
    if r.word(i) not in ("a", "an") and r.word(i) not in lx.GIVEN_AGAIN:
        return None
    looks = r.phrase(i + 1, lx.GIVEN_LOOKS)
    if looks is not None:
        return i + 1 + len(looks)
    k = i + 1 + (1 if r.word(i + 1) in lx.GIVEN_MANNER else 0)
    chore = r.word(k).isalpha() and r.word(k) not in lx.STRUCTURAL and r.head(k) is None
    return k + 1 if chore and r.word(k + 1) in lx.GIVEN_ENDS else None


def turned(r: Reader, verbs: VerbWords, i: int) -> VerbWords:
    """*go up and X*, *come down and X*: a floor move to the floors above / below, when the verb words end
    with *up* / *down* before a connective; a note's *up bth*, *down LR* (*up* / *down* right before a
    room's noun, with no article): the room upstairs / downstairs, as *go upstairs to the bathroom*."""
    if verbs.floor is None and verbs.words and verbs.words[-1] in lx.UP_DOWN and r.word(i) in ("and", ","):
        floor = RelativeFloor(lx.UP_DOWN[verbs.words[-1]], back=verbs.words[-2:-1] == ("back",))
        return replace(verbs, floor=floor, floor_span=r.span(i - 1, i))
    room = r.head(i)
    if verbs.floor is None and verbs.words and verbs.words[-1] in lx.UP_DOWN and room is not None \
            and room.kind == "room":
        return replace(verbs, floor=RelativeFloor(lx.UP_DOWN[verbs.words[-1]]), floor_span=r.span(i - 1, i))
    return verbs


def state_said(r: Reader, i: int) -> int:
    """After *check that the couch*: the state the check is about (*is tidy*, *is switched off*), which
    the translator does not read (being there is what a check needs)."""
    if r.word(i) not in lx.STATE_VERBS:
        return i
    k = r.skip(i + 1, lx.FILLERS)
    while k < min(i + 4, len(r)) and r.word(k).isalpha() and r.word(k) not in lx.STRUCTURAL \
            and r.head(k) is None and r.word(k) not in ("and", "then"):
        k += 1
    kept_away = set(r.words[i + 1:k]) & lx.KEPT_AWAY_STATES  # "is left alone": not a visit (refused)
    return k if k > i + 1 and r.word(k) in lx.CLAUSE_ENDS and not kept_away else i


def moved_action(r: Reader, i: int, in_condition: bool) -> Parse[Action]:
    """The action after a floor move (*go upstairs and ...*): every goal of it is on that floor."""
    if i >= len(r):
        return Refusal(rf.expected_action_after_floor())
    return action(r, i, in_condition)


def floor_move(r: Reader, i: int, phrases: PhraseList, in_condition: bool) -> Parse[Action]:
    """After a floor named as the one place to go (*go (up) to the top floor*), a connective and an action:
    the floor is where that action is done, not a goal of its own (*and check a bathroom (there)*)."""
    if len(phrases.items) != 1 or not isinstance(phrases.items[0], FloorPlace):
        return None
    k = r.skip(i, (",", "and", "then"))
    if k == i or not (r.word(k) in lx.POSITIVE_VERBS or r.np_starts(k)):
        return None
    return moved_action(r, k, in_condition)


_BEFORE_FROM = frozenset({"", ",", "so", "and", "then", "now", "ok", "okay"})
"""Words after which *from* opens its clause (*so from the kitchen go ...*): no verb of going before it."""


def starts_from(r: Reader, i: int) -> bool:
    """Whether the *from* at ``i`` says where the robot starts, which is never a goal: *from here*, *from up
    here* (*from on this floor*), or opening its clause before a verb of going in that clause (*From the
    kitchen go to the office*); not *From the kitchen, grab the bowl* (where the bowl is)."""
    if r.word(i + 1) == "here" or r.at(i + 1, "on", "this", "floor"):
        return True
    end = next((j for j in range(i + 1, len(r)) if r.word(j) == ","), len(r))
    return r.word(i - 1) in _BEFORE_FROM and any(w in lx.GOING_VERBS for w in r.words[i + 1:end])


def verb_words(r: Reader, i: int, in_condition: bool) -> Parse[VerbWords]:
    """The words before the phrase: the verb, whatever it is, unless it is refused or a word of the grammar
    (*always*, *floor*, *next* out of place are refused, not verbs); and a floor said among them (*go
    upstairs to ...*, *go down two floors to ...*)."""
    seen: list[str] = []
    floor: FloorSpec | None = None
    floor_span: Span | None = None
    first = again = False
    times = 1
    while i < len(r) and (((not r.np_starts(i) or verb_idiom(r, i)) and (
            r.word(i) not in lx.VERB_STOPS or said_first(r, i))) or times_before_place(r, i)):
        w = r.word(i)
        if said_first(r, i):  # "go first to the kitchen", "go before to the kitchen, after to ..."
            first, i = True, i + 1
            continue
        if w == "again" and (r.word(i + 1) in lx.PLACE_PREPOSITIONS or r.np_starts(i + 1)):
            again, i = True, i + 1  # "(go) again to the kitchen", "check again the bowl", as learners say it
            continue
        looked = r.phrase(i, lx.LOOKED_AGAIN)
        if looked is not None and r.word(i + len(looked)) in lx.PLACE_PREPOSITIONS:
            seen.append(looked[-1])  # "have another look in the kitchen": a new visit, as "... again"
            again, i = True, i + len(looked)
            continue
        said_times = times_before_place(r, i)
        if said_times is not None:  # "go two times to the kitchen", as learners place it
            times, i = said_times
            continue
        if floor is not None and (r.phrase(i, lx.WHOLE_MISSION) or r.phrase(i, lx.TIME_FILLERS)):
            break  # "don't go downstairs at any point"
        idiom = verb_idiom(r, i)
        if idiom:  # "go all the way up to", "take a look at", "wash your hands at": part of the verb
            seen += r.words[i : i + idiom]
            i += idiom
            continue
        refused = refused_verb(r, i, in_condition)
        if refused is not None:
            return refused
        if w in lx.PERMISSION_WORDS and r.word(i - 1) in lx.COPULAS:  # "you are allowed to go into X"
            return Refusal(rf.permission_only(r.quote(i, min(len(r), i + 5))))
        if w in lx.MODALS and r.word(i + 1) not in lx.NEGATING:
            seen.append(w)  # "may you go into ...", "I do want you to visit ...": no negation
            i += 1
            continue
        if r.phrase(i, lx.NEG_STARTS) is not None:
            break
        counted = floor_said(r, i)
        if counted is not None:  # "go two floors down to the garage": the garage on that floor
            floor, floor_span, i = counted.node, r.span(i, counted.end), counted.end
            continue
        if w in lx.RELATIVE_FLOORS:  # "go upstairs to the bathroom": the bathroom on that floor
            floor, floor_span = RelativeFloor(w), r.span(i, i + 1)
        elif w == "away" and r.word(i - 1) in lx.AWAY_VERBS:
            pass  # "put away the bowl": the verb's particle, not "stay away from"
        elif w not in lx.POSITIVE_VERBS and (w in lx.STRUCTURAL or not w.isalpha()):
            return unreadable(r, i)
        odd = odd_verb(r, i)
        if odd is not None:
            return odd
        if w not in lx.POSITIVE_VERBS and r.nouns.names_word(w) and r.np_starts(i + 1):  # "living chair"
            return Refusal(rf.cannot_understand_word(w, f"'{r.quote(i, min(len(r), i + 3))}'"))
        if w == "from" and not seen and starts_from(r, i):
            return Refusal(rf.starting_place(r.quote(i, min(len(r), i + 4))))
        if w == "out" and r.word(i + 1) == "from" and r.word(i - 1) in lx.FLOOR_MOVE_VERBS:
            return Refusal(rf.cannot_understand(lx.REFUSED_WORDS["leave"]))  # "go out from X": leaving X
        seen.append(w)
        i += 1
    return Match(VerbWords(tuple(seen), floor, floor_span, first, again, times), i)


def odd_verb(r: Reader, i: int) -> Refusal | None:
    """An unknown word in the verb slot is taken for a verb (whatever the verb, the goal is the same), unless
    it cannot be one: it looks like a room or object of the scene (*then bathrom sink*: a misspelt noun, whose
    loss would widen the goal), it has no vowel (*bthrm*, an abbreviation not known), it has one or two
    letters (*x kitchen*: operators' shorthand for *not*, known only as a kiss ending a message), or it
    follows another unknown word (*lvng rm couch*)."""
    spelling, w = r.spelling, r.word(i)
    if superlative(w):  # "grab heaviest bottle": a comparison, not a verb
        return Refusal(rf.superlative(w))
    if w in lx.CONTACT_SUBJECTS and r.word(i + 1) in lx.FIRST and r.word(i - 1) == ",":
        return Refusal(rf.first_mid_sentence(r.quote(0, i + 2)))  # "X, we start with Y": "we first Y"
    if spelling is None or (spelling.is_known(w) and w not in lx.KISSES) or w.endswith("ly"):
        return None
    if len(w) < 3 or spelling.scene_noun_like(w) is not None or not set(w) & set("aeiouy"):
        return Refusal(rf.not_a_verb(w))  # the refusal then says which name it looks like
    before = r.word(i - 1)
    if before.isalpha() and not spelling.is_known(before) and not before.endswith("ly"):
        return Refusal(rf.not_a_verb(f"{before} {w}"))
    return None


def said_first(r: Reader, i: int) -> bool:
    """*first* / *before* among the verb words, before the preposition of the place (*go first to X*)."""
    return bool(r.word(i - 1)) and (r.word(i) in lx.FIRST or r.word(i) == "before") \
        and r.word(i + 1) in lx.PLACE_PREPOSITIONS


def times_before_place(r: Reader, i: int) -> tuple[int, int] | None:
    """*twice* / *two times* (at most :data:`.lexicon.MAX_REPEATS`) after a verb, right before a place
    preposition or a noun phrase (*go two times to X*, *visit two times X*, as learners place it): how many
    times, and where the words end; ``None`` otherwise."""
    if r.word(i - 1) in ("", ",") or not r.word(i - 1).isalpha():
        return None
    n = 2 if r.word(i) == "twice" else None
    k = i + 1
    if n is None and r.word(i + 1) == "times":
        n, k = lx.NUMBER_WORDS.get(r.word(i)) or (int(r.word(i)) if r.word(i).isdigit() else None), i + 2
    if n is None or n < 2 or (r.word(k) not in lx.PLACE_PREPOSITIONS and not r.np_starts(k)):
        return None
    return n, k


def refused_verb(r: Reader, i: int, in_condition: bool) -> Refusal | None:
    """A verb the translator cannot express (*leave*, *wait*; *start in X*; *do it twice*), refused."""
    w, nxt = r.word(i), r.word(i + 1)
    if w in lx.REFUSED_WORDS:
        return Refusal(rf.cannot_understand(lx.REFUSED_WORDS[w]))
    if (w, nxt) in lx.CAUTION_PAIRS or (w in lx.CAUTION_VERBS and r.np_starts(i + 1)):
        return Refusal(rf.caution_not_goal(r.quote(i, min(len(r), i + 3))))
    if w in lx.CAUTIONS and (nxt in lx.PLACE_PREPOSITIONS or r.np_starts(i + 1)):  # "careful in X"
        return Refusal(rf.caution_not_goal(r.quote(i, min(len(r), i + 3))))
    if r.word(i - 1) == "be" and _manner(r, i):  # "be careful in X" ("be" is read before the verb slot)
        return Refusal(rf.caution_not_goal(r.quote(i - 1, min(len(r), i + 2))))
    if w == "be" and _manner(r, i + 1):
        return Refusal(rf.caution_not_goal(r.quote(i, min(len(r), i + 3))))
    if w in lx.START_VERBS and nxt in lx.START_END_PARTICLES and not in_condition:
        return Refusal(rf.path_start_or_end(w, nxt))
    if w in ("do", "does", "did", "doing") and nxt in lx.DONE_WHAT:
        return Refusal(rf.did_is_not_a_place(w, nxt))
    return None


def _manner(r: Reader, i: int) -> bool:
    """Whether the word at ``i``, after *be*, says a manner (*careful*, *quiet*) rather than a place (*be in
    the kitchen*) or a wrapper (*be sure to*)."""
    w = r.word(i)
    return w.isalpha() and w not in lx.PLACE_PREPOSITIONS and w not in lx.BE_FINE and not r.np_starts(i)


def floor_said(r: Reader, i: int) -> Match[FloorOffset] | None:
    """Floors counted from the start in a verb slot: *the floor above*, *two floors down*, *up a floor*."""
    offset = floor_offset(r, i)
    if offset is not None:
        return offset
    w = r.word(i)
    turned = floor_count(r, i + 1) if w in ("up", "down") else None
    if turned is None or r.word(i + 2) not in lx.FLOOR_PLURALS:
        return None  # "go down two floors", "go up a floor"
    said = f"{w} {r.word(i + 1)} {r.word(i + 2)}"
    return Match(FloorOffset(turned * lx.FLOOR_DIRECTIONS[w], said), i + 3)


def verb_idiom(r: Reader, i: int) -> int:
    """How many words at ``i`` belong to the verb although they look like a noun phrase: *all the way*, *a
    look* / *your way* (*take a look at*, *make your way to*), a body part before a place (*wash your hands
    at the sink*); 0 if none."""
    idiom = r.phrase(i, lx.VERB_IDIOMS) or r.phrase(i, lx.CHORE_PHRASALS)
    if idiom is not None:
        return len(idiom)
    beside = r.phrase(i, lx.CARRY_BESIDE) if r.word(i - 1) in lx.BESIDE_VERBS else None
    thing = r.head(i + len(beside) + (1 if r.word(i + len(beside)) in lx.ARTICLES else 0)) if beside else None
    if beside is not None and thing is not None and thing.kind == "object":
        return len(beside)  # "park next to the bed": the bed is where to be (a room next to X is another)
    if (r.word(i) in lx.BODY_PART_OWNERS and r.word(i + 1).isalpha() and r.head(i + 1) is None
            and r.word(i + 2) in lx.BODY_PART_LINKS and r.np_starts(i + 3)
            and not set(r.words[max(0, i - 2):i]) & lx.FETCH_VERBS):  # not "put my keys on the table"
        return 2
    return 0


def action_tail(r: Reader, i: int, node: Action) -> Parse[Action]:
    """What follows the phrases in the same action: *first*, a choice remark, an order remark, *last*,
    *again* / *twice*, a destination, a purpose, *there*, a time filler."""
    if r.word(i) in lx.FIRST:
        node, i = replace(node, first=True), i + 1
    remark = remark_ahead(r, i)
    if remark is not None:
        node, i = replace(node, remark=remark), i + len(remark)
    comma = 1 if r.word(i) == "," else 0
    ordered = r.phrase(i + comma, lx.ORDER_MODIFIERS)
    if ordered is not None:
        node, i = replace(node, ordered=True), i + comma + len(ordered)
    elif node.phrases is not None and node.phrases.comma_list and (r.phrase(i + comma, lx.THEN_NEXT)
                                                                   or action_then_ahead(r, i)):
        node = replace(node, ordered=True)  # "the fridge, the oven, (go up to X,) then ...": as written
    if r.word(i) in lx.LAST and r.word(i + 1) in ("", ","):
        node, i = replace(node, last=True), i + 1  # "the kitchen and the office last"
    repeat = repeats(r, i)
    if not isinstance(repeat, Match):
        return repeat
    if repeat.node is not None and counted_plural(r, i, node):  # "lobby vases x4": the four of them
        counted = counted_items(node, repeat.node.times)
        if counted is None:  # "the plants and the TVs x2": which is counted, or is it twice?
            return Refusal(rf.count_or_times(r.text[node.span.start:r.toks[repeat.end - 1].end]))
        node, i, repeat = counted, repeat.end, Match(None, repeat.end)
    if node.verbs.times > lx.MAX_REPEATS:
        return Refusal(rf.too_many_repeats(str(node.verbs.times)))
    if node.verbs.times > 1:  # "go two times to the kitchen": one place, that many visits
        several = node.phrases is not None and len(node.phrases.items) > 1
        if repeat.node is not None or several:
            return Refusal(rf.times_of_what(r.text[node.span.start:r.toks[i - 1].end]))
        between = in_between(r, i) if node.verbs.times == 2 else None  # "visit two times X, in between Y"
        node = replace(node, repeat=Repeat(False, 2, between.node) if between else
                       Repeat(False, node.verbs.times, None))
        i = between.end if between else i
    if repeat.node is not None:
        node, i = replace(node, repeat=repeat.node), repeat.end
    return destination_and_purpose(r, i, node)


def counted_plural(r: Reader, i: int, node: Action) -> bool:
    """Whether a count typed as a notation (*x2*, *2x*) at ``i`` follows a plural noun, where it may say how
    many there are as well as how many times."""
    typed = r.quote(i, i + 1).lower()
    plural = node.phrases is not None and any(
        isinstance(p, Described) and any(isinstance(h, Head) and h.plural for h in (p.head, p.compound))
        for p in node.phrases.items)  # "the plants x2", "LR plants x2"
    return plural and typed.strip("0123456789") == "x"


def counted_items(node: Action, count: int) -> Action | None:
    """``node``, its one phrase a bare plural counted by a notation after it (*lobby vases x4*, *kitchen
    bottles x2*) read as *all <count> <plural>* (the number checked against the scene, as *all four vases*
    is), or ``None`` when it is not that one phrase: notes count the things of a plural so, and say a
    visit again with the place alone (*LR x2*)."""
    items = node.phrases.items if node.phrases is not None else ()
    if node.phrases is None or len(items) != 1 or not isinstance(items[0], Described):
        return None
    said = items[0]
    if said.determiner.count is not None or said.determiner.mode not in (None, "all", "the"):
        return None
    counted = replace(said, determiner=replace(said.determiner, mode="all", count=count))
    return replace(node, phrases=replace(node.phrases, items=(counted,)))


def action_then_ahead(r: Reader, i: int) -> bool:
    """Whether a comma at ``i`` joins an action (*..., pop up to the bedroom, then ...*) to a sequence that a
    *then* later in the sentence makes: comma-joined steps before a *then* are done as written."""
    later = range(i + 1, len(r))
    return (r.word(i) == "," and action_starts(r, i + 1) and any(said_then(r, j) for j in later)
            and not any(r.word(j) in lx.NOT_A_SEQUENCE and not choice_whichever(r, j) for j in later))


def choice_whichever(r: Reader, j: int) -> bool:
    """Whether *whichever* at ``j`` closes a choice (*... one of the chairs, whichever.*, *..., whichever one
    is fine*), not an order (*whichever first*, *in whichever order*)."""
    return r.word(j) == "whichever" and r.word(j - 1) == "," and r.word(j + 1) in ("", ",", ".", "one", "is",
                                                                                   "'s")


def action_after_then(r: Reader, i: int) -> bool:
    """Whether a comma (and an *and* after it) at ``i`` joins an action to a sequence that a *then* earlier in
    the sentence made (*A, then B, C, and bring everything to D*): such steps go on as written."""
    k = i + 2 if r.at(i, ",", "and") else i + 1
    if r.word(k) in lx.PLACE_PREPOSITIONS or r.word(k) == "between":
        return False  # "A, then B, and in between, C": not a step of the sequence (.body.in_between)
    return (r.word(i) == "," and action_starts(r, k) and any(said_then(r, j) for j in range(i))
            and not any(r.word(j) in lx.NOT_A_SEQUENCE for j in range(len(r))))


def action_starts(r: Reader, i: int) -> bool:
    """Whether the word at ``i`` is an action's verb (not a noun phrase, a word of the grammar, a prohibition
    or a waypoint)."""
    w = r.word(i)
    return not (not w.isalpha() or r.np_starts(i) or w in lx.STRUCTURAL or (w in lx.FILLERS and w not in
                lx.POSITIVE_VERBS) or w in lx.REFUSED_WORDS or r.phrase(i, lx.NEG_STARTS)
                or r.phrase(i, lx.WAYPOINT))


def said_then(r: Reader, j: int) -> bool:
    """Whether *then* / *next* at ``j`` follows a comma or *and* (a step of a sequence)."""
    return r.phrase(j, lx.THEN_NEXT) is not None and r.word(j - 1) in (",", "and")


def repeats(r: Reader, i: int) -> Parse[Repeat | None]:
    """*again*, *twice* / *two times* / *3 times* (at most :data:`.lexicon.MAX_REPEATS`), and after *twice*
    *(, ) with a trip to Y in between* / *, visiting Y in between*."""
    again = r.word(i) == "again"
    i += 1 if again else 0
    times = 1
    n = lx.NUMBER_WORDS.get(r.word(i)) or (int(r.word(i)) if r.word(i).isdigit() else None)
    if r.word(i) == "twice":
        times, i = 2, i + 1
    elif n is not None and r.word(i + 1) == "times":
        if not 1 <= n <= lx.MAX_REPEATS:
            return Refusal(rf.too_many_repeats(r.word(i)))
        times, i = n, i + 2
    between = in_between(r, i) if times == 2 else None
    if between is not None:
        return Match(Repeat(again, times, between.node), between.end)
    return Match(Repeat(again, times, None) if again or times > 1 else None, i)


def in_between(r: Reader, i: int) -> Match[Action] | None:
    """After *twice*: ``(,) with (a trip / visit / stop) (to) Y in between``, ``(,) (and) (go to) Y in
    between`` (*visiting Y*, *the office*, *pop into the office*) or ``(,) (and) in between (,) Y``: the
    action of Y; ``None`` when the words are not there."""
    k = i + (1 if r.word(i) == "," else 0)
    k += 1 if r.word(k) == "and" else 0
    lead = 2 if r.at(k, "in", "between") else 1 if r.word(k) == "between" else 0
    lead += len(r.phrase(k + lead, lx.BETWEEN_TAIL) or ()) if lead else 0  # "and between them / the visits"
    if lead:  # "the kitchen twice, and in between go to the office"
        k += lead + (1 if r.word(k + lead) == "," else 0)
        said = action(r, k)
        return said if isinstance(said, Match) and said.node.phrases is not None else None
    if r.word(k) == "with":
        k += 1
        k += 2 if r.word(k) in ("a", "an") and r.word(k + 1) in lx.TRIP_NOUNS else \
            1 if r.word(k) in lx.TRIP_NOUNS else 0
    elif r.word(k) in lx.STRUCTURAL and not r.np_starts(k):
        return None
    visit = action(r, k)
    if not isinstance(visit, Match) or visit.node.phrases is None:
        return None
    end = visit.end
    if not (r.at(end, "in", "between") or r.word(end) == "between"):
        return None
    end += 2 if r.word(end) == "in" else 1
    tail = r.phrase(end, lx.BETWEEN_TAIL)
    return Match(visit.node, end + (len(tail) if tail else 0))


def particles(r: Reader, i: int) -> int:
    """A particle closing an action (*turn it off*, *pick it up*)."""
    particle = r.word(i) in lx.PARTICLES or (r.word(i) == "away" and bool(set(r.words[:i]) & lx.AWAY_VERBS))
    if particle and (r.word(i + 1) in ("", ",", "and", "then", "to")
                                      or r.phrase(i + 1, lx.NEG_STARTS)):
        return i + 1
    return i


def destination_and_purpose(r: Reader, i: int, node: Action) -> Parse[Action]:
    """*put X in Y* / *take X to Y* / *go from X to Y* (Y: the destination), *... to turn them off* (a
    purpose clause), then *there* and a time filler."""
    i = particles(r, i)
    carry = bool(set(node.verbs.words) & lx.CARRY_VERBS)
    into = lx.CARRY_DESTINATION_WORDS if carry else lx.DESTINATION_WORDS
    if carry and (r.word(i) in lx.PARTICLES or r.word(i) == "away") and r.word(i + 1) in into:
        i += 1  # "put the bowl down in the sink", "heat the bowl up in the microwave": the verb's particle
    beside = r.phrase(i, lx.CARRY_BESIDE) if carry else None  # "put the cup by the keyboard"
    if (r.word(i) in into or beside) and r.np_starts(i + len(beside or ("in",))):
        dest = phrase_list(r, i + len(beside or ("in",)), "goal")
        if not isinstance(dest, Match):
            return dest
        node, i = replace(node, destination=dest.node), dest.end
        remark = remark_ahead(r, i)  # "put it on the table of the dining room, which one you want"
        if remark is not None:
            node, i = replace(node, destination_remark=remark), i + len(remark)
    i = particles(r, i)
    if r.word(i) == "to" and not r.np_starts(i + 1):  # purpose clause: "... to turn them off"
        verbs = verb_words(r, i + 1, node.in_condition)
        if not isinstance(verbs, Match):
            return verbs
        looks = r.phrase(i + 2, lx.VERB_IDIOMS) is not None  # "... to take a look at the laptop": no carrying
        if set(verbs.node.words[looks:]) & lx.CARRY_VERBS:  # "go to the kitchen to put the bowl in the sink"
            return Refusal(rf.carried_in_purpose(r.rest(i)))
        i = verbs.end
        if r.np_starts(i):
            purpose = phrase_list(r, i, "goal")
            if not isinstance(purpose, Match):
                return purpose
            node, i = replace(node, purpose=purpose.node), particles(r, purpose.end)
            remark = remark_ahead(r, i)  # "go to the kitchen to grab an apple, either one, and ..."
            if remark is not None:
                node, i = replace(node, purpose_remark=remark), i + len(remark)
        elif not verbs.node.words:
            return Refusal(rf.cannot_understand(r.rest(i)))
    elif r.word(i) == "for" and node.purpose is None and not carry and r.np_starts(i + 1):
        purpose = phrase_list(r, i + 1, "goal")  # "go to the office for the laptop": the laptop there
        if isinstance(purpose, Match):
            node, i = replace(node, purpose=purpose.node), particles(r, purpose.end)
    there = r.phrase(i, lx.THERE_SAID)  # "look at the TV there / while you're (in) there": where the step is
    i += len(there) if there and (len(there) == 1 or r.word(i + len(there)) in lx.CLAUSE_ENDS) else 0
    filler = r.phrase(i, lx.TIME_FILLERS)
    if filler in lx.ANY_TIME and set(r.words[:i]) & {"then", "after"}:  # "A, then B and C at some point, ..."
        return Refusal(rf.any_time_in_sequence(r.quote(0, i + len(filler))))  # (C after A, or at any time?)
    if filler and not r.trailing_after(i):
        i += len(filler)  # not "... the office later": that says an order (.body.trailing_after)
    if r.word(i) == "instead" and r.word(i + 1) in lx.CLAUSE_ENDS and not node.in_condition:
        node, i = replace(node, instead=True), i + 1
    return Match(replace(node, span=Span(node.span.start, r.toks[i - 1].end)), i)


def after_conjunction(r: Reader, i: int, in_condition: bool = False) -> Parse[Action]:
    """The action after *after*, *before*, *once*, *until*, *if* ...: its subject skipped first."""
    return action(r, skip_subject(r, i), in_condition)


def left_things_put(readers: list[Reader]) -> list[Reader]:
    """``readers`` with *leave it / them* before where it goes (*on*, *in*, *next to*, *by* ... Y) read as
    *put it*, when a verb of fetching or carrying comes before it in its sentence or the one before (*grab the
    book, then leave it next to the TV*): the thing carried is put there. Without one (*look at the bowl and
    leave it on the table*: do not move it?), or after *but* / a negation, *leave* stays refused."""
    out: list[Reader] = []
    for n, r in enumerate(readers):
        before = (readers[n - 1].words if n else ()) + r.words
        offset = len(before) - len(r)
        for k in range(len(r)):
            if (r.word(k) in lx.LEAVE and r.word(k + 1) in ("it", "them")
                    and r.word(k - 1) not in lx.LEAVE_AS_IS
                    and (r.word(k + 2) in lx.CARRY_DESTINATION_WORDS or r.phrase(k + 2, lx.CARRY_BESIDE))
                    and set(before[:offset + k]) & lx.FETCH_VERBS):
                put = Tok("put", r.toks[k].start, r.toks[k].end)
                r = replace(r, toks=(*r.toks[:k], put, *r.toks[k + 1:]))
        out.append(r)
    return out
