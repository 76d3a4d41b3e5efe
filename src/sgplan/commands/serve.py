"""``sgplan serve``: the mission service (JSON API, live page) over one or more warm scenes.

Building the parser imports nothing of the service (FastAPI, uvicorn, SQLAlchemy load when it runs), so
the other commands stay fast and work without the ``serve`` extra.
"""

from __future__ import annotations

import argparse
import importlib.util
from pathlib import Path

from sgplan.commands.common import non_negative_int, positive_int, positive_seconds, say
from sgplan.errors import SgplanError


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "serve", help="serve missions over HTTP: a JSON API and a live web page (docs/serve.md)",
        description="Serve missions over HTTP: explain, plan, runs with progress and event streams, and a "
        "live web page at /. Listens on 127.0.0.1 unless told otherwise; any other address needs a token.",
    )
    parser.add_argument("--scene", action="append", required=True, metavar="SCENE",
                        help="a scene to serve (repeat for more): 'demo', a Gibson name or a scene folder")
    parser.add_argument("--data", metavar="DIR", default=None, help="folder holding the Gibson scenes")
    parser.add_argument("--host", default="127.0.0.1", help="address to listen on (default 127.0.0.1)")
    parser.add_argument("--port", type=positive_int, default=8000, help="TCP port (default 8000)")
    token = parser.add_mutually_exclusive_group()
    token.add_argument("--token-file", metavar="FILE", help="file holding the token every request must carry "
                       "(chmod 600); required to listen beyond this machine")
    token.add_argument("--token", metavar="TOKEN", help="the token itself (visible to other users in the "
                       "process list: prefer --token-file)")
    parser.add_argument("--state", metavar="DIR", default="sgplan-state",
                        help="folder of the runs' database (default ./sgplan-state)")
    parser.add_argument("--database-url", metavar="URL", help="a SQLAlchemy URL for the runs instead of "
                        "the SQLite file in --state (e.g. postgresql://...)")
    parser.add_argument("--workers", type=positive_int, default=2, help="plans running at once (default 2)")
    parser.add_argument("--backlog", type=non_negative_int, default=8,
                        help="plans that may wait for a worker before requests get 503 (default 8)")
    parser.add_argument("--request-time-limit", type=positive_seconds, default=30.0, metavar="S",
                        help="wall-clock seconds one plan request may take (default 30)")
    parser.add_argument("--hot-runs", type=positive_int, default=8, metavar="N",
                        help="runs kept in memory with their planner parts (default 8); the others wait in "
                        "the database")
    parser.add_argument("--cors-origin", action="append", default=[], metavar="ORIGIN",
                        help="an origin allowed to call the API from its pages (repeat; default none)")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    if importlib.util.find_spec("fastapi") is None or importlib.util.find_spec("uvicorn") is None:
        raise SgplanError("sgplan serve needs the serve extra: pip install 'sgplan[serve]'")
    import uvicorn

    from sgplan.serve.app import create_app
    from sgplan.serve.config import ServeConfig, read_token_file

    config = ServeConfig(
        scenes=tuple(args.scene), host=args.host, port=args.port,
        token=read_token_file(args.token_file) if args.token_file else args.token,
        state_dir=Path(args.state), database_url=args.database_url, data=args.data, plan_workers=args.workers,
        plan_backlog=args.backlog, request_time_limit_s=args.request_time_limit, hot_runs=args.hot_runs,
        cors_origins=tuple(args.cors_origin),
    ).checked()
    say(f"loading {len(config.scenes)} scene(s): {', '.join(config.scenes)}")
    app = create_app(config)
    service = app.state.service
    say(f"serving {', '.join(service.scenes.names())} ({service.runs.count()} run(s) restored from "
        f"{config.database_url or config.state_dir}) on http://{config.host}:{config.port}/ "
        f"(API description at /docs)")
    uvicorn.run(app, host=config.host, port=config.port, log_level="warning", access_log=False)
    return 0
