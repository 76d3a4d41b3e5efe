"""The HTTP face of the mission service: routes, error answers, middleware (FastAPI).

:func:`create_app` builds the application from a :class:`~sgplan.serve.config.ServeConfig` (or from a
:class:`~sgplan.serve.service.MissionService` already made, in tests). The routes only translate HTTP to
the service's calls and back; what they do is in :mod:`sgplan.serve.service`. The OpenAPI description
is at ``/docs`` (and ``/openapi.json``); docs/serve.md lists every route.
"""

from __future__ import annotations

from contextlib import asynccontextmanager
from importlib import resources
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.middleware.cors import CORSMiddleware
from fastapi.responses import HTMLResponse, JSONResponse, Response
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException as StarletteHTTPException

from sgplan import __version__
from sgplan.errors import SgplanError
from sgplan.serve.config import ServeConfig
from sgplan.serve.errors import error_body, error_response, not_found, validation_message
from sgplan.serve.guards import BodyLimit, TokenGuard
from sgplan.serve.models import (
    AmendRequest,
    ChangesRequest,
    ExplainRequest,
    ExplainResponse,
    ObserveRequest,
    PlanRecord,
    PlanRequest,
    RunRequest,
    SceneInfo,
)
from sgplan.serve.service import MissionService

ASSETS = {
    "page.js": ("sgplan.serve", "page/page.js", "text/javascript"),
    "page.css": ("sgplan.serve", "page/page.css", "text/css"),
    "report.js": ("sgplan.report", "report.js", "text/javascript"),
    "report.css": ("sgplan.report", "report.css", "text/css"),
}
"""The page's files: its own and the HTML report's (the same hover and drawing code), by name."""
_ERRORS: dict[int | str, dict[str, Any]] = {
    code: {"description": text}
    for code, text in (
        (404, "unknown scene or run"),
        (422, "bad input (the one-line message says which field or entity)"),
        (401, "missing or wrong token"),
        (413, "request body too large"),
    )
}


def create_app(config: ServeConfig | None = None, *, service: MissionService | None = None) -> FastAPI:
    """The ASGI application serving ``config``'s scenes (loaded now), or ``service``'s."""
    if service is None:
        assert config is not None
        service = MissionService.start(config.checked())
    config = service.config

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> Any:
        service.attach_loop()
        yield
        service.close()

    app = FastAPI(
        title="sgplan mission service",
        version=__version__,
        lifespan=lifespan,
        description="Plan and carry out missions over 3D scene graphs (docs/serve.md).",
    )
    app.state.service = service
    _add_error_handlers(app)
    _add_scene_routes(app, service)
    _add_mission_routes(app, service)
    _add_run_routes(app, service)
    _add_page_routes(app)
    if config.cors_origins:
        app.add_middleware(
            CORSMiddleware,
            allow_origins=list(config.cors_origins),
            allow_methods=["GET", "POST"],
            allow_headers=["Authorization", "Content-Type"],
        )
    app.add_middleware(BodyLimit)
    if config.token:
        app.add_middleware(TokenGuard, token=config.token)
    return app


def _add_error_handlers(app: FastAPI) -> None:
    @app.exception_handler(SgplanError)
    async def sgplan_error(request: Request, error: SgplanError) -> Response:
        return error_response(error)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, error: StarletteHTTPException) -> Response:
        message = {
            404: f"no route {request.url.path}; the API is described at /docs",
            405: f"{request.method} is not allowed on {request.url.path}",
        }.get(error.status_code, str(error.detail))
        return JSONResponse(
            error_body(error.status_code, message, kind="HTTPError"),
            status_code=error.status_code,
            headers=error.headers,
        )

    @app.exception_handler(RequestValidationError)
    async def bad_request(request: Request, error: RequestValidationError) -> Response:
        message = validation_message(list(error.errors()))
        return JSONResponse(error_body(422, message, kind="RequestError"), status_code=422)


def _add_scene_routes(app: FastAPI, service: MissionService) -> None:
    @app.get("/api/health")
    def health() -> dict[str, Any]:
        """The server's state: scenes served, plans in flight and refused, runs held."""
        return service.health()

    @app.get("/api/scenes", response_model=list[SceneInfo])
    def scenes() -> list[dict[str, Any]]:
        """The scenes this server serves (its own configuration)."""
        return [host.info() for host in service.scenes]

    @app.get("/api/scenes/{scene}", responses=_ERRORS, response_class=JSONResponse)
    def scene(scene: str) -> Response:
        """A scene's summary (``sgplan inspect --json``) with its doors."""
        return JSONResponse(service.scenes[scene].summary)

    @app.get("/api/scenes/{scene}/floors/{floor}.png", responses=_ERRORS, response_class=Response)
    def floor_picture(scene: str, floor: int) -> Response:
        """A floor's picture (PNG): rooms, objects, walls; cells the robot may not enter shaded."""
        return Response(
            service.scenes[scene].floor_png(floor),
            media_type="image/png",
            headers={"Cache-Control": "max-age=3600"},
        )

    @app.get("/api/scenes/{scene}/layers", responses=_ERRORS)
    def layers(scene: str) -> dict[str, Any]:
        """The page's floors of a scene, drawn by the HTML report's renderer (HTML and entities)."""
        return service.layers(scene)


def _add_mission_routes(app: FastAPI, service: MissionService) -> None:
    @app.post("/api/explain", response_model=ExplainResponse, responses=_ERRORS)
    def explain(request: ExplainRequest) -> dict[str, Any]:
        """What the server understood: formula, the mission in words, the scene checks."""
        return service.explain(request)

    @app.post(
        "/api/plan",
        responses={
            **_ERRORS,
            200: {"model": PlanRecord},
            408: {"description": "no path within the server's time limit"},
            503: {"description": "every plan worker busy (Retry-After)"},
        },
    )
    async def plan(request: PlanRequest) -> Response:
        """A one-shot plan: the JSON of ``sgplan plan --json -`` (with ``view``: the page's overlays)."""
        return JSONResponse(await service.plan(request))


def _add_run_routes(app: FastAPI, service: MissionService) -> None:
    run_errors = {**_ERRORS, 409: {"description": "conflict with the run's state"}}

    @app.post("/api/runs", status_code=201, responses=run_errors)
    async def create_run(request: RunRequest) -> Response:
        """Start a run: the mission is planned from the start and carried out as poses come in."""
        return JSONResponse(await service.runs.create(request), status_code=201)

    @app.get("/api/runs")
    def list_runs() -> list[dict[str, Any]]:
        """Every run held: id, scene, status, progress."""
        return service.runs.list()

    # The run routes answer JSONResponse themselves: FastAPI's encoder walks every value of a dict answer
    # again (a plan's waypoints), which cost more than the rest of a pose report.
    @app.get("/api/runs/{run_id}", responses=run_errors, response_class=JSONResponse)
    def get_run(run_id: str, view: bool = False) -> Response:
        """A run: mission, progress, plan, changes, amendments (with ``view``: the page's overlays)."""
        return JSONResponse(service.runs.get(run_id, view=view))

    @app.post("/api/runs/{run_id}/observe", responses=run_errors, response_class=JSONResponse)
    def observe(run_id: str, request: ObserveRequest) -> Response:
        """Report poses ``[x_m, y_m, floor]``: ``{"run": the run, "monitor": the runtime monitor's status}``
        (verdict, state, what is left in words, the poses' issues)."""
        return JSONResponse(service.runs.observe(run_id, request))

    @app.post("/api/runs/{run_id}/changes", responses=run_errors, response_class=JSONResponse)
    async def changes(run_id: str, request: ChangesRequest) -> Response:
        """Apply scene changes (a door closed, an area blocked ...) and replan from where the robot is."""
        return JSONResponse(await service.runs.change(run_id, request))

    @app.post("/api/runs/{run_id}/amend", responses=run_errors, response_class=JSONResponse)
    async def amend(run_id: str, request: AmendRequest) -> Response:
        """Amend the mission in words and replan."""
        return JSONResponse(await service.runs.amend(run_id, request))

    @app.post("/api/runs/{run_id}/replan", responses=run_errors, response_class=JSONResponse)
    async def replan(run_id: str) -> Response:
        """Plan again from where the robot is (e.g. after it left its plan)."""
        return JSONResponse(await service.runs.replan(run_id))

    @app.post("/api/runs/{run_id}/cancel", responses=run_errors, response_class=JSONResponse)
    def cancel(run_id: str) -> Response:
        """Cancel a run (and any plan of it still searching)."""
        return JSONResponse(service.runs.cancel(run_id))

    @app.get("/api/runs/{run_id}/events", responses=run_errors)
    async def events(run_id: str, request: Request) -> Response:
        """The run's events as Server-Sent Events: replanned, progress, violated, done, cancelled."""
        return await service.runs.stream(run_id, request)


def _add_page_routes(app: FastAPI) -> None:
    @app.get("/", response_class=HTMLResponse, include_in_schema=False)
    def page() -> HTMLResponse:
        text = resources.files("sgplan.serve").joinpath("page/index.html").read_text(encoding="utf-8")
        return HTMLResponse(text, headers={"Cache-Control": "no-cache"})

    @app.get("/assets/{name}", include_in_schema=False)
    async def asset(name: str) -> Response:
        if name not in ASSETS:
            raise not_found("asset", name, sorted(ASSETS))
        package, file, media = ASSETS[name]
        text = await run_in_threadpool(resources.files(package).joinpath(file).read_text, encoding="utf-8")
        return Response(text, media_type=media, headers={"Cache-Control": "no-cache"})
