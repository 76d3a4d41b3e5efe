"""The authors' mission folder: read into a :class:`~sgplan.mission.model.Mission`, written from one.

The folder is the authors' layout (reference-algorithm.md §1.4)::

    NL_instructions.txt       the mission in natural language
    NL_instructions_uuid.txt  the same with room_<uuid> / object_<uuid> references
    GPT_LTL_formula.txt       the prefix token list, Python repr
    Spot_LTL_formula.txt      LBT prefix string over p1..pN
    ap_dict.txt               action token -> pK
    ap_desc.yaml              pK -> {type: kEnterRoom|kReachObject, uuid, reach_distance}
    automaton.aut             HOA automaton over p1..pN
    building_desc.yaml        the attribute hierarchy given to the LLM (prompt text)
    llm_heuristic.yaml        guidance {room_uuid: {q: [calls]}}
    scene.yaml                sgplan's folders only: the scene it was made for (mission/identity.py)

Only ``automaton.aut`` and ``ap_desc.yaml`` are required to plan; the rest is read when present.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Mapping, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any, Literal

import yaml

from sgplan.errors import FormulaError, MissionError, SgplanError
from sgplan.files import write_text_atomically
from sgplan.limits import MAX_REACH_RADIUS_M
from sgplan.logic import number_aps, parse_tokens, read_hoa, to_prefix, to_tokens, write_hoa
from sgplan.mission.model import Guidance, Mission
from sgplan.safeio import load_yaml, quote, read_text
from sgplan.scene.fields import is_int, is_number
from sgplan.scene.labels import Proposition
from sgplan.scene.model import Building

_AP_TYPES: dict[str, Literal["enter", "reach"]] = {"kEnterRoom": "enter", "kReachObject": "reach"}


MAX_MISSION_FILE_BYTES = 16 * 2**20
"""Cap of one mission-folder file (16 MiB); the Gibson missions' largest, building_desc.yaml, is ~0.1 MB."""


def _read_text(path: Path) -> str | None:
    """The stripped text of an optional file, ``None`` when absent; anything else under its name is an
    error."""
    if not (path.exists() or path.is_symlink()):
        return None
    return read_text(path, MissionError, "file", MAX_MISSION_FILE_BYTES).strip()


def _read_yaml(path: Path) -> Any:
    return load_yaml(path, MissionError, "YAML file", MAX_MISSION_FILE_BYTES)


def read_ap_desc(path: str | Path) -> dict[str, Proposition]:
    """Read an ``ap_desc.yaml``: ``pK -> {type, uuid, reach_distance}`` (-1 = the global reach radius).

    ``kNA`` entries (always false in the authors' code) are skipped; an automaton that uses one then
    fails with a message naming it.
    """
    path = Path(path)
    doc = _read_yaml(path)
    if not isinstance(doc, dict):
        raise MissionError("expected a mapping of proposition name -> {type, uuid}", path)
    meaning: dict[str, Proposition] = {}
    for name, entry in doc.items():
        if not isinstance(name, str):
            raise MissionError(f"proposition names must be strings like p1, got {quote(name)}", path)
        if not isinstance(entry, dict) or "type" not in entry:
            raise MissionError(f"proposition {quote(name)}: expected a mapping with 'type' and 'uuid'", path)
        kind = _AP_TYPES.get(entry["type"]) if isinstance(entry["type"], str) else None
        if entry["type"] == "kNA":
            continue
        if kind is None:
            raise MissionError(
                f"proposition {quote(name)}: unknown type {quote(entry['type'])} (use kEnterRoom or "
                "kReachObject)",
                path,
            )
        uuid: Any = entry.get("uuid")
        radius: Any = entry.get("reach_distance", -1.0)
        if not is_int(uuid) or uuid < 0:
            raise MissionError(
                f"proposition {quote(name)}: 'uuid' must be a whole number >= 0, got {quote(uuid)}", path
            )
        # -1 (any value <= 0) means the global reach radius; others are capped as --reach-radius is.
        if not is_number(radius) or not math.isfinite(radius) or radius > MAX_REACH_RADIUS_M:
            raise MissionError(
                f"proposition {quote(name)}: 'reach_distance' must be a number of metres <= "
                f"{MAX_REACH_RADIUS_M:g} "
                f"(or -1 for the scene's), got {quote(radius)}",
                path,
            )
        try:
            meaning[name] = Proposition(
                kind, int(uuid), float(radius) if kind == "reach" and radius > 0 else None
            )
        except SgplanError as exc:
            raise MissionError(f"proposition {quote(name)}: {exc}", path) from None
    return meaning


def read_guidance(path: str | Path) -> Guidance:
    """Read an ``llm_heuristic.yaml``. Only its outer shape is checked here; the planner skips (and
    counts) calls it cannot use."""
    path = Path(path)
    doc = _read_yaml(path)
    if doc is None:
        return {}
    if not isinstance(doc, dict) or not all(isinstance(v, dict) or v is None for v in doc.values()):
        raise MissionError("expected {room_uuid: {automaton state: [calls]}}", path)
    for room, states in doc.items():
        for state, calls in (states or {}).items():
            if calls is not None and not (isinstance(calls, list) and all(isinstance(c, str) for c in calls)):
                raise MissionError(
                    f"room {quote(room)}, state {quote(state)}: expected a list of call strings, got "
                    f"{quote(calls)}",
                    path,
                )
    return {room: (states or {}) for room, states in doc.items()}


def write_guidance(guidance: Mapping[Any, Mapping[Any, Sequence[str]]], path: str | Path) -> Path:
    """Write ``guidance`` as the authors' ``llm_heuristic.yaml`` (integer keys, lists of call strings)."""
    path = Path(path)
    plain = {int(r): {int(q): list(calls) for q, calls in states.items()} for r, states in guidance.items()}
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_text_atomically(path, yaml.safe_dump(plain, sort_keys=True))
    except OSError as exc:
        raise MissionError(f"cannot write the guidance ({exc.strerror or exc})", path) from None
    return path


def load_mission_folder(path: str | Path, profile: str = "ltlf", guidance: bool = True) -> Mission:
    """Load a mission folder in the authors' layout (see the module docstring).

    ``profile`` says how the HOA automaton's missing edges are read: ``"ltlf"`` (reject) or
    ``"authors"`` (keep the state). With ``guidance=False`` llm_heuristic.yaml is not read.
    """
    if not str(path).strip():
        raise MissionError("the mission folder is an empty path")
    folder = Path(path)
    if not folder.is_dir():
        raise MissionError("mission folder does not exist" if not folder.exists() else "not a folder", folder)
    hoa_path, ap_path = folder / "automaton.aut", folder / "ap_desc.yaml"
    for required in (hoa_path, ap_path):
        if not (required.exists() or required.is_symlink()):
            raise MissionError(
                f"missing {required.name}: a mission folder needs automaton.aut and ap_desc.yaml", folder
            )
    automaton = read_hoa(hoa_path, profile)  # type: ignore[arg-type]
    meaning = read_ap_desc(ap_path)
    missing = [ap for ap in automaton.aps if ap not in meaning]
    if missing:
        raise MissionError(
            f"automaton.aut uses {', '.join(missing)}, which ap_desc.yaml does not define", folder
        )

    formula = None
    tokens_text = _read_text(folder / "GPT_LTL_formula.txt")
    ap_dict_text = _read_text(folder / "ap_dict.txt")
    if tokens_text:
        try:
            ap_names = number_aps(tokens_text) if not ap_dict_text else _literal_dict(ap_dict_text, folder)
            formula = parse_tokens(tokens_text, ap_names=ap_names)
        except FormulaError as exc:
            raise MissionError(f"GPT_LTL_formula.txt: {exc}", folder) from None

    heuristic = folder / "llm_heuristic.yaml"
    unused = sorted(set(meaning) - set(automaton.aps))
    return Mission(
        automaton=automaton,
        propositions=meaning,
        formula=formula,
        text=_read_text(folder / "NL_instructions.txt"),
        grounded_text=_read_text(folder / "NL_instructions_uuid.txt"),
        guidance=read_guidance(heuristic)
        if guidance and (heuristic.exists() or heuristic.is_symlink())
        else None,
        source=folder,
        notes=[f"ap_desc.yaml defines {', '.join(unused)}, which the automaton does not use"]
        if unused
        else [],
    )


def _literal_dict(text: str, folder: Path) -> dict[str, str]:
    try:
        value = ast.literal_eval(text)
    except (ValueError, SyntaxError, TypeError, MemoryError, RecursionError):
        raise MissionError("ap_dict.txt is not a Python dict literal", folder) from None
    if not isinstance(value, dict):
        raise MissionError("ap_dict.txt is not a dict", folder)
    return {str(k): str(v) for k, v in value.items()}


# -- writing the authors' folder ---------------------------------------------------------------------


def save_mission_folder(mission: Mission, path: str | Path, hierarchy_text: str | None = None,
                        building: Building | None = None) -> Path:
    """Write ``mission`` in the authors' layout under ``path`` (created if needed); returns the folder.

    Propositions are renamed p1..pN by first appearance in the token list, as the authors do, so the
    folder loads back with :func:`load_mission_folder` to an equivalent mission. With ``building``, the
    scene it was made for is recorded in ``scene.yaml`` (:mod:`sgplan.mission.identity`), so that planning
    it on another scene is refused.
    """
    folder = Path(path)
    folder.mkdir(parents=True, exist_ok=True)
    actions = mission.descriptions
    if mission.formula is not None:
        tokens = to_tokens(mission.formula, ap_tokens=actions)
        p_names = number_aps(tokens)
        write_text_atomically(folder / "GPT_LTL_formula.txt", repr(tokens) + "\n")
        write_text_atomically(folder / "ap_dict.txt", repr(p_names) + "\n")
        write_text_atomically(
            folder / "Spot_LTL_formula.txt", to_prefix(parse_tokens(tokens, ap_names=p_names)) + "\n"
        )
    else:
        p_names = {token: f"p{k + 1}" for k, token in enumerate(dict.fromkeys(actions.values()))}
    renamed = replace(mission.automaton, aps=tuple(p_names[actions[ap]] for ap in mission.automaton.aps))
    write_hoa(renamed, folder / "automaton.aut")
    ap_desc = {}
    for ap in mission.automaton.aps:
        prop = mission.propositions[ap]
        entry: dict[str, Any] = {
            "type": "kEnterRoom" if prop.kind == "enter" else "kReachObject",
            "uuid": prop.uuid,
        }
        if prop.kind == "reach":
            entry["reach_distance"] = float(prop.reach_radius_m) if prop.reach_radius_m else -1.0
        ap_desc[p_names[prop.name]] = entry
    write_text_atomically(folder / "ap_desc.yaml", yaml.safe_dump(ap_desc, sort_keys=True))
    for name, value in (
        ("NL_instructions.txt", mission.text),
        ("NL_instructions_uuid.txt", mission.grounded_text),
        ("building_desc.yaml", hierarchy_text),
    ):
        if value is not None:
            write_text_atomically(folder / name, value.rstrip("\n") + "\n")
    if mission.guidance is not None:
        write_guidance(mission.guidance, folder / "llm_heuristic.yaml")
    if building is not None:
        from sgplan.mission.identity import write_scene_record

        write_scene_record(folder, mission.propositions, building)
    return folder
