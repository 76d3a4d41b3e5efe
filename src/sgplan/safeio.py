"""One way to read every input file: size and depth limits before parsing, bounded quotes in messages.

Every reader of a user-supplied file (scene YAML / JSON, mission YAML, HOA automata, LLM cache entries,
benchmark rows) goes through this module, so that a hostile or damaged file ends in one clear
:class:`~sgplan.errors.SgplanError` naming the file, never in a hang, a traceback or a crash:

- :func:`read_bytes` / :func:`read_text` refuse a missing path, a directory or special file where a file
  is expected, a symlink loop, an unreadable file and a file larger than its cap, before reading it.
- :func:`load_yaml` parses with a safe loader that refuses duplicate keys, bounds the aliases a document
  may use and the size the document expands to (an "anchor bomb" of nine aliases per level expands to
  10^9 nodes), and bounds the nesting depth from the parser's event stream *before* the document is
  composed (libyaml's composer recurses on the C stack and crashes the interpreter on deep nesting).
- :func:`load_json` bounds the size and the nesting depth.
- :func:`quote` is the bounded ``repr`` every error message uses to show a value from a file.

The caller passes the :class:`SgplanError` subclass to raise (``SceneError``, ``MissionError`` ...), so
messages keep their ``<file>: <problem>`` shape.
"""

from __future__ import annotations

import json
import os
import re
import reprlib
import stat
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from sgplan.errors import SgplanError

MAX_FILE_BYTES = 256 * 2**20
"""Default cap of an input file (256 MiB): far above any real scene file (the largest
``building.yaml`` of the Gibson data is about 0.4 MB)."""
MAX_DEPTH = 64
"""Nesting depth allowed in a YAML or JSON document; sgplan's formats nest at most 7 levels."""
MAX_YAML_ALIASES = 1_000
"""Alias references (``*name``) allowed in one YAML document; sgplan never writes any."""
MAX_YAML_NODES = 5_000_000
"""Nodes a YAML document may expand to once its aliases are followed (the Gibson files have ~0.1 M)."""

ErrorType = Callable[..., SgplanError]
"""An :class:`SgplanError` subclass taking ``(message, path)``."""

_REPR = reprlib.Repr()
_REPR.maxstring = 60
_REPR.maxother = 60
_REPR.maxlist = _REPR.maxtuple = _REPR.maxdict = _REPR.maxset = _REPR.maxfrozenset = 6
_REPR.maxlevel = 3


def quote(value: object, limit: int = 80) -> str:
    """``repr(value)`` cut to at most ``limit`` characters, in time and memory bounded by ``limit``.

    Values from files can be huge (a long string, a list of a million items, an alias-expanded tree),
    so messages never call ``repr`` on them directly.
    """
    try:
        text = _REPR.repr(value)
    except Exception:  # noqa: BLE001 - a value whose __repr__ fails still gets a message
        text = f"<{type(value).__name__}>"
    return text if len(text) <= limit else text[: limit - 3] + "..."


def clip(text: str, limit: int = 200) -> str:
    """``text`` on one line, cut to at most ``limit`` characters (for messages quoting other messages)."""
    text = " ".join(text[: limit * 4].split())
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _describe_os_error(error: OSError) -> str:
    return error.strerror or type(error).__name__


def check_regular_file(
    path: Path, error: ErrorType, what: str = "file", max_bytes: int = MAX_FILE_BYTES
) -> int:
    """The size in bytes of ``path``, after checking it is a readable regular file of at most ``max_bytes``.

    Raises ``error(message, path)`` for a missing path, a directory, a device or FIFO (reading one may
    block forever), a symlink loop, or a file above the cap.
    """
    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise error(f"cannot read the {what}: it does not exist", path) from None
    except OSError as exc:  # ELOOP (symlink loop), EACCES on a parent, ENAMETOOLONG ...
        raise error(f"cannot open the {what}: {_describe_os_error(exc)}", path) from None
    if stat.S_ISDIR(info.st_mode):
        raise error(f"cannot read the {what}: it is a directory, not a file", path)
    if not stat.S_ISREG(info.st_mode):
        raise error(f"cannot read the {what}: it is a device, FIFO or socket, not a regular file", path)
    if info.st_size > max_bytes:
        raise error(f"{what} is {info.st_size:,} bytes, more than the {max_bytes:,} sgplan reads", path)
    return info.st_size


def read_bytes(
    path: str | Path, error: ErrorType, what: str = "file", max_bytes: int = MAX_FILE_BYTES
) -> bytes:
    """The content of ``path`` (see :func:`check_regular_file` for what is refused)."""
    path = Path(path)
    check_regular_file(path, error, what, max_bytes)
    try:
        with open(path, "rb") as stream:
            data = stream.read(max_bytes + 1)
    except OSError as exc:
        raise error(f"cannot read the {what}: {_describe_os_error(exc)}", path) from None
    if len(data) > max_bytes:  # grew while being read
        raise error(f"{what} is more than the {max_bytes:,} bytes sgplan reads", path)
    return data


def read_text(path: str | Path, error: ErrorType, what: str = "file", max_bytes: int = MAX_FILE_BYTES) -> str:
    """The UTF-8 text of ``path``; a wrong encoding names the byte offset."""
    data = read_bytes(path, error, what, max_bytes)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"{what} is not UTF-8 text (byte {exc.start}); save it as UTF-8", Path(path)) from None


# -- JSON ----------------------------------------------------------------------------------------------

_JSON_STRING = re.compile(rb'"(?:[^"\\]|\\.)*"', re.DOTALL)


def json_depth(text: str | bytes) -> int:
    """The bracket nesting depth of a JSON text (strings skipped); vectorised, linear in the size."""
    data = text.encode("utf-8", "surrogatepass") if isinstance(text, str) else text
    data = _JSON_STRING.sub(b"", data)
    codes = np.frombuffer(data, dtype=np.uint8)
    steps = (np.isin(codes, (ord("["), ord("{"))).astype(np.int32)
             - np.isin(codes, (ord("]"), ord("}"))).astype(np.int32))
    return int(np.cumsum(steps).max(initial=0))


def parse_json(
    text: str, error: ErrorType, path: Path | None, what: str = "JSON", max_depth: int = MAX_DEPTH
) -> Any:
    """``json.loads(text)`` with a depth bound; NaN and infinities are refused (not JSON)."""
    if json_depth(text) > max_depth:
        raise error(f"{what} nests deeper than {max_depth} levels", path)

    def refuse_constant(name: str) -> Any:
        raise ValueError(f"{name} is not a JSON number")

    try:
        return json.loads(text, parse_constant=refuse_constant)
    except json.JSONDecodeError as exc:
        raise error(f"invalid JSON at line {exc.lineno} column {exc.colno}: {exc.msg}", path) from None
    except (ValueError, RecursionError) as exc:
        raise error(f"invalid JSON: {clip(str(exc))}", path) from None


def load_json(path: str | Path, error: ErrorType, what: str = "JSON file", max_bytes: int = MAX_FILE_BYTES,
              max_depth: int = MAX_DEPTH) -> Any:
    """The JSON document in ``path``, read within the size cap and parsed within the depth bound."""
    path = Path(path)
    return parse_json(read_text(path, error, what, max_bytes), error, path, what, max_depth)


# -- YAML ----------------------------------------------------------------------------------------------


class YamlLimitError(yaml.YAMLError):
    """A YAML document breaks one of this module's limits (duplicate key, aliases, size, depth)."""


def _bounded_construct(loader: Any, node: yaml.Node) -> None:
    """Check the composed document before anything is built: aliases, expanded size, depth, duplicates.

    Walks the node graph once, iteratively; a node reached again is an alias (the composer shares the
    anchored node). The expanded size counts a shared subtree once per reference, which is what anything
    walking the built value (a message, a copy, a loop) would pay.
    """
    expanded: dict[int, int] = {}
    aliases = 0
    # Frames: (node, depth, children pending?)
    stack: list[tuple[yaml.Node, int, bool]] = [(node, 1, True)]
    on_path: set[int] = set()
    while stack:
        current, depth, entering = stack.pop()
        ident = id(current)
        if not entering:
            on_path.discard(ident)
            expanded[ident] = 1 + sum(expanded[id(c)] for c in _children(current))
            if expanded[ident] > MAX_YAML_NODES:
                raise YamlLimitError(
                    f"the document expands to more than {MAX_YAML_NODES:,} nodes (an alias bomb?)"
                )
            continue
        if ident in expanded or ident in on_path:
            aliases += 1
            if aliases > MAX_YAML_ALIASES:
                raise YamlLimitError(f"the document uses more than {MAX_YAML_ALIASES:,} aliases")
            if ident in on_path:
                raise YamlLimitError("the document refers to itself (a recursive alias)")
            continue
        if depth > MAX_DEPTH and not isinstance(
            current, yaml.ScalarNode
        ):  # collections count, as in the events
            mark = current.start_mark
            raise YamlLimitError(f"nesting deeper than {MAX_DEPTH} levels at line {mark.line + 1}")
        if isinstance(current, yaml.MappingNode):
            _check_duplicate_keys(loader, current)
        on_path.add(ident)
        stack.append((current, depth, False))
        for child in _children(current):
            stack.append((child, depth + 1, True))


def _children(node: yaml.Node) -> list[yaml.Node]:
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    if isinstance(node, yaml.MappingNode):
        return [item for pair in node.value for item in pair]
    return []


def _check_duplicate_keys(loader: Any, node: yaml.MappingNode) -> None:
    seen: set[tuple[str, str]] = set()
    for key_node, _ in node.value:
        if not isinstance(key_node, yaml.ScalarNode):
            continue
        # Resolved scalars: `1` and `"1"` differ, `1` and `01`... are compared by their constructed value.
        try:
            key = (key_node.tag, repr(loader.construct_object(key_node)))
        except yaml.YAMLError:
            key = (key_node.tag, key_node.value)
        if key in seen:
            mark = key_node.start_mark
            raise YamlLimitError(
                f"duplicate key {quote(key_node.value)} at line {mark.line + 1} (a key may appear once per "
                "mapping)"
            )
        seen.add(key)


class _LimitsMixin:
    def construct_document(self, node: yaml.Node) -> Any:
        _bounded_construct(self, node)
        return super().construct_document(node)  # type: ignore[misc]


class SafeLimitedLoader(_LimitsMixin, yaml.SafeLoader):
    """PyYAML's pure-Python safe loader with this module's limits; its recursion is in Python."""


_CLoader: Any = getattr(yaml, "CSafeLoader", None)
if _CLoader is not None:

    class CSafeLimitedLoader(_LimitsMixin, _CLoader):
        """libyaml's safe loader with this module's limits (only for documents shallow enough)."""

    _FAST_LOADER: Any = CSafeLimitedLoader
else:  # pragma: no cover - PyYAML built without libyaml
    _FAST_LOADER = SafeLimitedLoader


def _check_events(text: str, loader: Any) -> None:
    """Walk the parser's event stream (libyaml's parser is iterative) to bound depth and aliases before
    the document is composed: libyaml's composer recurses on the C stack and would crash on deep nesting."""
    depth = aliases = 0
    for event in yaml.parse(text, Loader=loader):
        if isinstance(event, (yaml.SequenceStartEvent, yaml.MappingStartEvent)):
            depth += 1
            if depth > MAX_DEPTH:
                mark = event.start_mark
                where = f" at line {mark.line + 1}" if mark is not None else ""
                raise YamlLimitError(f"nesting deeper than {MAX_DEPTH} levels{where}")
        elif isinstance(event, (yaml.SequenceEndEvent, yaml.MappingEndEvent)):
            depth -= 1
        elif isinstance(event, yaml.AliasEvent):
            aliases += 1
            if aliases > MAX_YAML_ALIASES:
                raise YamlLimitError(f"the document uses more than {MAX_YAML_ALIASES:,} aliases")


def parse_yaml(text: str, error: ErrorType, path: Path | None, what: str = "YAML") -> Any:
    """The YAML document ``text`` (safe types only) within this module's limits; see the module docstring."""
    try:
        _check_events(text, _FAST_LOADER)
        return yaml.load(text, Loader=_FAST_LOADER)  # a SafeLoader subclass
    except RecursionError:
        raise error(f"{what} nests deeper than {MAX_DEPTH} levels", path) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or (str(exc).splitlines() or [type(exc).__name__])[0]
        raise error(f"invalid YAML{where}: {clip(str(problem))}", path) from None


def load_yaml(
    path: str | Path, error: ErrorType, what: str = "YAML file", max_bytes: int = MAX_FILE_BYTES
) -> Any:
    """The YAML document in ``path``, read and parsed within this module's limits."""
    path = Path(path)
    return parse_yaml(read_text(path, error, what, max_bytes), error, path, what)
