"""The service's request and response bodies as pydantic models (the OpenAPI description at ``/docs``
is generated from them). Every text, list and number a request carries is bounded here, with the limits
of :mod:`sgplan.limits`.

Planning options are those of ``sgplan plan`` (setup, profile, radii, budgets); a start is one of a cell,
a metric point, a room or an initial-position index, as on the command line.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from sgplan.limits import (
    MAX_CHANGES_PER_REQUEST,
    MAX_FORMULA_CHARS,
    MAX_MISSION_TEXT_CHARS,
    MAX_NAME_CHARS,
    MAX_POSES_PER_BATCH,
    MAX_REACH_RADIUS_M,
    MAX_ROBOT_RADIUS_M,
    MAX_SECONDS,
)

Name = Annotated[str, Field(min_length=1, max_length=MAX_NAME_CHARS)]
Cell = tuple[Annotated[int, Field(ge=0)], Annotated[int, Field(ge=0)], Annotated[int, Field(ge=0)]]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Start(_Strict):
    """Where the robot starts: exactly one of ``cell`` ``[row, col, floor]``, ``xy_m`` ``[x_m, y_m,
    floor]`` (snapped to the nearest free cell within 0.5 m), ``room`` (``"kitchen"``, ``"room_5"``,
    ``"bathroom on floor 1"``) or ``index`` (the scene's initial position)."""

    cell: Cell | None = None
    xy_m: tuple[float, float, Annotated[int, Field(ge=0)]] | None = None
    room: Name | None = None
    index: Annotated[int, Field(ge=0, le=100_000)] | None = None

    @model_validator(mode="after")
    def _one(self) -> Start:
        given = [k for k in ("cell", "xy_m", "room", "index") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError(
                f"give exactly one of cell, xy_m, room, index (got {', '.join(given) or 'none'})"
            )
        return self

    def spec(self) -> Any:
        """The start as :func:`sgplan.starts.start_cell` takes it."""
        from sgplan.starts import Point

        if self.xy_m is not None:
            return Point(*self.xy_m)
        if self.cell is not None:
            return tuple(self.cell)
        return self.room if self.room is not None else self.index


class Options(_Strict):
    """Planning options, as ``sgplan plan``'s (default: ALL, ltlf, the scene's radii, no budget but the
    server's request time limit)."""

    setup: Literal["ALL", "NO-LLM", "A*", "OCC", "OBJ", "ROOM", "FLR"] = "ALL"
    profile: Literal["ltlf", "authors"] = "ltlf"
    robot_radius_m: Annotated[float, Field(ge=0, le=MAX_ROBOT_RADIUS_M)] | None = None
    reach_radius_m: Annotated[float, Field(gt=0, le=MAX_REACH_RADIUS_M)] | None = None
    time_limit_s: Annotated[float, Field(gt=0, le=MAX_SECONDS)] | None = None
    max_expansions: Annotated[int, Field(ge=1, le=10**12)] | None = None


class MissionIn(_Strict):
    """A mission on a served scene: exactly one of ``text`` (natural language, translated by the server's
    translator) or ``formula`` (LTL: token list, Spot infix or LBT prefix over ``enter(room_<uuid>)`` /
    ``reach(object_<uuid>)``)."""

    scene: Name
    text: Annotated[str, Field(min_length=1, max_length=MAX_MISSION_TEXT_CHARS)] | None = None
    formula: Annotated[str, Field(min_length=1, max_length=MAX_FORMULA_CHARS)] | None = None

    @model_validator(mode="after")
    def _one_mission(self) -> MissionIn:
        if (self.text is None) == (self.formula is None):
            raise ValueError("give exactly one of text (natural language) or formula (LTL)")
        if not (self.text or self.formula or "").strip():
            raise ValueError("the mission is blank")
        return self


class ExplainRequest(MissionIn):
    """A mission to say back and check; with ``start``, the start-dependent checks run too."""

    start: Start | None = None
    options: Options = Field(default_factory=Options)


class PlanRequest(MissionIn):
    """A one-shot plan. ``view``: also return the page's SVG overlays of the path (one per floor)."""

    start: Start | None = None
    options: Options = Field(default_factory=Options)
    view: bool = False


class Finding(BaseModel):
    kind: str
    severity: Literal["error", "warning", "note"]
    message: str


class ExplainResponse(BaseModel):
    """What the server understood: the formula, each proposition's meaning, the mission in words (every
    entity named by category, id and floor), and the scene checks."""

    scene: str
    formula: str | None
    propositions: dict[str, str]
    explanation: str
    method: str
    scene_check: list[Finding]
    notes: list[str]


class PlanRecord(BaseModel):
    """The JSON of ``sgplan plan --json -`` (:meth:`sgplan.PlanResult.to_dict`); the main fields are
    listed, the rest (iterations, waypoints, events, timings ...) as documented in docs/serve.md."""

    model_config = ConfigDict(extra="allow")
    scene: str
    status: str
    cost_m: float | None
    bound: float | None
    path: list[list[int]] | None
    start: list[int]


class SceneInfo(BaseModel):
    name: str
    floors: int
    rooms: int
    objects: int


class Door(BaseModel):
    """An opening between two rooms of a floor, at its middle cell."""

    floor: int
    rooms: tuple[str, str]
    names: tuple[str, str]
    row: int
    col: int


Poses = Annotated[
    list[tuple[float, float, Annotated[int, Field(ge=0)]]],
    Field(min_length=1, max_length=MAX_POSES_PER_BATCH),
]


class RunRequest(MissionIn):
    """A run: a mission carried out from ``start``; it is planned at once."""

    start: Start | None = None
    options: Options = Field(default_factory=Options)


class ObserveRequest(_Strict):
    """Poses the robot drove through since the last report, oldest first: ``[x_m, y_m, floor]``."""

    poses: Poses


class ChangesRequest(_Strict):
    """Scene changes (the JSON Schema of docs/execution.md: ``close_door``, ``open_door``, ``block``,
    ``unblock``, ``move_object``, ...)."""

    changes: Annotated[list[dict[str, Any]], Field(min_length=1, max_length=MAX_CHANGES_PER_REQUEST)]


class AmendRequest(_Strict):
    """An amendment in words (``"also go to the kitchen"``), translated over the run's scene."""

    text: Annotated[str, Field(min_length=1, max_length=MAX_MISSION_TEXT_CHARS)]
