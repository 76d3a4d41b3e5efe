"""Typed, validated access to the mappings of a scene file (YAML, JSON or an unpickled dict).

Every loader reads its nodes through :class:`Fields`, so a bad value anywhere gives one
:class:`~sgplan.errors.SceneError` that names the file, the entity (``room 7``) and the field
(``location``) instead of a ``KeyError`` or ``TypeError`` deep inside the loader.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from sgplan.errors import SceneError
from sgplan.safeio import quote

_MISSING: Any = object()


def is_int(value: object) -> bool:
    """True for Python and numpy integers, False for ``bool`` (YAML ``yes`` must not pass as 1)."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def is_number(value: object) -> bool:
    """True for Python and numpy integers and floats (not ``bool``)."""
    return is_int(value) or isinstance(value, (float, np.floating))


class Fields:
    """One mapping of a scene file, read field by field.

    Parameters
    ----------
    data:
        The mapping; anything else raises :class:`SceneError` naming ``entity``.
    path:
        The file it came from (prefixed to every error message).
    entity:
        What the mapping describes, e.g. ``"room 7 (floor 1)"``.
    """

    def __init__(self, data: object, path: Path | None, entity: str) -> None:
        if not isinstance(data, Mapping):
            raise SceneError(f"{entity} must be a mapping, got {type(data).__name__}", path)
        self.data = data
        self.path = path
        self.entity = entity

    def error(self, message: str) -> SceneError:
        """A :class:`SceneError` about this entity in this file."""
        return SceneError(f"{self.entity}: {message}", self.path)

    def has(self, key: str) -> bool:
        return key in self.data

    def raw(self, key: str, default: Any = _MISSING) -> Any:
        """The value of ``key`` as stored; a missing required field raises :class:`SceneError`."""
        if key in self.data:
            return self.data[key]
        if default is _MISSING:
            raise self.error(f"missing field {key!r}")
        return default

    def integer(self, key: str, default: Any = _MISSING) -> int:
        value = self.raw(key, default)
        if not is_int(value):
            raise self.error(f"field {key!r} must be an integer, got {quote(value)}")
        return int(value)

    def number(self, key: str, default: Any = _MISSING) -> float:
        """A finite number (int or float, Python or numpy, or a 0-d array)."""
        value = self.raw(key, default)
        if isinstance(value, np.ndarray) and value.shape == ():
            value = value.item()
        if not is_number(value) or not math.isfinite(value):
            raise self.error(f"field {key!r} must be a finite number, got {quote(value)}")
        return float(value)

    def text(self, key: str, default: Any = _MISSING) -> str:
        value = self.raw(key, default)
        if not isinstance(value, str):
            raise self.error(f"field {key!r} must be a string, got {quote(value)}")
        return value

    def vector(self, key: str, length: int) -> np.ndarray:
        """A list (or array) of ``length`` finite numbers as a float64 array."""
        value = self.raw(key)
        items = value.tolist() if isinstance(value, np.ndarray) else value
        if (
            not isinstance(items, (list, tuple))
            or len(items) != length
            or not all(is_number(v) and math.isfinite(v) for v in items)
        ):
            raise self.error(f"field {key!r} must be a list of {length} finite numbers, got {quote(value)}")
        return np.array(items, dtype=np.float64)

    def int_list(self, key: str, length: int | None = None, *, allow_null: bool = False) -> list[int]:
        """A list of integers (of ``length`` items if given); ``null`` reads as ``[]`` if allowed."""
        value = self.raw(key)
        if value is None and allow_null:
            return []
        if (
            not isinstance(value, (list, tuple))
            or (length is not None and len(value) != length)
            or not all(is_int(v) for v in value)
        ):
            size = f"{length} " if length is not None else ""
            raise self.error(f"field {key!r} must be a list of {size}integers, got {quote(value)}")
        return [int(v) for v in value]

    def cell(self, key: str) -> tuple[int, int]:
        """A ``[row, col]`` pair of integers."""
        row, col = self.int_list(key, 2)
        return (row, col)

    def strings(self, key: str) -> tuple[str, ...]:
        """A list of strings; ``null`` or a missing field reads as ``()``."""
        value = self.raw(key, None)
        if value is None:
            return ()
        if not isinstance(value, (list, tuple)) or not all(isinstance(v, str) for v in value):
            raise self.error(f"field {key!r} must be a list of strings, got {quote(value)}")
        return tuple(value)

    def mapping(self, key: str, *, allow_null: bool = True) -> Mapping[Any, Any]:
        """A nested mapping; ``null`` or ``{}`` reads as empty when ``allow_null``."""
        value = self.raw(key)
        if value is None and allow_null:
            return {}
        if not isinstance(value, Mapping):
            raise self.error(f"field {key!r} must be a mapping, got {type(value).__name__}")
        return value
