"""Check a blind mission set (JSON Lines) before a writer hands it in.

    .venv/bin/python benchmarks/blind_writing/check_set.py FILE.jsonl [--no-plan]

For every line: the fields (``id``, ``scene``, ``text``, ``formula``, ``style``, ``why``; optional
``start_floor``), that the gold formula parses and names only rooms / objects of its scene, the gold said back
in plain words (the writer reads it against the text), and that the gold can be done: an optimal plan exists
from one of the scene's starts (on ``start_floor`` when given). Ends with the number of problems (0: ready).

This is the only tool a blind writer runs besides ``sgplan inspect``: it never translates English, so the
writer never sees how the translator reads the texts (see ``brief_styles.md`` beside it).
"""

from __future__ import annotations

import json
import sys
from functools import cache
from pathlib import Path

import sgplan
from sgplan.errors import SgplanError
from sgplan.explain import explain_mission
from sgplan.mission import Mission
from sgplan.scene.model import Building

SCENES = ("demo", "Allensville", "Benevolence", "Collierville")


@cache
def building(scene: str) -> Building:
    return sgplan.load_scene(scene)


@cache
def session(scene: str) -> sgplan.Session:
    return sgplan.Session(building(scene))


def can_be_done(scene: str, mission: Mission, start_floor: int | None) -> tuple[str | None, str]:
    """``(None, "from start k, cost c m")`` when an optimal plan exists from a start (on ``start_floor``),
    else ``(the reason, "")``."""
    b = building(scene)
    why = "the scene has no start there"
    for k, cell in enumerate(b.initial_cells):
        if start_floor is not None and cell[2] != start_floor:
            continue
        try:
            result = sgplan.plan(b, mission, k, session=session(scene), setup="NO-LLM", time_limit_s=60)
        except SgplanError as exc:
            why = f"from start {k}: {exc}"
            continue
        if result.path is not None and len(result.path):
            return None, f"from start {k}, cost {result.cost_m:.2f} m"
        why = f"from start {k}: status {result.status}"
    return why, ""


def check_line(entry: dict, plan: bool) -> tuple[list[str], list[str]]:
    """What to print for one mission and its problems."""
    out = [f"[{entry.get('id')}] ({entry.get('scene')}) {entry.get('text')}"]
    bad = [f"missing field {key!r}" for key in ("style", "why") if not entry.get(key)]
    scene = entry.get("scene")
    if scene not in SCENES:
        return out, [*bad, f"scene must be one of {SCENES}"]
    floors = sorted({cell[2] for cell in building(scene).initial_cells})
    start_floor = entry.get("start_floor")
    if start_floor is not None and start_floor not in floors:
        bad.append(f"start_floor {start_floor!r}: the scene has starts only on floors {floors}")
    if entry.get("formula") is None:
        return [*out, f"   MUST BE REFUSED: {entry.get('why')}"], bad
    try:
        mission = sgplan.mission_from_formula(entry["formula"], building(scene))
    except SgplanError as exc:
        return out, [*bad, f"gold formula: {exc}"]
    words = explain_mission(mission, building(scene)).text
    out += ["   gold in words: " + line for line in words.splitlines()]
    if plan:
        why, done = can_be_done(scene, mission, start_floor)
        if why is None:
            out.append(f"   can be done: {done}")
        else:
            where = f" on floor {start_floor}" if start_floor is not None else ""
            bad.append(f"cannot be done from any start{where}: {why}")
    return out, bad


def main(argv: list[str]) -> int:
    paths = [a for a in argv if not a.startswith("--")]
    if len(paths) != 1:
        print(__doc__)
        return 2
    from sgplan.llm.evaluate import load_jsonl_set

    try:
        load_jsonl_set(paths[0])
    except SgplanError as exc:
        print(f"PROBLEM (whole file): {exc}")
        return 1
    problems = 0
    for line in Path(paths[0]).read_text(encoding="utf-8").splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        out, bad = check_line(json.loads(line), "--no-plan" not in argv)
        print("\n".join([*out, *(f"   PROBLEM: {p}" for p in bad)]))
        problems += len(bad)
    print(f"\n{problems} problem(s) in {paths[0]}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
