"""The configuration of one ``sgplan serve`` process: which scenes it serves, where it listens, who may
talk to it, where it keeps its state, and how much planning it takes on at once.

:class:`ServeConfig` is a frozen value checked when made (:meth:`ServeConfig.checked`): the CLI builds
one from its arguments, tests and embedders build one in code and hand it to
:func:`sgplan.serve.app.create_app`.
"""

from __future__ import annotations

import ipaddress
import os
from dataclasses import dataclass, field
from pathlib import Path

from sgplan.errors import SgplanError

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8000
DEFAULT_STATE_DIR = "sgplan-state"
MIN_TOKEN_CHARS = 16
"""A token shorter than this is refused: it could be guessed."""


class ServeError(SgplanError):
    """The service cannot start as configured (an address without a token, a bad state folder ...);
    ``path``, when given, is the file at fault and prefixes the message."""

    def __init__(self, message: str, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        super().__init__(f"{self.path}: {message}" if self.path is not None else message)


@dataclass(frozen=True)
class ServeConfig:
    """How one service runs.

    Attributes
    ----------
    scenes:
        the scenes served, as ``sgplan.load_scene`` names them (``"demo"``, a Gibson name, a folder);
        requests name them by the loaded building's name, never by a path.
    host, port:
        where to listen; any host but a loopback address needs ``token``.
    token:
        the secret every request must carry (``Authorization: Bearer <token>``); ``None``: no check
        (loopback only).
    state_dir:
        the folder of the runs' database (``runs.sqlite``); nothing from a request is written elsewhere.
    database_url:
        a SQLAlchemy URL for the runs instead of the SQLite file in ``state_dir`` (e.g. PostgreSQL when
        several replicas serve one fleet).
    data:
        the folder holding the Gibson scenes (``sgplan.load_scene``'s ``data``).
    plan_workers, plan_backlog:
        plans running at once (threads), and plans that may wait for one; a request beyond both is
        answered 503 with ``Retry-After``.
    request_time_limit_s:
        wall-clock seconds one plan request may take (queueing and planning) before it is stopped: the
        best path so far, or 408 without one.
    hot_runs:
        runs kept in memory with their planner parts (tens of MB each on a Gibson scene); the others are
        brought back from the database when next used.
    cors_origins:
        origins allowed to call the API from a browser page served elsewhere; empty: no CORS headers.
    """

    scenes: tuple[str, ...]
    host: str = DEFAULT_HOST
    port: int = DEFAULT_PORT
    token: str | None = None
    state_dir: Path = field(default_factory=lambda: Path(DEFAULT_STATE_DIR))
    database_url: str | None = None
    data: str | None = None
    plan_workers: int = 2
    plan_backlog: int = 8
    request_time_limit_s: float = 30.0
    hot_runs: int = 8
    cors_origins: tuple[str, ...] = ()

    def checked(self) -> ServeConfig:
        """This configuration, or :class:`ServeError` naming the setting at fault and what to do."""
        if not self.scenes:
            raise ServeError("no scene to serve: give at least one --scene (e.g. --scene demo)")
        if not is_loopback(self.host) and not self.token:
            raise ServeError(
                f"refusing to listen on {self.host} without a token: any machine that reaches it could plan "
                "and drive runs; give --token-file FILE (or --token), or listen on 127.0.0.1"
            )
        if self.token is not None and len(self.token) < MIN_TOKEN_CHARS:
            raise ServeError(
                f"the token has {len(self.token)} characters; use at least {MIN_TOKEN_CHARS} "
                "(e.g. python3 -c 'import secrets; print(secrets.token_urlsafe(32))')"
            )
        if not (0 < self.port < 65536):
            raise ServeError(f"--port {self.port} is not a TCP port (1-65535)")
        if self.plan_workers < 1 or self.plan_backlog < 0 or self.hot_runs < 1:
            raise ServeError("--workers and --hot-runs must be >= 1, --backlog >= 0")
        if not (0 < self.request_time_limit_s <= 3600):
            raise ServeError(f"--request-time-limit {self.request_time_limit_s:g} s is not in (0, 3600]")
        return self


def is_loopback(host: str) -> bool:
    """Whether ``host`` is a loopback address (``127.0.0.0/8``, ``::1``) or ``localhost``."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def read_token_file(path: str | Path) -> str:
    """The token in ``path`` (its first line, stripped), refusing a file others may read.

    Raises
    ------
    ServeError
        the file is missing, unreadable, empty, or readable by group or others (``chmod 600`` it).
    """
    from sgplan.safeio import read_text

    target = Path(path).expanduser()
    text = read_text(target, ServeError, what="token file", max_bytes=4096)
    if os.name == "posix" and target.stat().st_mode & 0o077:
        raise ServeError(f"the token file may be read by others; chmod 600 {target}", target)
    token = text.strip().splitlines()[0].strip() if text.strip() else ""
    if not token:
        raise ServeError("the token file is empty", target)
    return token
