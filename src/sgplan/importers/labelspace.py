"""Label files: the names of the integer semantic labels in a Hydra scene graph.

Three shapes are read:

- Hydra's label-space YAML (``config/label_spaces/*.yaml``): a ``label_names`` list of
  ``{label: 5, name: chair}``;
- a plain YAML mapping ``{5: chair, 16: table}``, or one with ``objects:`` and ``rooms:`` sections of
  that shape (rooms are named by the room nodes' labels; without a rooms section rooms are "room");
- a CSV file of ``id,name`` lines (a header line is skipped).

Names are lower-cased, with ``_`` read as a space for objects and spaces as ``_`` for rooms (the
Gibson conventions the translator knows: ``dining table``, ``living_room``).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from sgplan.errors import SceneError
from sgplan.scene.fields import is_int


@dataclass(frozen=True)
class LabelMap:
    """Integer label -> object name (and room name), read from ``path``."""

    path: Path
    objects: dict[int, str]
    rooms: dict[int, str] = field(default_factory=dict)

    def object_name(self, label: int) -> str | None:
        name = self.objects.get(label)
        return None if name is None else name.replace("_", " ")

    def room_name(self, label: int) -> str:
        return self.rooms.get(label, "room").replace(" ", "_")


def read_label_map(path: str | Path) -> LabelMap:
    """Read a label file in any of the shapes of the module docstring.

    Raises
    ------
    SceneError
        for a missing or unreadable file, or one in none of those shapes (naming the bad entry).
    """
    path = Path(path).expanduser()
    if not path.is_file():
        raise SceneError("label file does not exist", path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise SceneError(f"cannot read the label file: {error}", path) from None
    if path.suffix.lower() == ".csv":
        return LabelMap(path, _csv(text, path))
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as error:
        raise SceneError(f"the label file is not valid YAML: {error}", path) from None
    if isinstance(data, dict) and "label_names" in data:
        return LabelMap(path, _hydra(data["label_names"], path))
    if isinstance(data, dict) and ("objects" in data or "rooms" in data):
        return LabelMap(
            path,
            _mapping(data.get("objects") or {}, path, "objects"),
            _mapping(data.get("rooms") or {}, path, "rooms"),
        )
    if isinstance(data, dict):
        return LabelMap(path, _mapping(data, path, "labels"))
    raise SceneError(
        "a label file is Hydra's label-space YAML (label_names: [{label, name}]), a YAML mapping id -> name, "
        "or a CSV of id,name lines",
        path,
    )


def _name(value: Any, where: str, path: Path) -> str:
    if not isinstance(value, str) or not value.strip():
        raise SceneError(f"{where}: the name must be a non-empty string, got {value!r}", path)
    return value.strip().lower()


def _hydra(entries: Any, path: Path) -> dict[int, str]:
    if not isinstance(entries, list):
        raise SceneError("'label_names' must be a list of {label: N, name: TEXT}", path)
    names = {}
    for k, entry in enumerate(entries):
        if not isinstance(entry, dict) or not is_int(entry.get("label")):
            raise SceneError(f"label_names entry {k}: needs an integer 'label' and a 'name'", path)
        names[int(entry["label"])] = _name(entry.get("name"), f"label_names entry {k}", path)
    return names


def _mapping(data: Any, path: Path, section: str) -> dict[int, str]:
    if not isinstance(data, dict):
        raise SceneError(f"'{section}' must be a mapping id -> name", path)
    names = {}
    for key, value in data.items():
        if not is_int(key):
            raise SceneError(f"{section}: key {key!r} is not an integer label", path)
        names[int(key)] = _name(value, f"{section}: label {key}", path)
    return names


def _csv(text: str, path: Path) -> dict[int, str]:
    names = {}
    for number, row in enumerate(csv.reader(text.splitlines()), start=1):
        if not row or not "".join(row).strip():
            continue
        if len(row) < 2:
            raise SceneError(f"line {number}: expected id,name", path)
        key = row[0].strip()
        if not key.lstrip("-").isdigit():
            if number == 1:
                continue  # a header
            raise SceneError(f"line {number}: {key!r} is not an integer label", path)
        names[int(key)] = _name(row[1], f"line {number}", path)
    if not names:
        raise SceneError("the CSV label file holds no id,name line", path)
    return names
