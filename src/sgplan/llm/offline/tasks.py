"""What a mission's sentences are read into, before they become a formula: tasks and steps.

A :class:`Task` is one goal over a set of alternatives or obligations; a :class:`Step` is a list of tasks done
in any order; a sentence is a sequence of steps (:mod:`.meaning.compose` says what formula they stand for).
The discourse state (:mod:`.grounding.discourse`) keeps the last step read, for *there* and *that* after it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from sgplan.logic.formula import Formula


@dataclass
class Task:
    """One goal: ``any`` of ``members`` or ``all`` of them, each with the local negations ``avoid``;
    ``revisit``: reached anew, after being elsewhere (see the module docstring)."""

    mode: Literal["any", "all"]
    members: list[Formula]
    avoid: list[Formula] = field(default_factory=list)
    revisit: bool = False
    strict: bool = False
    """Said with *only after that* / *only then*: not done before the previous step (see
    :func:`.meaning.compose.strict_formulas`)."""
    said_at: int = -1
    """The character offset of the phrase the task was read from (-1: none), for
    :func:`.meaning.compose.check_text_order`."""
    moved: bool = False
    """An explicit word placed the task out of the order of the text (*before that*, *first*, *via*, *after
    X*, *twice with Y in between*)."""


Step = list[Task]
