"""Valid inputs of every format, and helpers to damage fresh copies of them (one per fault case)."""

from __future__ import annotations

import io
import pickle
import shutil
import tempfile
import zipfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np

MISSION_FORMULA = 'F ("reach(object_32)" & F "enter(room_7)")'
"""A demo-building mission: the teddy bear upstairs, then the dining room."""


def scene_graph_dict() -> dict:
    """A small scene-graph dict in the Gibson npz layout (two rooms, one object)."""
    room = {
        "id": 1, "floor_number": "A", "scene_category": "kitchen", "location": np.zeros(3),
        "size": np.ones(3),
    }
    return {
        "building": {"id": 1, "name": "Tiny"},
        "room": {1: room, 2: {**room, "id": 2, "scene_category": "bathroom"}},
        "object": {
            3: {
                "id": 3, "parent_room": 1, "class_": "sink", "location": np.zeros(3), "size": np.ones(3),
                "action_affordance": ["wash"],
            }
        },
        "camera": {},
        "panorama": {},
    }


def write_npz(path: Path, value: object, protocol: int = 2) -> None:
    """Store ``value`` as the pickled 0-d object array ``output`` of an npz, as the Gibson files do."""
    array = np.empty((), dtype=object)
    array[()] = value
    pickled_npz(path, pickle.dumps(array, protocol=protocol))


def pickled_npz(path: Path, pickle_bytes: bytes) -> None:
    """An npz whose ``output.npy`` holds the raw ``pickle_bytes`` after a 0-d object-array header."""
    buffer = io.BytesIO()
    np.lib.format.write_array_header_1_0(buffer, {"descr": "|O", "fortran_order": False, "shape": ()})
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("output.npy", buffer.getvalue() + pickle_bytes)


@contextmanager
def fresh_copy(template: Path) -> Iterator[Path]:
    """A throw-away copy of ``template`` (a folder or a file), for one generated example."""
    with tempfile.TemporaryDirectory(prefix="sgplan-fault-") as tmp:
        target = Path(tmp) / template.name
        if template.is_dir():
            shutil.copytree(template, target)
        else:
            shutil.copy2(template, target)
        yield target
