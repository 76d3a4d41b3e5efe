"""Sub-commands of the ``sgplan`` CLI, one module each; ``REGISTRY`` lists their ``register`` functions."""

from __future__ import annotations

from sgplan.commands import demo, inspect, plan

REGISTRY = [demo.register, inspect.register, plan.register]
