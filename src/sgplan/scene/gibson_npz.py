"""Reader of the raw 3D Scene Graph file ``3DSceneGraph_<Scene>.npz`` (graph only, no rasters).

The file is a zip holding one ``output.npy``: a 0-d object array whose pickle carries a dict with keys
``building``, ``room``, ``object``, ``camera``, ``panorama`` (reference-algorithm.md §1.6). Unpickling
runs code named by the file, so ``np.load(allow_pickle=True)`` would execute whatever a crafted file asks
for. :func:`read_scene_graph_dict` instead unpickles with :class:`RestrictedUnpickler`, which resolves only
the numpy array / dtype / scalar reconstructors and a few inert builtins, and rejects any other global
with a :class:`~sgplan.errors.SceneError` naming it.

:func:`load_gibson_npz` turns the dict into a :class:`~sgplan.scene.model.Building` whose floors have no
rasters (see :attr:`Floor.has_maps`): enough for grounding and the attribute hierarchy. uuids are
assigned exactly as the authors' converter does, so they equal those of the authors' ``building.yaml``.

Cost: the Gibson files are 0.46 GB of pickle once decompressed, mostly camera records that sgplan does
not use; reading stops once the building, room and object items are complete (they come first), so a
file is read in well under a second with a small memory footprint.
"""

from __future__ import annotations

import builtins
import codecs
import pickle
import zipfile
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any, cast

import numpy as np
from numpy.lib import format as npy_format

from sgplan.errors import SceneError
from sgplan.safeio import check_regular_file, clip, quote
from sgplan.scene.fields import Fields
from sgplan.scene.model import Building, Floor, Room, SceneObject

ARRAY_KEY = "output"
"""The one member of the npz (``output.npy``)."""
MAX_PICKLE_NESTING = 256
"""Open MARKs (nested tuples, lists, dicts being filled) the unpickler admits; Gibson files use < 10."""
MAX_PICKLE_STACK = 100_000
"""Items the unpickler's stack may hold at once (containers nested without MARKs count here)."""


def _reconstruct(subtype: type, shape: Any, dtype: Any) -> np.ndarray:
    # numpy's pickles call this with subtype = ndarray; any other class would be a way to build objects.
    if subtype is not np.ndarray:
        raise pickle.UnpicklingError(f"array reconstruction of a non-ndarray type {subtype!r}")
    return _NUMPY_RECONSTRUCT(subtype, shape, dtype)


def _latin1_encode(text: Any, encoding: str = "utf-8") -> bytes:
    # Protocol-2 pickles spell raw bytes as _codecs.encode(str, "latin1"); other codecs are not needed
    # and some (zlib, bz2) would let a file decompress arbitrary amounts of data.
    if not isinstance(text, str) or codecs.lookup(encoding).name != "iso8859-1":
        raise pickle.UnpicklingError(f"_codecs.encode is only admitted for latin1 text, got {encoding!r}")
    return text.encode("latin1")


# The reconstructors numpy's own pickles name, whatever module they live in for this numpy version.
_NUMPY_RECONSTRUCT = cast(Callable[..., np.ndarray], np.zeros(1).__reduce__()[0])
_NUMPY_SCALAR = cast(Callable[..., Any], np.float64(0).__reduce__()[0])
_NUMPY_FROMBUFFER = cast(Callable[..., Any], np.zeros(1).__reduce_ex__(5)[0])

# numpy < 2 pickles name numpy.core.*, numpy >= 2 numpy._core.*.
_MULTIARRAY = ("numpy.core.multiarray", "numpy._core.multiarray")
_NUMERIC = ("numpy.core.numeric", "numpy._core.numeric")
_ALLOWED: dict[tuple[str, str], Any] = {
    **{(module, "_reconstruct"): _reconstruct for module in _MULTIARRAY},
    **{(module, "scalar"): _NUMPY_SCALAR for module in _MULTIARRAY},
    **{(module, "_frombuffer"): _NUMPY_FROMBUFFER for module in _NUMERIC},
    ("numpy", "ndarray"): np.ndarray,
    ("numpy", "dtype"): np.dtype,
    ("_codecs", "encode"): _latin1_encode,
    **{("builtins", name): getattr(builtins, name) for name in ("set", "frozenset", "complex", "bytearray")},
}


class ForbiddenGlobal(pickle.UnpicklingError):
    """The pickle names a global outside the admitted numpy / builtin set."""

    def __init__(self, module: str, name: str) -> None:
        self.qualified_name = f"{module}.{name}"
        super().__init__(self.qualified_name)


class RestrictedUnpickler(pickle._Unpickler):
    """An unpickler that builds only numpy arrays, dtypes, numpy scalars and builtin containers/scalars.

    Any other global (``os.system``, ``builtins.eval``, ...) raises :class:`ForbiddenGlobal` before it is
    looked up, so nothing outside the admitted set is ever imported or called.

    It is the pure-Python unpickler (``pickle._Unpickler``) so that :class:`_KeysUnpickler` can watch
    the stack and stop reading early; unpickling the graph part of a Gibson file this way is fast.
    """

    dispatch = dict(pickle._Unpickler.dispatch)  # noqa: RUF012 - the class's own copy, hooked below
    # Set by the pure-Python unpickler's load(): the items read since the last MARK, and the outer ones.
    stack: list[Any]
    metastack: list[list[Any]]

    def find_class(self, module: str, name: str) -> Any:
        try:
            return _ALLOWED[(module, name)]
        except KeyError:
            raise ForbiddenGlobal(module, name) from None

    def _check_depth(self) -> None:
        # The unpickler itself is iterative, but what it builds is walked by recursive code later
        # (repr, comparisons); nesting shows as open MARKs (metastack) or containers left on the stack.
        if len(self.metastack) > MAX_PICKLE_NESTING or len(self.stack) > MAX_PICKLE_STACK:
            raise pickle.UnpicklingError(
                f"the pickle nests deeper than {MAX_PICKLE_NESTING} levels or holds more than "
                f"{MAX_PICKLE_STACK:,} open items"
            )

    for _opcode in (pickle.MARK, pickle.EMPTY_LIST, pickle.EMPTY_DICT, pickle.EMPTY_SET, pickle.EMPTY_TUPLE):
        def _bounded(self: RestrictedUnpickler, _load: Callable[..., None] = dispatch[_opcode[0]]) -> None:
            _load(self)
            self._check_depth()

        dispatch[_opcode[0]] = _bounded  # type: ignore[assignment]  # only called on this class's instances
    del _opcode, _bounded


class _KeysFound(Exception):
    """Raised by :class:`_KeysUnpickler` to stop reading once the wanted items are complete."""

    def __init__(self, items: dict[str, Any]) -> None:
        super().__init__()
        self.items = items


class _KeysUnpickler(RestrictedUnpickler):
    """Stops as soon as the items of ``keys`` of a dict being unpickled are complete.

    A pickled dict is ``MARK key value key value ... SETITEMS``: when a string is pushed while the items
    read so far (the stack since the last MARK) already hold every wanted key with its value, those values
    are complete and everything after them (the Gibson files' 0.4 GB of camera records) is never read.
    If the keys come last, the whole pickle is read as usual.
    """

    dispatch = dict(RestrictedUnpickler.dispatch)  # noqa: RUF012 - the class's own copy, hooked below

    def __init__(self, stream: IO[bytes], keys: frozenset[str]) -> None:
        super().__init__(stream, encoding="latin1")
        self.wanted = keys

    def _after_string_push(self) -> None:
        stack = self.stack
        # stack = [k1, v1, ..., kn, vn, new_key]; cheap length test first, it runs on every string.
        if len(stack) > 2 * len(self.wanted) and len(stack) % 2 == 1 and isinstance(stack[-1], str):
            items = dict(zip(stack[0:-1:2], stack[1:-1:2]))
            if self.wanted <= items.keys() and all(isinstance(k, str) for k in items):
                raise _KeysFound({key: items[key] for key in self.wanted})

    for _opcode in (
        pickle.BINUNICODE, pickle.SHORT_BINUNICODE, pickle.BINUNICODE8, pickle.UNICODE,
        pickle.BINGET, pickle.LONG_BINGET, pickle.GET,
    ):
        def _hooked(self: _KeysUnpickler, _load: Callable[..., None] = dispatch[_opcode[0]]) -> None:
            _load(self)
            self._after_string_push()

        dispatch[_opcode[0]] = _hooked  # type: ignore[assignment]  # only called on this class's instances
    del _opcode, _hooked


SCENE_GRAPH_KEYS = ("building", "room", "object")
"""The items of the npz dict sgplan uses (``camera`` and ``panorama`` are not)."""


def read_scene_graph_dict(
    path: str | Path, keys: tuple[str, ...] | None = SCENE_GRAPH_KEYS
) -> dict[str, Any]:
    """The dict stored under ``output`` in a 3D Scene Graph npz, unpickled safely.

    Parameters
    ----------
    path:
        The ``.npz`` file.
    keys:
        The items to return (reading stops once they are complete); ``None`` reads and returns them all.

    Raises
    ------
    SceneError
        The file does not exist, is not a zip / npz (or is truncated), has no ``output`` array, is not a
        pickled dict, lacks one of ``keys``, or its pickle names a forbidden global (the message names it).
    """
    path = Path(path).expanduser()
    check_regular_file(path, SceneError, "raw scene graph file")
    member = f"{ARRAY_KEY}.npy"
    try:
        with zipfile.ZipFile(path) as archive:
            if member not in archive.namelist():
                raise SceneError(
                    f"npz has no {ARRAY_KEY!r} array (members: {quote(archive.namelist())})", path
                )
            with archive.open(member) as stream:
                value = _unpickle_npy(stream, frozenset(keys) if keys is not None else None)
    except ForbiddenGlobal as error:
        raise SceneError(
            f"refusing to unpickle: the file references {error.qualified_name}, which is not a numpy or "
            "builtin data type (the file may be malicious)",
            path,
        ) from None
    except SceneError:
        raise
    except (zipfile.BadZipFile, zlib.error, EOFError, OSError) as error:
        raise SceneError(f"not a readable npz (corrupt or truncated): {clip(str(error))}", path) from None
    except (
        pickle.UnpicklingError, ValueError, TypeError, AttributeError, IndexError, KeyError, RecursionError,
    ) as error:
        raise SceneError(f"corrupt pickle in {member}: {clip(str(error))}", path) from None
    except MemoryError:
        raise SceneError(f"{member} asks for more memory than is available", path) from None
    if not isinstance(value, dict):
        raise SceneError(f"{ARRAY_KEY!r} holds a {type(value).__name__}, expected a pickled dict", path)
    if keys is None:
        return value
    missing = [key for key in keys if key not in value]
    if missing:
        raise SceneError(f"the scene-graph dict has no {missing} item(s) (it has {quote(list(value))})", path)
    return {key: value[key] for key in keys}


def _unpickle_npy(stream: IO[bytes], keys: frozenset[str] | None) -> Any:
    """The object stored in a 0-d object ``.npy`` stream (header, then a pickle of the array).

    With ``keys``, reading may stop early and return a dict holding just those items.
    """
    version = npy_format.read_magic(stream)
    if version == (1, 0):
        shape, _, dtype = npy_format.read_array_header_1_0(stream)
    else:
        shape, _, dtype = npy_format.read_array_header_2_0(stream)
    if not dtype.hasobject or shape != ():
        raise pickle.UnpicklingError(
            f"expected a 0-d object array holding a pickled dict, got dtype {dtype} and shape {shape}"
        )
    unpickler = _KeysUnpickler(stream, keys) if keys else RestrictedUnpickler(stream, encoding="latin1")
    try:
        array = unpickler.load()
    except _KeysFound as found:
        return found.items
    if not isinstance(array, np.ndarray) or array.shape != ():
        raise pickle.UnpicklingError("expected a 0-d object array holding the scene-graph dict")
    return array.item()


def load_gibson_npz(path: str | Path) -> Building:
    """A :class:`Building` (graph only, no rasters) from a raw ``3DSceneGraph_<Scene>.npz``.

    Floors are the distinct ``floor_number`` letters of the rooms in alphabetical order ('A' = floor 0).
    uuids follow the authors: building 1; then, walking the rooms in file order, each room takes the next
    uuid and a floor takes the next one right after its first room; then the objects in file order.
    Rooms have no connections or doors and all grid boxes are ``(0, 0)``; see :attr:`Floor.has_maps`.

    Raises
    ------
    SceneError
        Unreadable or unsafe file (see :func:`read_scene_graph_dict`), a missing or mistyped field, an
        object whose ``parent_room`` is not a room of the file. The message names the room or object.
    """
    path = Path(path).expanduser()
    data = Fields(read_scene_graph_dict(path, SCENE_GRAPH_KEYS), path, "scene graph")
    building = Fields(data.raw("building"), path, "building")
    rooms = data.mapping("room")
    objects = data.mapping("object")

    next_uuid = 2
    floor_uuid: dict[str, int] = {}
    room_records: list[tuple[Fields, object, int, str]] = []
    for key, record in rooms.items():
        fields = Fields(record, path, f"room {key}")
        letter = fields.text("floor_number")
        if len(letter) != 1 or not letter.isalpha():
            raise fields.error(f"field 'floor_number' must be one floor letter, got {quote(letter)}")
        room_uuid = next_uuid
        next_uuid += 1
        if letter not in floor_uuid:
            floor_uuid[letter] = next_uuid
            next_uuid += 1
        room_records.append((fields, key, room_uuid, letter))

    letters = sorted(floor_uuid)
    floors = [_bare_floor(index, letter, floor_uuid[letter]) for index, letter in enumerate(letters)]
    room_by_id: dict[int, Room] = {}
    for fields, key, room_uuid, letter in room_records:
        room = Room(
            id=_node_id(fields, key),
            uuid=room_uuid,
            name=fields.text("scene_category"),
            floor=letters.index(letter),
            location_m=fields.vector("location", 3),
            size_m=fields.vector("size", 3),
            grid_min=(0, 0),
            grid_max=(0, 0),
        )
        floors[room.floor].rooms[room.id] = room
        room_by_id[room.id] = room

    for key, record in objects.items():
        fields = Fields(record, path, f"object {key}")
        parent = fields.integer("parent_room")
        if parent not in room_by_id:
            raise fields.error(f"parent_room {parent} is not a room of the file")
        room = room_by_id[parent]
        obj = SceneObject(
            id=_node_id(fields, key),
            uuid=next_uuid,
            name=fields.text("class_"),
            room_id=room.id,
            room_uuid=room.uuid,
            location_m=fields.vector("location", 3),
            size_m=fields.vector("size", 3),
            grid_min=(0, 0),
            grid_max=(0, 0),
            action_affordance=fields.strings("action_affordance"),
        )
        next_uuid += 1
        room.objects[obj.id] = obj

    name = building.text("name")
    building_id = building.integer("id")
    try:
        return Building(id=building_id, uuid=1, name=name, floors=floors, source=path)
    except SceneError as error:  # the model's uniqueness checks know no file
        raise SceneError(str(error), path) from None


def is_gibson_npz(path: str | Path) -> bool:
    """True if ``path`` is a file ending in ``.npz`` (its content is checked when it is read)."""
    path = Path(path)
    return path.is_file() and path.suffix == ".npz"


def _node_id(fields: Fields, key: object) -> int:
    node_id = fields.integer("id")
    if node_id != key or node_id <= 0:
        raise fields.error(f"field 'id' is {node_id} but the node is keyed {quote(key)} (ids are positive)")
    return node_id


def _bare_floor(index: int, letter: str, uuid: int) -> Floor:
    """A floor without rasters or grid frame (``has_maps`` is False)."""
    empty = np.zeros((0, 0), np.int16)
    return Floor(
        index=index,
        name=letter,
        uuid=uuid,
        origin_m=(0.0, 0.0),
        resolution_m=(0.0, 0.0),
        ground_z_m=float("nan"),
        cat_map=empty,
        room_map=empty.copy(),
    )

