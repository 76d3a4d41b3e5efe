"""Where runs are kept across restarts: a relational database through SQLAlchemy 2.

By default an SQLite file, ``runs.sqlite`` in the server's state folder, in WAL mode: every change to a
run (its record and the events it produced) is one transaction, so a server killed at any moment
(SIGKILL included) comes back with each run as of its last committed change, never half-written. With
``synchronous=NORMAL`` a commit survives the process's death; a power cut may lose the last commits
(the database stays consistent). Any SQLAlchemy URL works instead (``postgresql://...``), so several
replicas can serve one fleet from one database; each update checks the run's version, so two replicas
never overwrite each other's change unseen (:class:`StaleRun`).

Two tables: ``runs`` (id, scene, status, version, times, the run's JSON record) and ``run_events`` (the
events of each run in order: ``seq``, ``kind``, JSON data), from which a reconnecting stream replays.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from sqlalchemy import (
    JSON,
    Float,
    ForeignKey,
    Integer,
    String,
    bindparam,
    create_engine,
    event,
    func,
    insert,
    select,
    update,
)
from sqlalchemy.engine import Engine
from sqlalchemy.exc import SQLAlchemyError
from sqlalchemy.orm import DeclarativeBase, Mapped, Session, mapped_column

from sgplan.serve.config import ServeError

DATABASE_NAME = "runs.sqlite"


class _Base(DeclarativeBase):
    pass


class RunRow(_Base):
    __tablename__ = "runs"
    id: Mapped[str] = mapped_column(String(64), primary_key=True)
    scene: Mapped[str] = mapped_column(String(200))
    status: Mapped[str] = mapped_column(String(32), index=True)
    version: Mapped[int] = mapped_column(Integer)
    created_at: Mapped[float] = mapped_column(Float)
    updated_at: Mapped[float] = mapped_column(Float)
    record: Mapped[dict[str, Any]] = mapped_column(JSON)
    plan: Mapped[dict[str, Any] | None] = mapped_column(JSON, nullable=True)
    """The run's current plan, apart: it is written only when it changes (a plan is tens to hundreds of
    kB; a pose report changes only the small record)."""


class EventRow(_Base):
    __tablename__ = "run_events"
    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    run_id: Mapped[str] = mapped_column(ForeignKey("runs.id"), index=True)
    seq: Mapped[int] = mapped_column(Integer)
    kind: Mapped[str] = mapped_column(String(32))
    at: Mapped[float] = mapped_column(Float)
    data: Mapped[dict[str, Any]] = mapped_column(JSON)


class Unchanged:
    """The type of :data:`UNCHANGED`."""


UNCHANGED = Unchanged()
"""Passed as a plan to :meth:`RunStore.update`: keep the stored one."""


_WHERE = (RunRow.id == bindparam("run_id"), RunRow.version == bindparam("old_version"))
_FIELDS: dict[str, Any] = {name: bindparam(name) for name in ("status", "record", "version", "updated_at")}
_UPDATE_RECORD = update(RunRow).where(*_WHERE).values(**_FIELDS)
_UPDATE_RECORD_AND_PLAN = update(RunRow).where(*_WHERE).values(**_FIELDS, plan=bindparam("plan"))


class StaleRun(ServeError):
    """The run changed in the database since it was read (another replica changed it)."""


@dataclass(frozen=True)
class StoredRun:
    """A run as read back: its row and its record (:meth:`RunStore.load_all`)."""

    id: str
    scene: str
    status: str
    version: int
    record: dict[str, Any]
    plan: dict[str, Any] | None
    last_seq: int


@dataclass(frozen=True)
class StoredEvent:
    seq: int
    kind: str
    at: float
    data: dict[str, Any]


class RunStore:
    """The runs' database (see the module docstring)."""

    def __init__(self, engine: Engine) -> None:
        self.engine = engine
        try:
            _Base.metadata.create_all(engine)
        except SQLAlchemyError as error:
            raise ServeError(
                f"cannot open the runs' database {engine.url!r}: {error.__class__.__name__}: "
                f"{str(error).splitlines()[0]}"
            ) from None

    @classmethod
    def open(cls, url: str | None, state_dir: str | Path) -> RunStore:
        """The database at ``url``, or ``runs.sqlite`` in ``state_dir`` (created, private to the user)."""
        if url is not None:
            return cls(create_engine(url))
        folder = Path(state_dir).expanduser()
        try:
            folder.mkdir(parents=True, exist_ok=True, mode=0o700)
        except OSError as error:
            raise ServeError(f"cannot make the state folder: {error.strerror}", folder) from None
        engine = create_engine(
            f"sqlite:///{folder / DATABASE_NAME}", connect_args={"check_same_thread": False}
        )
        event.listen(engine, "connect", _sqlite_pragmas)
        return cls(engine)

    def insert(
        self,
        run_id: str,
        scene: str,
        status: str,
        record: dict[str, Any],
        plan: dict[str, Any] | None,
        events: list[tuple[int, str, dict[str, Any]]],
    ) -> None:
        """Store a new run, its plan and its first events (``(seq, kind, data)``) in one transaction."""
        now = time.time()
        with Session(self.engine) as session, session.begin():
            session.add(
                RunRow(
                    id=run_id,
                    scene=scene,
                    status=status,
                    version=1,
                    created_at=now,
                    updated_at=now,
                    record=record,
                    plan=plan,
                )
            )
            session.add_all(_event_rows(run_id, events, now))

    def update(
        self,
        run_id: str,
        version: int,
        status: str,
        record: dict[str, Any],
        events: list[tuple[int, str, dict[str, Any]]],
        plan: dict[str, Any] | Unchanged | None = UNCHANGED,
    ) -> int:
        """Replace the run's record (and its plan, unless :data:`UNCHANGED`) if it is still at ``version``
        and add its new events, in one transaction; returns the new version.

        Raises
        ------
        StaleRun
            the run is no longer at ``version`` (changed elsewhere) or is gone.
        """
        now = time.time()
        params = {
            "run_id": run_id,
            "old_version": version,
            "status": status,
            "record": record,
            "version": version + 1,
            "updated_at": now,
        }
        statement = _UPDATE_RECORD
        if not isinstance(plan, Unchanged):
            statement, params["plan"] = _UPDATE_RECORD_AND_PLAN, plan
        # Core statements with bound parameters in one transaction: a pose report's write is on every
        # robot's path, and a statement built with its values would be keyed on them again each time.
        with self.engine.begin() as connection:
            done = connection.execute(statement, params)
            if done.rowcount != 1:
                raise StaleRun(f"run {run_id} changed in the database since it was read; read it again")
            if events:
                connection.execute(insert(EventRow), _event_values(run_id, events, now))
        return version + 1

    def load_all(self) -> list[StoredRun]:
        """Every run, oldest first, with its plan and the sequence number of its last event."""
        with Session(self.engine) as session:
            rows = session.scalars(select(RunRow).order_by(RunRow.created_at)).all()
            last = {
                run_id: int(seq)
                for run_id, seq in session.execute(
                    select(EventRow.run_id, func.max(EventRow.seq)).group_by(EventRow.run_id)
                ).all()
            }
            return [
                StoredRun(r.id, r.scene, r.status, r.version, r.record, r.plan, last.get(r.id, 0))
                for r in rows
            ]

    def events(self, run_id: str, after_seq: int = 0) -> list[StoredEvent]:
        """The run's events after ``after_seq``, in order."""
        with Session(self.engine) as session:
            rows = session.scalars(
                select(EventRow)
                .where(EventRow.run_id == run_id, EventRow.seq > after_seq)
                .order_by(EventRow.seq)
            ).all()
            return [StoredEvent(r.seq, r.kind, r.at, r.data) for r in rows]

    def close(self) -> None:
        self.engine.dispose()


def _event_values(
    run_id: str, events: list[tuple[int, str, dict[str, Any]]], now: float
) -> list[dict[str, Any]]:
    return [
        {"run_id": run_id, "seq": seq, "kind": kind, "at": now, "data": data} for seq, kind, data in events
    ]


def _event_rows(run_id: str, events: list[tuple[int, str, dict[str, Any]]], now: float) -> list[EventRow]:
    return [EventRow(run_id=run_id, seq=seq, kind=kind, at=now, data=data) for seq, kind, data in events]


def _sqlite_pragmas(connection: Any, _record: Any) -> None:
    cursor = connection.cursor()
    cursor.execute("PRAGMA journal_mode=WAL")
    cursor.execute("PRAGMA synchronous=NORMAL")
    cursor.execute("PRAGMA busy_timeout=5000")
    cursor.close()
