"""A mission that asks for a place and forbids it: refused, never planned as an impossible formula.

*Go to the lobby, then the kitchen, then, actually skip the kitchen, ...* (a change of mind the translator
does not read as one), *grab the bowl in the kitchen; never enter the kitchen*: a goal that every path of the
formula must reach and a prohibition of the whole mission (``G !x``) on the same room or object. The planner
would only report that no path exists; the translator says which place is both, so the user can say which
holds.
"""

from __future__ import annotations

from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.logic.formula import Always, And, Atom, Eventually, Formula, Next, Not, Or, Until


def check_goal_not_forbidden(formula: Formula, vocab: SceneVocabulary) -> None:
    """Refuse ``formula`` when a proposition every satisfying path must make true is also forbidden for the
    whole mission by one of its top-level conjuncts (see the module docstring)."""
    both = sorted(required(formula) & forbidden(formula))
    if both:
        rf.refuse(rf.goal_and_forbidden([spoken(name, vocab) for name in both]))


def required(f: Formula) -> frozenset[str]:
    """The propositions every path satisfying ``f`` makes true at some point (an under-approximation: a
    choice requires only what all its options do; a negation or an implication requires nothing)."""
    if isinstance(f, Atom):
        return frozenset({f.name})
    if isinstance(f, And):
        return frozenset().union(*(required(a) for a in f.args))
    if isinstance(f, Or):
        return frozenset.intersection(*(required(a) for a in f.args))
    if isinstance(f, (Eventually, Always, Next)):
        return required(f.arg)
    if isinstance(f, Until):
        return required(f.right)
    return frozenset()


def forbidden(f: Formula) -> frozenset[str]:
    """The propositions a top-level conjunct of ``f`` forbids for the whole mission (``G !x``,
    ``G(!x & !y)``)."""
    parts = f.args if isinstance(f, And) else (f,)
    out: set[str] = set()
    for part in parts:
        if isinstance(part, Always):
            body = part.arg.args if isinstance(part.arg, And) else (part.arg,)
            out |= {b.arg.name for b in body if isinstance(b, Not) and isinstance(b.arg, Atom)}
    return frozenset(out)


def spoken(name: str, vocab: SceneVocabulary) -> str:
    """``enter(room_4)`` as *the kitchen (room_4)*."""
    entity = next((e for e in vocab.entities if e.action == name), None)
    return f"the {entity.category} ({entity.key})" if entity is not None else name
