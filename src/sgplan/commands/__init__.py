"""Sub-commands of the ``sgplan`` CLI, one module each; ``REGISTRY`` lists their ``register`` functions."""

from __future__ import annotations

from sgplan.commands import (
    bench,
    demo,
    eval_translation,
    guide,
    import_scene,
    inspect,
    monitor,
    plan,
    serve,
    simulate,
    translate,
)

REGISTRY = [
    demo.register, inspect.register, plan.register, translate.register, guide.register, bench.register,
    import_scene.register, eval_translation.register, monitor.register, simulate.register, serve.register,
]
