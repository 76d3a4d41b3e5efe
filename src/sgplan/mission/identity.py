"""Mission <-> scene identity: which scene a mission folder was made for, and whether it fits another.

Every mission folder sgplan writes holds ``scene.yaml``::

    format: sgplan-scene-identity/1
    scene: Allensville                 # the building's name
    graph_sha256: 3f5c...              # content hash of the scene graph (see scene_graph_hash)
    entities:                          # every entity the mission's propositions name
      room_11: {category: kitchen, floor: 0}
      object_21: {category: vase, floor: 0, room: room_10}

:func:`check_folder_scene` compares a folder with the scene it is about to be planned on: through
``scene.yaml`` when present, else through the authors' ``building_desc.yaml`` (the hierarchy their
prompts used, which names each room's and object's category and floor), else it cannot tell.
Ids are per scene, so ``room_11`` of one building is usually some other room of another: a folder
planned on the wrong building would give an optimal plan of the wrong mission.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from sgplan.errors import MissionError, SceneMismatchError
from sgplan.safeio import load_yaml
from sgplan.scene.labels import Proposition
from sgplan.scene.model import Building, category_words

SCENE_RECORD_NAME = "scene.yaml"
FORMAT = "sgplan-scene-identity/1"


def scene_graph_hash(building: Building) -> str:
    """SHA-256 (hex) of the scene graph: floors, rooms (id, uuid, category, floor, connections) and
    objects (id, uuid, category, room), in a canonical order. The rasters are not hashed: the graph is
    what missions refer to."""
    graph = [
        [room.uuid, room.id, room.name, room.floor, sorted(room.connected_room_uuids),
         sorted([o.uuid, o.id, o.name] for o in room.objects.values())]
        for room in sorted(building.rooms(), key=lambda r: r.uuid)
    ]
    text = json.dumps([building.num_floors, graph], separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _a(category: str) -> str:
    word = category_words(category)
    return f"{'an' if word[:1] in 'aeiou' else 'a'} {word}"


def entity_facts(propositions: Mapping[str, Proposition], building: Building) -> dict[str, dict[str, Any]]:
    """``{key: {category, floor[, room]}}`` for every entity ``propositions`` name that ``building`` has."""
    facts: dict[str, dict[str, Any]] = {}
    for prop in propositions.values():
        if prop.kind == "enter" and building.has_room(prop.uuid):
            room = building.room(uuid=prop.uuid)
            facts[room.key] = {"category": room.name, "floor": room.floor}
        elif prop.kind == "reach" and building.has_object(prop.uuid):
            obj = building.object(uuid=prop.uuid)
            room = building.room(id=obj.room_id)
            facts[obj.key] = {"category": obj.name, "floor": room.floor, "room": room.key}
    return dict(sorted(facts.items()))


def write_scene_record(
    folder: str | Path, propositions: Mapping[str, Proposition], building: Building
) -> Path:
    """Write ``scene.yaml`` (see the module docstring) into ``folder``; returns its path."""
    path = Path(folder) / SCENE_RECORD_NAME
    doc = {"format": FORMAT, "scene": building.name, "graph_sha256": scene_graph_hash(building),
           "entities": entity_facts(propositions, building)}
    try:
        path.write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
    except OSError as exc:
        raise MissionError(f"cannot write the scene record ({exc.strerror or exc})", path) from None
    return path


@dataclass(frozen=True)
class SceneFit:
    """How a mission folder fits a scene.

    ``source``: what the folder was compared through (``scene.yaml``, ``building_desc.yaml`` or
    ``nothing``); ``mismatches``: one sentence per difference (empty: it fits); ``notes``: remarks.
    """

    source: str
    mismatches: tuple[str, ...] = ()
    notes: tuple[str, ...] = field(default=())

    @property
    def fits(self) -> bool:
        return not self.mismatches


def check_folder_scene(
    folder: str | Path, propositions: Mapping[str, Proposition], building: Building
) -> SceneFit:
    """Compare the mission folder ``folder`` (whose propositions are ``propositions``) with ``building``.

    Raises
    ------
    MissionError
        ``scene.yaml`` exists but is not a scene record.
    """
    folder = Path(folder)
    here = entity_facts(propositions, building)
    missing = [f"{'room' if p.kind == 'enter' else 'object'}_{p.uuid} does not exist in {building.name!r}"
               for p in propositions.values()
               if not (building.has_room(p.uuid) if p.kind == "enter" else building.has_object(p.uuid))]
    record = folder / SCENE_RECORD_NAME
    if record.is_file():
        doc = _read(record)
        if (
            not isinstance(doc, dict)
            or doc.get("format") != FORMAT
            or not isinstance(doc.get("entities"), dict)
        ):
            raise MissionError(f"not a scene record ({FORMAT}); delete it or write the mission again", record)
        if doc.get("graph_sha256") == scene_graph_hash(building):
            return SceneFit(SCENE_RECORD_NAME)
        made_for = str(doc.get("scene"))
        problems = _differences(doc["entities"], here, building.name) + missing
        notes: tuple[str, ...] = ()
        if made_for != building.name:
            problems.insert(0, f"it was made for scene {made_for!r}, not {building.name!r}")
        elif not problems:
            notes = ((f"the scene graph of {building.name!r} changed since the mission was written; every "
                     "entity the mission names is still the same"),)
        return SceneFit(SCENE_RECORD_NAME, tuple(problems), notes)
    described = _authors_description(folder / "building_desc.yaml")
    if described is None:
        return SceneFit(
            "nothing",
            tuple(missing),
            (
                (
                    "the folder records no scene (no scene.yaml or building_desc.yaml): it could not be "
                    "checked against the scene"
                ),
            ),
        )
    wanted = {key: described[key] for key in here if key in described}
    unnamed = [key for key in here if key not in described]
    problems = _differences(wanted, here, building.name) + missing
    problems += [f"{key} is not in the folder's building_desc.yaml" for key in unnamed]
    return SceneFit("building_desc.yaml", tuple(problems))


def ensure_folder_fits_scene(folder: str | Path, propositions: Mapping[str, Proposition], building: Building,
                             *, force: bool = False) -> SceneFit:
    """:func:`check_folder_scene`, refusing a mismatch unless ``force``.

    Raises
    ------
    SceneMismatchError
        the folder was made for another scene (every difference is named), and ``force`` is false.
    """
    fit = check_folder_scene(folder, propositions, building)
    if fit.fits:
        return fit
    said = "; ".join(fit.mismatches)
    if not force:
        raise SceneMismatchError(
            f"this mission does not fit scene {building.name!r} (checked through "
            f"{fit.source}): {said}. Plan it on its own scene, or pass --force to plan it "
            "here anyway",
            folder,
        )
    return SceneFit(fit.source, fit.mismatches,
                    (*fit.notes, (f"planning anyway (--force) although the mission does not fit scene "
                                 f"{building.name!r}: {said}")))


def _read(path: Path) -> Any:
    """The scene record's YAML document (libyaml's loader, within safeio's limits)."""
    return load_yaml(path, MissionError, "scene record")


def _differences(recorded: Mapping[str, Any], here: Mapping[str, dict[str, Any]], scene: str) -> list[str]:
    out = []
    for key, then in recorded.items():
        now = here.get(key)
        if now is None or not isinstance(then, dict):
            continue
        said_then = f"{_a(str(then.get('category')))} on floor {then.get('floor')}"
        said_now = f"{_a(now['category'])} on floor {now['floor']}"
        if (
            category_words(str(then.get("category"))) != category_words(now["category"])
            or then.get("floor") != now["floor"]
        ):
            out.append(f"{key} was {said_then}, but in {scene!r} it is {said_now}")
    return out


def _authors_description(path: Path) -> dict[str, dict[str, Any]] | None:
    """``{key: {category, floor}}`` from the authors' building_desc.yaml, or ``None`` if absent or of
    another shape (sgplan's own folders store their prompt text there, and carry scene.yaml instead)."""
    if not path.is_file():
        return None
    try:
        doc = load_yaml(path, MissionError, "building description")
        rooms = doc["Building description"]
        out: dict[str, dict[str, Any]] = {}
        for entry in rooms:
            (name, fields), = entry.items()
            merged = {k: v for item in fields for k, v in item.items()}
            room_key, floor = str(merged["id"]), int(merged["floor"])
            out[room_key] = {"category": str(name).rsplit("_", 1)[0], "floor": floor}
            for obj in merged.get("objects") or []:
                (obj_name, obj_key), = obj.items()
                out[str(obj_key)] = {"category": str(obj_name).rsplit("_", 1)[0], "floor": floor}
        return out
    except (MissionError, KeyError, TypeError, ValueError, AttributeError):
        return None
