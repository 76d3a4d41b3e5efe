"""Everyday names of rooms that no scene category spells: *the loo*, *the kids' room*, *the nursery*.

They are read before parsing, against the scene, and only when the scene decides them:

- *loo* / *lavatory* / *WC* name the place one goes to: the scene's bathrooms, or its toilets when it has
  no bathroom category.
- *kids' room* / *kid's room* / *children's room* / *nursery* / *playroom* name the room with the toys:
  the one room that holds a teddy bear. With several such rooms, or none (then every bedroom is a
  candidate), the phrase is refused, naming the candidate rooms.

The replacement tokens span the user's words, so messages and references still quote them.
"""

from __future__ import annotations

from sgplan.errors import MissionError
from sgplan.llm.offline.names import Entity, SceneVocabulary
from sgplan.llm.offline.text import Tok

_LOO: dict[tuple[str, ...], bool] = {("loo",): False, ("loos",): True, ("lavatory",): False,
                                     ("lavatories",): True, ("wc",): False}
"""Words for the bathroom; the value says whether the word is plural."""
_LOO_TARGETS = (("room", "bathroom"), ("object", "toilet"))
"""What *loo* means, in order of preference: the first category the scene has."""
_KIDS_ROOM = (("kids", "room"), ("kid", "'s", "room"), ("kids", "'s", "room"), ("children", "'s", "room"),
              ("childrens", "room"), ("nursery",), ("playroom",), ("play", "room"))
_TOYS = frozenset({"teddy bear"})
"""Object classes that mark a child's room."""


def everyday_names(tokens: list[Tok], vocabulary: SceneVocabulary) -> list[Tok]:
    """``tokens`` with the everyday room names of the module docstring replaced by what they name here.

    Raises
    ------
    MissionError
        a kids' room the scene does not single out (the message names the candidate rooms).
    """
    loo = _loo(vocabulary)
    out: list[Tok] = []
    i = 0
    while i < len(tokens):
        words = tuple(t.text for t in tokens[i : i + 3])
        kids = next((k for k in _KIDS_ROOM if words[: len(k)] == k), None)
        if kids is not None:
            span = tokens[i : i + len(kids)]
            out.append(Tok(_kids_room(vocabulary, _said(span)), span[0].start, span[-1].end))
            i += len(kids)
        elif words[:1] in _LOO and loo is not None:
            said = loo + ("s" if _LOO[words[:1]] else "")  # "the loos": the bathrooms
            out += [Tok(w, tokens[i].start, tokens[i].end) for w in said.split()]
            i += 1
        else:
            out.append(tokens[i])
            i += 1
    return out


def _said(span: list[Tok]) -> str:
    return " ".join(t.text for t in span).replace(" 's", "'s")


def _loo(vocabulary: SceneVocabulary) -> str | None:
    for kind, category in _LOO_TARGETS:
        if category in vocabulary.category_names(kind):  # type: ignore[arg-type]
            return category
    return None


def _kids_room(vocabulary: SceneVocabulary, said: str) -> str:
    """The key of the one room holding a toy, else a refusal naming the candidates."""
    keys = list(dict.fromkeys(e.room_key for e in vocabulary.entities if e.kind == "object"
                              and e.category in _TOYS))
    if len(keys) == 1:
        return keys[0]
    if keys:
        why = "several rooms hold a teddy bear"
        candidates = [vocabulary.by_key[k] for k in keys]
    else:
        why = "no room of this scene holds a teddy bear"
        candidates = [e for e in vocabulary.entities if e.kind == "room" and e.category == "bedroom"]
    named = ", ".join(_describe(e) for e in candidates) or "none"
    raise MissionError(f"'{said}' is not a room category of this scene and {why}; candidates: {named}; "
                       f"name the room (e.g. by its ID or its contents: 'the bedroom with the ...')")


def _describe(room: Entity) -> str:
    return f"{room.key} ({room.category}, floor {room.floor})"
