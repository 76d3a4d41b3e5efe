"""Chit-chat before a mission: *Hi!*, *Okay, here's the plan.*, *I'm hungry, go to the fridge.*

People often open a mission with a sentence or a clause that asks nothing of the robot. Such leading
words are skipped only when they carry nothing the grammar could read: no room or object (nor an ID), no
verb of going or acting, no word with a role in the grammar (order, negation, conditions, floors,
quantities, references). Anything else is left to the parser, which reads it or refuses it; so a
skipped clause can never hold a goal, a place to avoid or a condition.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.names import SceneVocabulary

_ARTICLES = frozenset({"a", "an", "the", "my", "your", "our"})
_TALK_NOUNS = frozenset({"plan", "few", "couple", "thing", "things", "favour", "favor", "request", "job",
                         "task", "tasks", "lot", "bit", "moment", "minute", "second", "question", "list",
                         "day", "morning", "afternoon", "evening", "idea"})
"""After an article, only these say nothing (*here's the plan*, *I need a few things done*): any other word
there could name something to go to (*feed the cat* where the scene has no cat must be refused, not
skipped)."""

_OPENERS = frozenset({"hi", "hello", "hey", "okay", "ok", "alright", "well", "so", "good", "thanks", "thank",
                      "i", "we", "here", "right"})
"""Chit-chat starts with a greeting, an interjection or the speaker (*I'm hungry*, *here's the plan*); a
sentence starting otherwise may be an order about something the scene lacks (*feed pets*), so it is parsed
(and refused) instead."""

_GREETINGS = frozenset({"hi", "hello", "hey"})
"""*Hi there!*: after a greeting, *there* is no place."""


def is_chitchat(words: Sequence[str], vocabulary: SceneVocabulary, grammar_words: Collection[str]) -> bool:
    """Whether ``words`` (a sentence or a leading clause, lower case) carry no mission content: they start
    with a greeting, an interjection or the speaker (``_OPENERS``), and have no room or
    object noun of the scene, no ID, no verb the grammar reads as an action (``lx.POSITIVE_VERBS``) or
    refuses (``lx.REFUSED_VERBS``), no upstairs / downstairs, and none of ``grammar_words`` (the words with a
    role in the grammar), and no article before anything but a word of talk (*the plan*)."""
    if not words or words[0] not in _OPENERS:
        return False
    for k, w in enumerate(words):
        if w == "there" and k > 0 and words[k - 1] in _GREETINGS:
            continue
        if w == ",":
            continue
        if w in _ARTICLES:
            if k + 1 < len(words) and words[k + 1] in _TALK_NOUNS:
                continue
            return False
        if (w.startswith(("room_", "object_")) or w in lx.POSITIVE_VERBS or w in lx.REFUSED_VERBS
                or w in lx.RELATIVE_FLOORS or w in grammar_words or w.isdigit()):
            return False
        if vocabulary.match_head(list(words), k) is not None:
            return False
    return True


def leading_clause(words: Sequence[str], vocabulary: SceneVocabulary, grammar_words: Collection[str]) -> int:
    """How many words of a sentence's leading clause (up to and including its first comma) are chit-chat
    to skip (*I'm hungry, go to the fridge*); 0 if none or if nothing would be left."""
    if "," not in words:
        return 0
    comma = list(words).index(",")
    if comma == 0 or comma == len(words) - 1:
        return 0
    return comma + 1 if is_chitchat(words[:comma], vocabulary, grammar_words) else 0
