"""Errors as HTTP answers: one JSON shape, the CLI's one-line messages, the right status.

Every error answer is ``{"error": {"status": 422, "kind": "MissionError", "message": "...",
"plan_status": "infeasible"}}`` (``plan_status`` only for planning errors), with ``Retry-After`` on 408
and 503. The message is the same line ``sgplan`` prints after ``sgplan: error:``.

=====  ==========================================================================================
422    bad input: an unknown room in the mission, a malformed formula, a start in a wall, a mission
       no path from this start satisfies, a field out of its bounds
404    an unknown scene, run or page asset
409    a conflict with a run's state: an amendment or a change that leaves the mission
       unsatisfiable, an action on a run that has ended
408    the request's time limit ran out before any path was found (``Retry-After``)
413    a request body larger than :data:`sgplan.limits.MAX_REQUEST_BYTES`
401    a missing or wrong token
503    every plan worker busy and the backlog full (``Retry-After``)
=====  ==========================================================================================
"""

from __future__ import annotations

from typing import Any

from starlette.responses import JSONResponse

from sgplan.errors import PlanningError, SgplanError
from sgplan.safeio import clip


class HTTPProblem(SgplanError):
    """An error with its HTTP status chosen where it is raised (404 unknown run, 409 conflict, ...);
    ``retry_after_s`` adds a ``Retry-After`` header."""

    def __init__(
        self, status: int, message: str, *, retry_after_s: int | None = None, plan_status: str | None = None
    ) -> None:
        self.status = status
        self.retry_after_s = retry_after_s
        self.plan_status = plan_status
        super().__init__(message)


def not_found(what: str, name: str, known: list[str] | None = None) -> HTTPProblem:
    """404 for an unknown ``what`` (``"scene"``, ``"run"``) called ``name``, listing the known ones."""
    listing = f"; the {what}s are {', '.join(known)}" if known else ""
    return HTTPProblem(404, f"unknown {what} {clip(repr(name), 80)}{listing}")


def status_of(error: SgplanError) -> int:
    """The HTTP status of a library error raised while serving a request (see the module docstring)."""
    if isinstance(error, HTTPProblem):
        return error.status
    return 422


def error_body(status: int, error: SgplanError | str, kind: str | None = None) -> dict[str, Any]:
    """The JSON body of an error answer."""
    message = str(error)
    body: dict[str, Any] = {
        "status": status,
        "kind": kind or type(error).__name__,
        "message": clip(message, 2000),
    }
    plan_status = getattr(error, "plan_status", None) or (
        error.status if isinstance(error, PlanningError) else None
    )
    if plan_status is not None:
        body["plan_status"] = plan_status
    return {"error": body}


def error_response(error: SgplanError, status: int | None = None) -> JSONResponse:
    """The answer to ``error`` (status from :func:`status_of` unless given)."""
    code = status_of(error) if status is None else status
    headers = {}
    retry = getattr(error, "retry_after_s", None)
    if retry is not None:
        headers["Retry-After"] = str(int(retry))
    return JSONResponse(error_body(code, error), status_code=code, headers=headers)


def validation_message(errors: list[dict[str, Any]]) -> str:
    """One line for pydantic's validation errors: where in the request and what is wrong, first error
    first (``request body field start.cell: Tuple should have at most 3 items``)."""
    parts = []
    for error in errors[:3]:
        location = [str(p) for p in error.get("loc", ()) if p not in ("body",)]
        where = f"field {'.'.join(location)}" if location else "the request body"
        parts.append(f"{where}: {error.get('msg', 'invalid')}")
    more = f" (and {len(errors) - 3} more)" if len(errors) > 3 else ""
    return "bad request: " + "; ".join(parts) + more
