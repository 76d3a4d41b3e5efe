"""The sgplan exception family.

Every error a user can cause (bad files, bad formulas, unreachable goals, a misbehaving LLM) is raised as
a subclass of :class:`SgplanError`. Its message is one or two sentences that name the file, field or
entity at fault and, where there is one, what to do about it. The CLI prints ``str(error)`` and exits
with the error's ``exit_code`` (2; 4 for a mission no path in the scene can satisfy); it never shows a
traceback for these. (Exit code 3 is a search budget that ran out, 70 a bug in sgplan.)
"""

from __future__ import annotations

from pathlib import Path


class SgplanError(Exception):
    """Base class of every error sgplan raises on purpose."""

    exit_code = 2
    """The CLI's exit status for this error."""


class SceneError(SgplanError):
    """A scene (building, floors, rooms, objects, maps) is missing, malformed or inconsistent.

    Parameters
    ----------
    message:
        What is wrong, naming the entity or field.
    path:
        The file the problem was found in, if any; it is prefixed to the message.
    """

    def __init__(self, message: str, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        super().__init__(f"{self.path}: {message}" if self.path is not None else message)


class FormulaError(SgplanError):
    """An LTL formula (infix, prefix string or LLM token list) cannot be parsed or is unsupported.

    ``position`` is the 0-based token index (token lists) or character offset (strings) of the fault,
    or ``None`` when the fault is the input as a whole (e.g. empty input).
    """

    def __init__(self, message: str, position: int | None = None) -> None:
        self.position = position
        super().__init__(message)


class AutomatonError(SgplanError):
    """An automaton cannot be built (too large) or read (HOA syntax, unsupported acceptance)."""

    def __init__(self, message: str, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        super().__init__(f"{self.path}: {message}" if self.path is not None else message)


class MissionError(SgplanError):
    """A mission (folder, propositions, guidance) is malformed or does not fit the scene."""

    def __init__(self, message: str, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        super().__init__(f"{self.path}: {message}" if self.path is not None else message)


class PlanningError(SgplanError):
    """Planning cannot start or cannot succeed.

    ``status`` is the machine-readable outcome reported in JSON results: ``"invalid-start"`` (the start
    cell is not free, or its label already violates the mission), ``"infeasible"`` (no path from this
    start satisfies the mission), ``"unsatisfiable"`` (no path anywhere in the scene can, see
    :class:`UnsatisfiableMissionError`), or ``"error"`` for anything else.
    """

    def __init__(self, message: str, status: str = "error") -> None:
        self.status = status
        super().__init__(message)


class UnsatisfiableMissionError(PlanningError):
    """No path in this scene, from any start, satisfies the mission (e.g. "go to the kitchen; never enter
    the kitchen", or an object to reach from a room its reach does not cover). Status
    ``"unsatisfiable"``, CLI exit code 4, so scripts tell it from a bad start (exit code 2)."""

    exit_code = 4

    def __init__(self, message: str) -> None:
        super().__init__(message, status="unsatisfiable")


class SceneMismatchError(MissionError):
    """A mission folder was made for another scene (its recorded scene, or the categories and floors of
    the entities it names, differ from the scene given); ``--force`` plans it anyway."""


class ConfirmationError(SgplanError):
    """``--confirm`` could not ask (no terminal), or the user did not confirm the mission."""


class LLMError(SgplanError):
    """The language-model backend failed (network, protocol, cache miss in replay mode, bad replies)."""


class OutputError(SgplanError):
    """A result file (JSON, waypoints CSV, ROS path YAML, drawing) cannot be written."""


class TrajectoryError(SgplanError):
    """A trajectory (the poses a robot drove) cannot be read or monitored: a malformed file, a pose that is
    not a number, off the grid or on a floor the scene lacks, a floor change with no stairs.

    Parameters
    ----------
    message:
        What is wrong, naming the pose (``pose 12``) or the field.
    path, line:
        The file and its 1-based line, if any; prefixed to the message (``w.csv: line 14: ...``).
    """

    def __init__(self, message: str, path: str | Path | None = None, line: int | None = None) -> None:
        self.path = Path(path) if path is not None else None
        self.line = line
        where = [str(self.path)] if self.path is not None else []
        where += [f"line {line}"] if line is not None else []
        super().__init__(": ".join([*where, message]))


class MissionViolatedError(PlanningError):
    """What a robot already did breaks the mission: no continuation can satisfy it (``plan --after`` a
    trajectory that entered a forbidden room). Status ``"violated"``, CLI exit code 6, as ``sgplan
    monitor`` gives for a violated trajectory."""

    exit_code = 6

    def __init__(self, message: str) -> None:
        super().__init__(message, status="violated")
