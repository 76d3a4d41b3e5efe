"""What happened to a run (:class:`RunEvent`), as the callbacks of
:meth:`~sgplan.execution.run.Run.subscribe` get it and :attr:`~sgplan.execution.run.Run.history` keeps it
(the kinds: :mod:`sgplan.execution.run`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class RunEvent:
    """Something that happened to a run: its ``kind``, a sentence, JSON-safe ``details`` and, apart
    (not saved: it differs between two runs of the same thing), the ``seconds`` it took."""

    kind: str
    message: str
    details: dict[str, Any] = field(default_factory=dict)
    seconds: float | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "message": self.message, "details": self.details}
