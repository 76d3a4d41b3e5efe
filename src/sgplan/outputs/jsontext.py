"""The text of a plan record as JSON: one key per line, and one line per row of its long lists.

``json.dumps(record, indent=1)`` puts every number of a path on its own line (a Gibson plan's record was
~30,000 lines) and, with an indent, Python's JSON encoder runs in pure Python (14-40 ms per plan). Here the
top-level keys are indented as before, while each element of a list of rows (the path cells, the
waypoints, the events: lists whose elements are all lists or dicts) is one compact line made by the C
encoder. Any JSON reader sees the same document (:func:`json.loads` gives what it gives for
``json.dumps(record)``); NaN and infinities are refused as there.

    {
     "status": "optimal",
     "path": [
      [300, 800, 0, 2],
      [301, 801, 0, 2]
     ],
     ...
    }
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from sgplan.planning.amra import IterationRecord

_ROW = json.JSONEncoder(allow_nan=False, separators=(", ", ": "))
"""Encodes one row on one line (no indent: the C encoder)."""


def record_json(record: dict[str, Any]) -> str:
    """``record`` (a dict of JSON values) as JSON text laid out as the module says, ending in a newline.

    Raises
    ------
    ValueError
        a NaN or infinite number in ``record``.
    TypeError
        a value JSON cannot hold.
    """
    if not record:
        return "{}\n"
    items = []
    for key, value in record.items():
        name = json.dumps(str(key))
        if isinstance(value, list) and value and all(isinstance(row, (list, dict)) for row in value):
            rows = ",\n  ".join(_ROW.encode(row) for row in value)
            items.append(f" {name}: [\n  {rows}\n ]")
        else:  # nested as json.dumps(indent=1) would nest it one level down (strings hold no raw newline)
            text = json.dumps(value, indent=1, allow_nan=False).replace("\n", "\n ")
            items.append(f" {name}: {text}")
    return "{\n" + ",\n".join(items) + "\n}\n"


def iteration_records(iterations: Sequence[IterationRecord]) -> list[dict[str, Any]]:
    """JSON-ready records of AMRA* iterations: weights, ``cost_m`` (metres), suboptimality bound w1*w2,
    cumulative search seconds and cumulative expansions per queue (``PlanResult.queues`` order).
    The one shape of iterations in every sgplan output (``plan --json``, demo's run.json, bench rows)."""
    return [
        {"w1": it.w1, "w2": it.w2, "cost_m": it.cost_m, "bound": it.bound, "time_s": it.time_s,
         "expansions": list(it.expansions)}
        for it in iterations
    ]


def finite_or_none(value: float) -> float | None:
    """``value``, or ``None`` for an infinite / NaN one (JSON has no infinity)."""
    return value if math.isfinite(value) else None
