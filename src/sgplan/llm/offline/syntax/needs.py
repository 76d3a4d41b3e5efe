"""A need of a room or object said as the task itself: *The bathroom with the vase needs a check afterwards
too.*, *Both bathroom sinks need a clean, then do the kitchen sink last.*, *The bathroom with the two toilets
needs checking, then the bedroom ...*

People state what a place needs instead of ordering it. When no order after the need names that place
again (then the need is only the reason, set aside: :func:`.context.met_need`), the need is the task: the
sentence is read as *check <place> ...*, its words after the need kept (*afterwards too*, *, then ...*).
Only a sentence that opens with the place (a phrase naming a room or object of the scene, or several joined
by commas and *and*, *all* / *both* after them: *The oven and the fridge both need a look.*), then *need* /
*needs* and a chore (its particle with it: *looking at*, *sorting out*): a word in *-ing* (*checking*,
*watering*), *water* / *attention*, *a* / *an* / *some*
/ *new* and at most two words naming nothing of the scene (*a clean*, *a quick look*, *new soap*), or *to
be* and a word (*to be checked*); and not when a later sentence points back or names that kind again (*The
plants need watering. Water the one in the bedroom.*, *... first. Water the plant in the office.*: which of
them?). A need of a person or of a pronoun (*it needs watering*), or one naming
another thing (*the vase needs the bowl back*), is left to the parser, which refuses it.
"""

from __future__ import annotations

from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.noun_slot import names_scene, place_phrase
from sgplan.llm.offline.syntax.reader import Reader
from sgplan.llm.offline.text import Tok

_NEED = frozenset({"need", "needs"})
_CHORE_NOUNS = frozenset({"water", "attention"})
_CHORE_OPENERS = frozenset({"a", "an", "some", "new"})
_CHORE_PARTICLES = frozenset({"at", "to", "out", "over", "up"})
_ALL = ("all", "both")
"""Between the places and their need (*the oven and the fridge both need a look*)."""
_POINTERS = frozenset({"it", "them", "they", "one", "ones", "those", "these", "that", "this", "there"})


def need_as_order(r: Reader, later: list[Reader]) -> Reader:
    """``r`` read as *check <place> ...* when it states a need of that place as its task (see the module
    docstring), else ``r``; not when a sentence after it (``later``) points back with a pronoun or *one*
    (*The plants need watering. Water the one in the bedroom.*: which of them the need asks for)."""
    if r.aside or any(w in _POINTERS and not (w == "that" and o.word(k - 1) in ("after", "before"))
                      for o in later if not o.aside for k, w in enumerate(o.words)):
        return r  # (not "After that, ...": the order after the need)
    start = r.skip(0, lx.INTERJECTIONS)
    places_end = places_said(r, start)
    if places_end is None or r.word(r.skip(places_end, _ALL)) not in _NEED:
        return r
    end = chore_end(r, r.skip(places_end, _ALL) + 1)
    kinds = {c for j in range(start, places_end) if (h := r.head(j)) is not None for c in h.categories}
    if end is None or any(kinds & h.categories for o in later if not o.aside
                          for j in range(len(o)) if (h := o.head(j)) is not None):
        return r  # "The plants need watering first. Water the plant in the office.": which plants?
    said = r.toks[start]
    check = Tok("check", said.start, said.start)
    return replace(r, toks=r.toks[:start] + (check,) + r.toks[start:places_end] + r.toks[end:])


def places_said(r: Reader, start: int) -> int | None:
    """The end of the places said from ``start``: one noun phrase naming the scene (*the bathroom with the
    vase*) or several joined by commas and *and* (*the toilet downstairs, the kitchen sink and the oven*);
    ``None`` when there is none."""
    place = place_phrase(r, start, "goal")
    if place is None or not names_scene(r, start, place.end):
        return None
    end = place.end
    while r.word(end) in (",", "and"):
        k = r.skip(end, (",", "and"))
        more = place_phrase(r, k, "goal")
        if more is None or not names_scene(r, k, more.end):
            break
        end = more.end
    return end


def chore_end(r: Reader, k: int) -> int | None:
    """The end of the chore a need names at ``k`` (see the module docstring), or ``None``."""
    w = r.word(k)
    if w.endswith("ing") and len(w) > 4 and w not in lx.STRUCTURAL and r.head(k) is None:
        return k + 1 + (r.word(k + 1) in _CHORE_PARTICLES)  # "needs looking at", "need sorting out"
    if w in _CHORE_NOUNS:
        return k + 1
    if r.at(k, "to", "be") and r.word(k + 2).isalpha():
        return k + 3
    if w in _CHORE_OPENERS:
        words = [j for j in range(k + 1, min(k + 3, len(r)))
                 if r.word(j).replace("-", "").isalpha() and r.word(j) not in lx.STRUCTURAL]
        end = k + 1
        for j in words:
            if j != end or r.head(j) is not None:
                break
            end = j + 1
        return end if end > k + 1 and r.head(k + 1) is None else None
    return None
