"""Sub-commands of the ``sgplan`` CLI, one module each; ``REGISTRY`` lists their ``register`` functions."""

from __future__ import annotations

REGISTRY: list = []
