"""Everyday names of a room that no scene category spells and the scene decides: *the kids' room*, *the
nursery*, *the playroom* name the room with the toys, the one room that holds one of
:data:`.lexicon.TOYS`. With several such rooms, or none (then every bedroom is a candidate), the phrase is
refused, naming the candidate rooms. (*the loo* is a head noun of :mod:`.nouns`: the bathrooms, or the
toilets of a scene without bathrooms.)
"""

from __future__ import annotations

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.names import Entity, SceneVocabulary


def kids_room(vocabulary: SceneVocabulary, said: str) -> Entity:
    """The one room holding a toy (``said``: the name as said, for the refusal).

    Raises
    ------
    MissionError
        no room or several rooms hold a toy; the message names the candidate rooms.
    """
    keys = list(dict.fromkeys(e.room_key for e in vocabulary.entities if e.kind == "object"
                              and e.category in lx.TOYS))
    if len(keys) == 1:
        return vocabulary.by_key[keys[0]]
    if keys:
        why = "several rooms hold a teddy bear"
        candidates = [vocabulary.by_key[k] for k in keys]
    else:
        why = "no room of this scene holds a teddy bear"
        candidates = [e for e in vocabulary.entities if e.kind == "room" and e.category == "bedroom"]
    rf.refuse(rf.kids_room(said, why, ", ".join(e.describe() for e in candidates) or "none"))
