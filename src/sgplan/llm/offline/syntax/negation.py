"""Syntax rules for prohibitions: *always avoid X*, *never enter X*, *don't touch X*, *avoid X*, *without
X*, *neither A nor B*, *keep out of X until Y*, *X is off limits*, *stay on this floor*, *don't leave this
floor*, *never go upstairs*."""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.syntax.actions import action, particles, verb_words
from sgplan.llm.offline.syntax.floors import floor_words
from sgplan.llm.offline.syntax.links import skip_until_subject
from sgplan.llm.offline.syntax.phrases import phrase_list
from sgplan.llm.offline.syntax.qualifiers import anaphoric_one
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal
from sgplan.llm.offline.syntax.tree import (
    Action,
    FloorPlace,
    FloorSpec,
    Negation,
    OffLimits,
    PlainAction,
    RelativeFloor,
    StartFloor,
    StayExtreme,
    StayOnFloor,
    UntilDone,
    VerbWords,
)


def negation(r: Reader, i: int) -> Parse[Negation | PlainAction]:
    """A prohibition at ``i`` (after verbs that say nothing before *neither*: *go to neither A nor B*); a
    negated goal (*don't forget the sink*) is that goal."""
    j = r.skip(i, lx.POSITIVE_VERBS)
    start = j if j > i and r.word(j) == "neither" else i
    marker = r.phrase(start, lx.NEG_STARTS)
    if marker is None:
        return None
    if marker == ("not",) and r.word(start - 1) == "," and r.np_starts(
            start + 1 + (r.word(start + 1) in lx.PLACE_PREPOSITIONS)):
        return Refusal(rf.not_after_comma(r.quote(start, len(r))))  # "Go to the kitchen, not the office"
    if marker == ("not",) and r.word(start - 1) != "," and any(
            anaphoric_one(r, k) for k in range(start + 1, min(len(r), start + 6))):
        # "Check the sink. Not the kitchen one.", "the teddy bear in the living room not the bedroom one"
        return Refusal(rf.not_the_one(r.quote(start, len(r))))
    forgot = negated_goal(r, start + len(marker), marker)
    return forgot if forgot is not None else negation_after(r, start + len(marker), marker)


def negated_goal(r: Reader, j: int, marker: tuple[str, ...]) -> Parse[PlainAction]:
    """*don't forget (to water) the plant*, *never miss the kitchen*, *don't fail to visit X*: the goal the
    words negate (not a place to avoid)."""
    k = r.skip(j, lx.NEGATION_EVER)
    if r.word(k) not in lx.FORGET_VERBS or marker[-1] not in lx.NEGATING:
        return None
    k = r.skip(k + 1, lx.FORGOTTEN_LINKS)
    goal = action(r, k)
    if not isinstance(goal, Match):
        return goal
    return Match(PlainAction(goal.node, False, False, False, None, r.rest(goal.end), ""), goal.end)


def negation_after(r: Reader, j: int, marker: tuple[str, ...]) -> Parse[Negation]:
    """What follows the words ``marker`` of a prohibition (at ``j``): what is forbidden, and for how long."""
    j += 1 if r.at(j, ",", "ever") else 0  # "never, ever"
    j += 1 if r.word(j) in lx.NEGATION_EVER else 0  # "never ever", "don't ever"
    # "no need to X": X free, not forbidden; "you need not (needn't) go"
    needed = ((r.word(j) in lx.NEGATED_NEED_WORDS and r.word(j + 1) in ("to", "for"))
              or r.word(j) in lx.NOT_NEEDED_VERBS  # "no need for X", "don't bother going to X"
              or r.word(j) in ("need", "needs"))  # "you won't need the kitchen": not needed, not forbidden
    if needed or (marker == ("not",) and r.word(j - 2) in lx.NEGATED_NEED_WORDS):
        return Refusal(rf.not_needed(r.quote(j - len(marker) - (0 if needed else 1), min(j + 4, len(r)))))
    stay = stay_on_floor(r, j, negated=True)  # "don't leave this floor"
    if stay is not None:
        if not isinstance(stay, Match):
            return stay
        return Match(Negation(marker, stay.node, None, None, None, False, None), stay.end)
    verbs = concord_verb_words(r, j, marker)
    if not isinstance(verbs, Match):
        return verbs
    if set(verbs.node.words) & lx.REVISIT_VERBS:  # "never go back to X": only after a first visit
        return Refusal(rf.never_go_back())
    if verbs.node.again:  # "never go again to X", "don't check again the bowl": as "X again", from then on
        again_at = next(k for k in range(j, verbs.end) if r.word(k) == "again")
        return Refusal(rf.partial_prohibition(r.rest(again_at)))
    unknown = next((k for k in range(j, verbs.end) if r.word(k) in verbs.node.words
                    and r.word(k) not in lx.AVOID_VERBS and r.word(k) not in lx.NEGATION_NEUTRAL), None)
    if unknown is not None:  # "don't xyzzy the sink": read as "never at the sink", it could reverse the ask
        said = r.quote(j - len(marker) + (1 if marker[0] in lx.NEGATION_JOINERS else 0), unknown + 1)
        return Refusal(rf.unknown_negated_verb(said, r.word(unknown)))
    k, phrases, floor = verbs.end, None, None
    spec, words = verbs.node.floor, verbs.node.words
    if spec is None and words[-2:-1] and words[-2] in lx.UP_DOWN and words[-1] == "at" and r.word(k) == "all":
        spec, k = RelativeFloor(lx.UP_DOWN[words[-2]]), k - 1  # "don't go down at all": "at all" after it
    if spec is not None and not r.np_starts(k):  # "never go upstairs": any room there
        floor = FloorPlace(r.span(k - 1, k), spec, "all")
    else:
        found = phrase_list(r, k, "avoid")
        if not isinstance(found, Match):
            return found
        phrases, k = found.node, found.end
    k = particles(r, k)
    k += 1 if marker == ("no",) and phrases is not None and r.word(k) in lx.VISIT_NOUNS else 0  # no X visits
    k += 1 if r.word(k) in lx.NEGATING + lx.NEGATION_EVER and marker[-1] in lx.NEGATING else 0  # "... never"
    whole = whole_mission(r, k)
    k += len(whole) if whole else 0
    comma = 1 if r.at(k, ",", "either") else 0  # "don't go in there either", "..., either": too
    k += 1 + comma if r.word(k + comma) == "either" and r.word(k + comma + 1) in ("", ".", "!") else 0
    if r.word(k) in lx.PARTIAL_PROHIBITION or any(r.at(k, *p) for p in lx.PARTIAL_FROM):
        return Refusal(rf.partial_prohibition(r.rest(k)))
    until = until_target(r, k)
    if isinstance(until, Refusal):
        return until
    node = Negation(marker, None, verbs.node, phrases, floor, whole is not None,
                    None if until is None else until.node)
    return Match(node, k if until is None else until.end)


def whole_mission(r: Reader, k: int) -> tuple[str, ...] | None:
    """*the whole time*, *at all times* ... after what to avoid or where to stay, and *always* there as
    learners place it (*stay in this floor always*, *keep out of X always*): the words, or ``None``."""
    return r.phrase(k, lx.WHOLE_MISSION) or (("always",) if r.word(k) == "always" else None)


def concord_verb_words(r: Reader, j: int, marker: tuple[str, ...]) -> Parse[VerbWords]:
    """The verb of a prohibition at ``j``, and a second *never* after it, as writers of languages with
    negative concord say it (*don't enter never in the kitchen*: *ne ... jamais*, *no ... nunca*): one
    negation, never a double one that would ask for the place."""
    verbs = verb_words(r, j, False)
    if not isinstance(verbs, Match) or marker[-1] not in lx.NEGATING or r.word(verbs.end) != "never":
        return verbs
    more = verb_words(r, verbs.end + 1, False)
    if not isinstance(more, Match):
        return more
    floor = more.node if more.node.floor is not None else verbs.node
    return Match(replace(verbs.node, words=verbs.node.words + more.node.words, floor=floor.floor,
                         floor_span=floor.floor_span), more.end)


def until_target(r: Reader, k: int) -> Parse[Action | UntilDone]:
    """*... until / before Y*, *... until you have done that*, *... until both of them are done*."""
    if r.word(k) not in lx.UNTIL_WORDS:
        return None
    if r.word(k + 1) in lx.EVENT_WORDS or (r.at(k + 1, "the") and r.word(k + 2) in lx.EVENT_WORDS):
        return Refusal(rf.until_a_time(r.quote(k, k + (2 if r.word(k + 1) in lx.EVENT_WORDS else 3))))
    if r.word(k + 1) in ("that", "this", "then") and r.word(k + 2) in ("", ","):
        return Match(UntilDone(), k + 2)  # "you are not allowed into X before that": the step named last
    k += 1 if r.word(k) in ("until", "till") and r.word(k + 1) == "after" else 0  # "until after you ..."
    said = skip_until_subject(r, k + 1)
    if said > k + 1 and r.word(said) in ("", ","):
        return Match(UntilDone(), said)  # "don't set foot in the kitchen until you have"
    k = said
    done = r.word(k) in lx.DONE
    if r.word(k) in lx.DONE and r.word(k + 1) in lx.DONE_WITH and r.np_starts(k + 2):
        k += 2  # "until you're done in the kitchen": until the kitchen
    elif r.word(k) in lx.DONE and ((r.word(k + 1) in lx.DONE_WHAT and not r.np_starts(k + 2))
                                 or not r.np_starts(k + 1)):
        k += 1  # "... before you've done that"
        return Match(UntilDone(), k + (1 if r.word(k) in lx.DONE_WHAT else 0))
    target = action(r, k)
    if not isinstance(target, Match):
        return target
    k = target.end
    passive = passive_end(r, k)
    if passive > k:
        k = passive
    elif r.word(k) in lx.DONE:
        k, done = k + 1, True  # "until DR done"
    elif r.word(k) in lx.UNTIL_DONE_LINKS and r.word(k + 1) in lx.UNTIL_DONE_WORDS:
        done = done or r.word(k + 1) in lx.DONE
        k += 2  # "until both bathrooms are done"
        k += 1 if r.word(k) in lx.UNTIL_DONE_VERBS else 0
    return Match(replace(target.node, done=True) if done else target.node, k)


def participle(w: str) -> bool:
    """Whether ``w`` is the past participle of a verb of the grammar (*checked*, *picked*, *grabbed*,
    *tidied*, *used*, and the irregular *made*, *set* ...), not any word in *-ed* (*red*)."""
    if w in lx.IRREGULAR_PARTICIPLES:
        return True
    if not w.endswith("ed"):
        return False
    stems = {w[:-2], w[:-1], w[:-3], w[:-3] + "y"}  # checked, used, grabbed, tidied
    return bool(stems & lx.POSITIVE_VERBS)


def passive_end(r: Reader, k: int) -> int:
    """After the target of *until*: the end of a passive that closes the clause (*until the oven is checked*,
    *until the cup has been picked up*, *until cup grabbed*), else ``k``."""
    j = k + (1 if r.word(k) in lx.UNTIL_DONE_LINKS else 0)
    j += 1 if r.word(j) == "been" else 0
    if not participle(r.word(j)):
        return k
    j += 1 if r.word(j + 1) in lx.PARTICLES else 0
    return j + 1 if r.word(j + 1) in ("", ",", "then", "and") else k


def stay_on_floor(r: Reader, i: int, negated: bool) -> Parse[StayOnFloor]:
    """*stay on this floor* / *stay on the ground floor* / *stay downstairs* / *keep to floor 1* (or, after a
    negation, *leave this floor*, *go to any other floor*, *change floors*)."""
    said = staying(r, i, negated)
    if said is None:
        return Refusal(rf.cannot_understand(lx.REFUSED_WORDS["leave"])) if negated and r.word(i) in lx.LEAVE \
            else None
    floor, end, where = said
    if i > 0 and r.word(i - 1) in lx.STAY_AFTER:
        return Refusal(rf.stay_for_the_rest(r.word(i - 1), r.word(i)))
    other = r.phrase(where, lx.OTHER_FLOOR) is not None
    span = r.span(where, end)
    whole = whole_mission(r, end)
    end += len(whole) if whole else 0
    and_off = None
    if r.at(end, "and", "off") and r.np_starts(end + 2):  # "stay on the top floor and off the stairs"
        off = negation_after(r, end + 2, ("off",))
        if not isinstance(off, Match):
            return off
        and_off, end = off.node, off.end
    return Match(StayOnFloor(floor, span, other, and_off), end)


def staying(r: Reader, i: int, negated: bool) -> tuple[FloorSpec, int, int] | None:
    """The floors of *stay on <floor>* / *stay downstairs* (or *leave <floor>* / *go to any other floor*
    after a negation) at ``i``: the floor, where the words end, and where the floor words begin."""
    if negated:  # "don't go to any other floor", "don't change floors"
        n = i
        while r.word(n) in lx.POSITIVE_VERBS and r.phrase(n, lx.OTHER_FLOOR) is None:
            n += 1
        other = r.phrase(n, lx.OTHER_FLOOR)
        if other is not None:
            changed = other[0] in ("change", "switch")  # "change floors": the floors are the ones kept
            return StartFloor(" ".join(other), to_stay=True), n + len(other), n + (1 if changed else 0)
    if r.word(i) not in (lx.LEAVE if negated else lx.STAY):
        return None
    k = i + 1
    if r.word(k) in lx.RELATIVE_FLOORS and not negated:
        return StayExtreme(r.word(k)), k + 1, k
    k += 1 if r.word(k) in lx.STAY_PREPOSITIONS and not negated else 0
    where = k
    k += 1 if r.word(k) == "the" else 0
    if r.word(k) == "same" and r.word(k + 1) in lx.FLOOR_WORDS:  # "stay on the same floor"
        return StartFloor(f"the same {r.word(k + 1)}", to_stay=True), k + 2, where
    said = floor_words(r, k)
    if said is None or r.head(said.end) is not None:
        return None  # not a floor, or "stay on the ground floor bathroom"
    return said.node, said.end, where


def off_limits(r: Reader, i: int) -> Parse[OffLimits | Negation]:
    """*The kitchen is off limits* / *the office and the garage are out of bounds* / *X should be avoided*;
    a sentence that states something else of a place (*the bowl is in the kitchen*) is refused."""
    if not r.np_starts(i) or r.word(i - 1) in lx.PLACE_PREPOSITIONS or r.word(i - 1) in lx.POSITIVE_VERBS:
        return None  # "go to the kitchen, the office is off limits": the kitchen is the place gone to
    phrases = phrase_list(r, i, "avoid")
    if not isinstance(phrases, Match):
        return None
    said = r.phrase(phrases.end, lx.OFF_LIMITS)
    if said is None:
        states = r.word(phrases.end) in lx.COPULAS
        return Refusal(rf.states_something(r.quote(i, phrases.end + 1))) if states else None
    if phrases.node.comma_list and len(phrases.node.items) > 1 and said[0] in ("is", "'s"):
        # "the kitchen, the office is off limits": both, or a goal said before the one off limits?
        return Refusal(rf.off_limits_list_of_one(r.quote(i, phrases.end + len(said))))
    end = phrases.end + len(said)
    until = until_target(r, end)
    if isinstance(until, Refusal):
        return until
    if until is not None:  # "the kitchen is off limits until you've checked the couch": never X until Y
        return Match(Negation(("never",), None, VerbWords((), None, None), phrases.node, None, False,
                              until.node), until.end)
    whole = whole_mission(r, end)
    return Match(OffLimits(phrases.node), end + (len(whole) if whole else 0))
