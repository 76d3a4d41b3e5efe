"""What a sweep runs: benchmark cases (scene x mission x start x setup) found in a data folder.

A data folder has the layout of ``../shared/datasets/gibson-3dsg``::

    <data>/<Scene>/              a scene sgplan can load (building.yaml, or scene.json) with initial positions
    <data>/<Scene>/missions/<m>/ mission folders (automaton.aut, ap_desc.yaml, llm_heuristic.yaml, ...)

A :class:`Case` is plain data (JSON-ready), so it can be sent to a worker process or a Ray node.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from sgplan.errors import SgplanError
from sgplan.safeio import quote

PAPER_SETUPS = ("ALL", "OCC", "OBJ", "ROOM", "FLR", "NO-LLM", "A*")
"""The seven setups in the order of the paper's Table II."""
TABLE3_SETUPS = ("ALL", "NO-LLM", "A*")
"""The setups of the paper's Table III (run on every scene, mission and start)."""
TABLE2_SCENE, TABLE2_MISSION = "Benevolence", "1"
"""The case of the paper's Table II (all seven setups, averaged over the starts)."""


class BenchError(SgplanError):
    """A sweep cannot be defined or run: bad data folder, unknown scene/mission/start/setup, bad results.

    ``path`` (the file or folder at fault), when given, is prefixed to the message.
    """

    def __init__(self, message: str, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        super().__init__(f"{self.path}: {message}" if self.path is not None else message)


def exact_number(value: float) -> str:
    """Shortest text of ``value`` that reads back as the same float (``5``, ``0.25``, ``1.0000001``)."""
    short = f"{value:g}"
    return short if float(short) == value else repr(value)


@dataclass(frozen=True)
class Case:
    """One benchmark case: plan ``mission`` of ``scene`` from initial position ``start`` with ``setup``.

    ``scene_dir`` / ``mission_dir`` are absolute paths (they must exist on the machine that runs the
    case); ``time_limit_s`` is the planner's search budget in seconds (``None`` = none); ``reach_model``
    the reach model chosen (``None``: the profile's, :attr:`effective_reach_model`).
    """

    scene: str
    mission: str
    start: int
    setup: str
    profile: str
    scene_dir: str
    mission_dir: str
    time_limit_s: float | None = None
    reach_model: str | None = None

    @property
    def effective_reach_model(self) -> str:
        """The reach model the case plans with: :attr:`reach_model`, else the profile's."""
        from sgplan.planning.setups import reach_model_for

        return reach_model_for(self.profile, self.reach_model)

    @property
    def key(self) -> str:
        """The resume key: every field that can change the outcome (not the paths, which may move). The
        reach model is named unless it is ``box``, the model of every row made before there was a choice,
        so that those rows still resume."""
        limit = "none" if self.time_limit_s is None else exact_number(self.time_limit_s)
        model = self.effective_reach_model
        reach = "" if model == "box" else f"/reach={model}"
        return f"{self.scene}/{self.mission}/{self.start}/{self.setup}/{self.profile}/tl={limit}{reach}"

    @property
    def slug(self) -> str:
        """A file-name-safe name, e.g. ``Benevolence_m1_s0_Astar`` (gallery files)."""
        setup = self.setup.replace("*", "star").replace("/", "-")
        return f"{self.scene}_m{self.mission}_s{self.start}_{setup}"

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Case:
        return cls(**{k: data[k] for k in cls.__dataclass_fields__})


@dataclass(frozen=True)
class DataScene:
    """A scene of a data folder: its name, folder, mission names (sorted) and number of initial cells."""

    name: str
    folder: Path
    missions: tuple[str, ...]
    num_starts: int


def mission_order(name: str) -> tuple[int, int | str]:
    """Sort key of mission names: numbers numerically, then other names."""
    return (0, int(name)) if name.isdigit() else (1, name)


def discover(data: str | Path, scenes: Sequence[str] | None = None) -> list[DataScene]:
    """The scenes of ``data`` (every sub-folder with a ``missions/`` folder), or the named ones.

    The building of each scene is loaded to count its initial positions.

    Raises
    ------
    BenchError
        ``data`` is not a folder, holds no scene, or a named scene is missing / has no missions.
    """
    from sgplan.formats import load_scene

    root = Path(data).expanduser()
    if not root.is_dir():
        raise BenchError(f"data folder {root} does not exist")
    available = sorted(p.name for p in root.iterdir() if (p / "missions").is_dir())
    if not available:
        raise BenchError(f"data folder {root} holds no scene: expected <scene>/missions/<mission>/ folders")
    names = list(scenes) if scenes else available
    unknown = [n for n in names if n not in available]
    if unknown:
        raise BenchError(
            f"no scene {', '.join(unknown)} under {root} (scenes with missions: {', '.join(available)})"
        )
    found = []
    for name in names:
        folder = root / name
        missions = sorted((p.name for p in (folder / "missions").iterdir() if p.is_dir()), key=mission_order)
        if not missions:
            raise BenchError(f"scene {name!r} has no mission folders under {folder / 'missions'}")
        found.append(
            DataScene(name, folder.resolve(), tuple(missions), len(load_scene(folder).initial_cells))
        )
    return found


@dataclass(frozen=True)
class Grid:
    """A cross product of selections; ``None`` selects everything the scene has."""

    scenes: tuple[str, ...] | None = None
    missions: tuple[str, ...] | None = None
    starts: tuple[int, ...] | None = None
    setups: tuple[str, ...] = TABLE3_SETUPS


def paper_grids(scene_names: Iterable[str]) -> list[Grid]:
    """The paper's experiments: Table III (every scene, mission and start x ALL / NO-LLM / A*) and,
    when the data has it, Table II (Benevolence mission 1 x every start x the seven setups)."""
    grids = [Grid(setups=TABLE3_SETUPS)]
    if TABLE2_SCENE in set(scene_names):
        grids.append(Grid(scenes=(TABLE2_SCENE,), missions=(TABLE2_MISSION,), setups=PAPER_SETUPS))
    return grids


def expand(
    scenes: Sequence[DataScene],
    grids: Sequence[Grid],
    *,
    profile: str = "authors",
    time_limit_s: float | None = None,
    reach_model: str | None = None,
) -> list[Case]:
    """Every case of the union of ``grids`` over ``scenes``, without duplicates, in a stable order
    (scene, mission, start, then the paper's setup order), under ``profile`` with ``reach_model`` (default:
    the profile's) and ``time_limit_s``.

    Raises
    ------
    BenchError
        a grid names a mission, start index or setup that a selected scene does not have.
    """
    from sgplan.planning.setups import get_setup

    by_name = {s.name: s for s in scenes}
    seen: dict[str, Case] = {}
    for grid in grids:
        setups = [get_setup(name).name for name in grid.setups]
        for name in grid.scenes or tuple(by_name):
            scene = by_name.get(name)
            if scene is None:
                raise BenchError(f"scene {name!r} is not in the sweep (have {', '.join(by_name)})")
            missions = grid.missions or scene.missions
            bad = [m for m in missions if m not in scene.missions]
            if bad:
                raise BenchError(
                    f"scene {name!r} has no mission {', '.join(bad)} (missions: {', '.join(scene.missions)})"
                )
            starts = grid.starts if grid.starts is not None else tuple(range(scene.num_starts))
            bad_starts = [k for k in starts if not 0 <= k < scene.num_starts]
            if bad_starts:
                raise BenchError(
                    f"scene {name!r} has {scene.num_starts} initial positions; start index "
                    f"{', '.join(map(str, bad_starts))} is out of range"
                )
            for mission in missions:
                for start in starts:
                    for setup in setups:
                        case = Case(
                            scene=name, mission=mission, start=int(start), setup=setup, profile=profile,
                            scene_dir=str(scene.folder), mission_dir=str(scene.folder / "missions" / mission),
                            time_limit_s=time_limit_s, reach_model=reach_model,
                        )
                        seen.setdefault(case.key, case)
    order = {name: k for k, name in enumerate(PAPER_SETUPS)}
    scene_order = {s.name: k for k, s in enumerate(scenes)}
    return sorted(
        seen.values(),
        key=lambda c: (scene_order[c.scene], mission_order(c.mission), c.start, order[c.setup]),
    )


MAX_STARTS = 100_000
"""Starts one selection may name (a scene has tens of initial positions)."""


def parse_selection(text: str) -> tuple[int, ...]:
    """Start indices from ``"0,2-4"`` style text (commas and inclusive ranges)."""
    out: list[int] = []
    for part in filter(None, (p.strip() for p in text.split(","))):
        match = re.fullmatch(r"(\d{1,9})(?:-(\d{1,9}))?", part)
        if not match:
            raise BenchError(f"bad start selection {quote(part)}: use indices and ranges like 0,2-4")
        lo, hi = int(match[1]), int(match[2] or match[1])
        if hi < lo:
            raise BenchError(f"bad start selection {quote(part)}: the range ends before it starts")
        if len(out) + hi - lo + 1 > MAX_STARTS:
            raise BenchError(f"start selection {quote(text)} names more than {MAX_STARTS:,} starts")
        out.extend(range(lo, hi + 1))
    return tuple(out)
