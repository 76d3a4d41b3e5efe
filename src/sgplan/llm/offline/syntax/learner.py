"""Marks of a learner's English in a mission text, which decide a word order only learners use.

*Wipe the table, after you go in kitchen for to check the oven* and *go in kitchen, after the living room*
use *after* as *afterwards* (then), as learners of English translate their *después* / *dopo* / *après*;
said by a native speaker, *A, after B* could put B first, so without a learner's mark it is refused
(:func:`.links.after_as_then`). A mark is a slip no native speaker makes in writing: a purpose said *for*
and a verb (*for check*, *for to take*), *where is the X* / *where are the X* inside a noun phrase, *must
to* / *can to*, *enter in*, *go / come / pass at*, *in this floor*, *is not matter*, a room's noun with no
article after a preposition of place (*go in kitchen*, *to living room*), or a thing *of* a room (*the sink
of the other bathroom*, *the plant of living room*). The marks are read in the whole mission, as typed.
"""

from __future__ import annotations

import re

_ROOM = (r"(?:kitchen|living room|dining room|bathroom|bedroom|office|home office|garage|lobby|corridor"
         r"|hallway|hall|empty room|utility room|staircase)")
_THING = r"(?:sink|plant|potted plant|vase|chair|couch|sofa|tv|table|dining table|bed|toilet|clock|bowl|cup)"
_MARKS = re.compile("|".join((
    r"\bfor (?:to )?(?:check|take|look|see|wash|watch|put|bring|clean|water|sit|get|open|use|touch)\b",
    r"\b(?:room|" + _ROOM + r") where (?:is|are) (?:the|a|an|one|two)\b",
    r"\b(?:must|can|should) to\b",
    r"\benter(?:ing)? in(?:to)?\b",
    r"\b(?:go|goes|going|come|coming|pass|passing) at\b",
    r"\bin this floor\b",
    r"\bis not matter\b",
    r"\b(?:to|in|into|at|from) " + _ROOM + r"\b",
    r"\bthe " + _THING + r" of (?:the )?(?:other )?" + _ROOM + r"\b",
)))


def learner_english(text: str) -> bool:
    """Whether the mission ``text`` (as typed) bears a mark of a learner's English (see the module
    docstring)."""
    return _MARKS.search(text.lower()) is not None
