"""What is done with each kind of node of the syntax tree, registered by the node's type.

Grounding a kind of phrase, applying a kind of qualifier, reading a kind of body item or sentence: each is
one function registered for its node type (``@REGISTRY.register(NodeType)``), and the registry calls the one
of a node's type. A new kind of node is a new registration, beside the others.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any, Generic, TypeVar

F = TypeVar("F", bound=Callable[..., Any])


class Registry(Generic[F]):
    """The functions of one job (``job``: for messages), by the type of node they take first."""

    def __init__(self, job: str) -> None:
        self.job = job
        self.functions: dict[type, F] = {}

    def register(self, kind: type) -> Callable[[F], F]:
        """Register the decorated function as the one for the nodes of type ``kind``."""
        def register(fn: F) -> F:
            if kind in self.functions:
                raise ValueError(f"{self.job} of {kind.__name__} is registered twice")
            self.functions[kind] = fn
            return fn
        return register

    def __call__(self, node: object, *args: Any) -> Any:
        """The registered function of ``node``'s type, called with ``node`` and ``args``."""
        return self.functions[type(node)](node, *args)

    def __iter__(self) -> Iterator[type]:
        return iter(self.functions)
