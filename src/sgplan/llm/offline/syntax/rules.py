"""Named, ordered sets of syntax rules: each construct of the grammar is one small registered function.

A :class:`RuleSet` is tried in the order its rules were registered; the first rule that does not return
``None`` (a :class:`.reader.Match` or a :class:`.reader.Refusal`) decides. Adding a construct to a slot of
the grammar (a qualifier after a noun, an item of a sentence body, ...) is registering one function in
that slot's set, next to the rules it must come before or after.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Generic, TypeVar

from sgplan.llm.offline.syntax.reader import Parse, Reader

N = TypeVar("N")
Rule = Callable[..., Parse[Any]]


class RuleSet(Generic[N]):
    """The rules of one slot of the grammar, in order of precedence.

    Example
    -------
    >>> QUALIFIERS: RuleSet[Qualifier] = RuleSet("qualifier")  # doctest: +SKIP
    >>> @QUALIFIERS.rule("next to")  # doctest: +SKIP
    ... def next_to(r: Reader, i: int, noun: NounSoFar) -> Parse[Qualifier]: ...
    """

    def __init__(self, slot: str) -> None:
        self.slot = slot
        self.rules: list[tuple[str, Rule]] = []

    def rule(self, name: str) -> Callable[[Rule], Rule]:
        """Register the decorated function as the rule ``name`` (after those registered before it)."""
        if any(n == name for n, _ in self.rules):
            raise ValueError(f"{self.slot} rule {name!r} is registered twice")

        def register(fn: Rule) -> Rule:
            self.rules.append((name, fn))
            return fn
        return register

    def first(self, r: Reader, i: int, *args: Any) -> Parse[N]:
        """The result of the first rule that applies at token ``i``, or ``None`` if none does."""
        for _, fn in self.rules:
            result = fn(r, i, *args)
            if result is not None:
                return result
        return None

    def names(self) -> list[str]:
        """The rule names, in order."""
        return [n for n, _ in self.rules]
