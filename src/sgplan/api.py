"""sgplan's public API, the one path every front end takes (the CLI ``plan`` and ``demo``, the benchmark
worker): scene -> mission -> plan -> result.

>>> import sgplan
>>> building = sgplan.load_scene("demo")
>>> mission = sgplan.mission_from_text("Go to the kitchen, then the bedroom with the clock.", building)
>>> result = sgplan.plan(building, mission, start="kitchen")      # planned and checked
>>> result.draw("out/quick"); result.write_json("out/quick/plan.json")  # doctest: +SKIP

:class:`Session` plans many missions on one building and keeps the occupancy grid of each robot radius
and the label raster of each proposition and reach radius between them.
"""

from __future__ import annotations

import difflib
import logging
import time
from collections import Counter
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypedDict

import numpy as np

from sgplan.assembly import make_problem
from sgplan.english import count
from sgplan.errors import PlanningError, SceneError
from sgplan.options import PlanOptions
from sgplan.planning.shared import SharedParts
from sgplan.radii import Radii, resolve_radii
from sgplan.scene.model import Building
from sgplan.scene.reach import DEFAULT_REACH_MODEL

if TYPE_CHECKING:  # the planner, grid and labels (numba, scipy) load when a plan is made, not for a mission
    from sgplan.explain import Explanation
    from sgplan.llm.backends import Backends
    from sgplan.llm.protocols import MissionGuide
    from sgplan.mission import Mission
    from sgplan.planning.amra import IterationCallback, SearchResult
    from sgplan.planning.problem import PlanningProblem
    from sgplan.planning.termination import Termination
    from sgplan.result import PlanResult
    from sgplan.scene.grid import OccupancyGrid
    from sgplan.scene.labels import Proposition
    from sgplan.starts import StartSpec

log = logging.getLogger("sgplan")

DEMO = "demo"
"""The scene name of the embedded demo building."""


# -- scenes ------------------------------------------------------------------------------------------


def load_scene(scene: str | Path | Building, data: str | Path | None = None) -> Building:
    """The building named by ``scene``.

    ``scene`` is ``"demo"`` (the embedded demo building), a Gibson scene name (``"Benevolence"``, any case)
    looked up under ``data`` (default: ``$SGPLAN_GIBSON_DIR``, else ``../shared/datasets/gibson-3dsg``), a
    scene folder or file in any supported format (:func:`sgplan.formats.load_scene`), or a
    :class:`Building` (returned as it is).

    Raises
    ------
    SceneError
        when ``scene`` is none of these, or its files are malformed.
    """
    from sgplan.datasets import SCENES, scene_dir
    from sgplan.formats import load_scene as load_path

    if isinstance(scene, Building):
        return scene
    spec = str(scene)
    if spec.lower() == DEMO:
        from sgplan.scene.demo import demo_building

        return demo_building()
    path = Path(spec).expanduser()
    try:
        exists = path.exists()
    except OSError as error:  # e.g. a parent folder that cannot be searched
        raise SceneError(f"cannot read the scene: {error.strerror or error}", path) from None
    if exists:
        return load_path(path)
    names = {name.lower(): name for name in SCENES}
    if spec.lower() in names:
        return load_path(scene_dir(names[spec.lower()], data))
    close = difflib.get_close_matches(spec.lower(), [*names, DEMO], n=1, cutoff=0.75)
    hint = f"; did you mean {names.get(close[0], close[0])!r}?" if close else ""
    raise SceneError(f"scene {spec!r} is neither an existing path, a Gibson scene name ({', '.join(SCENES)}) "
                     f"nor '{DEMO}'{hint}")


# -- missions ----------------------------------------------------------------------------------------


def load_mission(folder: str | Path, *, profile: str = "ltlf", guidance: bool = True) -> Mission:
    """The mission of a mission folder (the authors' layout; see :mod:`sgplan.mission`)."""
    from sgplan.mission import load_mission_folder

    return load_mission_folder(folder, profile=profile, guidance=guidance)


def mission_from_formula(
    formula: str | Any,
    building: Building | None = None,
    *,
    aps: str | Path | Mapping[str, Proposition] | None = None,
    text: str | None = None,
) -> Mission:
    """The mission of an LTL formula (LLM token list, Spot infix or LBT prefix) over action tokens
    ``enter(room_<uuid>)`` / ``reach(object_<uuid>)``, or over names given a meaning by ``aps`` (an
    ``ap_desc.yaml`` file or a mapping). With ``building``, its propositions are checked against it now.
    """
    from sgplan.mission import compile_mission, read_ap_desc

    meanings = read_ap_desc(aps) if isinstance(aps, (str, Path)) else aps
    mission = compile_mission(formula, meanings, text=text)
    if building is not None:
        mission.check_scene(building)
    return mission


def mission_from_text(
    text: str,
    building: Building,
    *,
    llm: str | Backends = "offline",
    save_to: str | Path | None = None,
    **llm_options: Any,
) -> Mission:
    """Translate a mission in natural language into a :class:`Mission` (grounded in ``building``).

    ``llm`` is ``"offline"`` (rule-based backends for controlled English, not a language model),
    ``"openai:MODEL"`` (any OpenAI-compatible server; ``llm_options`` are those of
    :func:`sgplan.llm.backends.open_backends`: ``base_url``, ``cache_dir``, ``replay``, ``samples``,
    ``max_repairs``, ``requests_per_minute`` ...), or backends already open. With ``save_to``, the mission
    folder, the grounded IDs and the LLM run record are written there.

    Raises
    ------
    MissionError, LLMError
        an ambiguous or unknown reference (with the candidates), a failed translation.
    """
    from sgplan.llm.translation import mission_of, translate_to_folder

    backends = _backends(llm, **llm_options)
    if save_to is not None:
        _, mission = translate_to_folder(text, building, backends.translator, save_to, backends.record)
        return mission
    return mission_of(backends.translator.translate(text, building))


def _backends(llm: str | Backends, **options: Any) -> Backends:
    from sgplan.llm.backends import open_backends

    return open_backends(llm, **options) if isinstance(llm, str) else llm


def add_guidance(
    mission: Mission, building: Building, guide: MissionGuide | None = None
) -> tuple[Mission, str]:
    """``mission`` with LLM-heuristic guidance from ``guide`` (default: the offline symbolic guide, not an
    LLM) when it carries none, and where the guidance came from (``"mission"`` or the guide's name).
    The given mission is not changed."""
    if mission.guidance is not None:
        return mission, "mission"
    if guide is None:
        from sgplan.llm.offline import SymbolicGuide

        guide = SymbolicGuide()
    from sgplan.llm.guidance import LLMGuide

    if isinstance(guide, LLMGuide) and guide.mission_text is None:
        guide.mission_text = mission.grounded_text or mission.text  # the prompt quotes the mission
    log.debug("guidance from %s", guide.name)
    return replace(
        mission, guidance=guide.guide(building, mission.automaton, mission.descriptions)
    ), guide.name


class Explained(TypedDict):
    """The ``explanation`` and ``explanation_method`` of a :class:`PlanResult`."""

    explanation: str
    explanation_method: str


def explain_for_result(mission: Mission, building: Building, given: Explanation | None = None,
                       cells: Callable[[Proposition, float, str], np.ndarray] | None = None, *,
                       reach_radius_m: float | None = None, reach_model: str | None = None) -> Explained:
    """The mission explained in plain English (:func:`sgplan.explain.explain_mission`) as the
    ``explanation`` and ``explanation_method`` of a :class:`PlanResult`: the one place a plan gets it.
    ``given``: the caller's explanation of this mission and building (already said back), used as it is;
    ``cells``: where each proposition holds (:meth:`Session.proposition_cells`), objects reached within
    ``reach_radius_m`` under ``reach_model`` (the plan's)."""
    if given is None:
        from sgplan.explain import explain_mission

        given = explain_mission(mission, building, reach_radius_m=reach_radius_m, reach_model=reach_model,
                                cells=cells)
    return {"explanation": given.text, "explanation_method": given.method}


# -- planning ----------------------------------------------------------------------------------------


class Session:
    """Plans many missions on one building, keeping between them the occupancy grid of each robot radius,
    the cells of each (proposition, reach radius, reach model) and the planner's building-only parts
    (``parts``: the cell graph of each grid, the composite action tables and maps of each grid, reach
    radius and reach model, the
    h_LTL distance field of each target region; :mod:`sgplan.planning.shared`), so a second mission pays
    only for what depends on it. ``builds`` counts what the session built (grids, label masks);
    ``parts.builds`` the parts.

    The parts are bounded: after each plan the least recently used are dropped until they hold at most
    ``max_shared_bytes`` (default 1 GiB, or ``$SGPLAN_SESSION_BYTES``); grids and label masks are kept
    (one per radius and proposition).

    >>> session = Session(sgplan.load_scene("demo"))                    # doctest: +SKIP
    >>> [session.plan(m, start="kitchen").cost_m for m in missions]    # doctest: +SKIP
    """

    def __init__(
        self, building: Building | str | Path, data: str | Path | None = None, *,
        max_shared_bytes: int | None = None,
    ) -> None:
        self.building = load_scene(building, data)
        self._grids: dict[float, OccupancyGrid] = {}
        self._cells: dict[tuple[Proposition, float, str], np.ndarray] = {}  # flat indices where it holds
        self.parts = SharedParts(max_shared_bytes)
        self.builds: Counter[str] = Counter()

    def __repr__(self) -> str:
        radii = ", ".join(f"{r:g} m" for r in sorted(self._grids)) or "none yet"
        held_mib, cap_mib = self.parts.nbytes() / 2**20, self.parts.max_bytes / 2**20
        return (f"<Session {self.building.name!r}: grids for robot radii {radii}, "
                f"{count(len(self._cells), 'proposition')} located, {count(len(self.parts), 'planner part')} "
                f"({held_mib:.0f} of at most {cap_mib:.0f} MiB)>")

    def radii(self, robot_radius_m: float | None = None, reach_radius_m: float | None = None) -> Radii:
        """The radii a plan uses: given, else the scene's, else the defaults (:func:`resolve_radii`)."""
        return resolve_radii(self.building, robot_radius_m, reach_radius_m)

    def grid(self, robot_radius_m: float | None = None) -> OccupancyGrid:
        """The occupancy grid for this robot radius (built once per radius)."""
        from sgplan.scene.cache import occupancy_grid_cached
        from sgplan.scene.grid import build_occupancy_grid

        radius = self.radii(robot_radius_m).robot_m
        if radius not in self._grids:
            self._grids[radius] = occupancy_grid_cached(self.building, radius, build_occupancy_grid)
            self.builds["grid"] += 1
        return self._grids[radius]

    def labels(self, mission: Mission, reach_radius_m: float | None = None,
               reach_model: str = DEFAULT_REACH_MODEL) -> np.ndarray:
        """The mission's label raster (as :meth:`Mission.labels`), from the cells of each proposition kept
        between missions (flat indices: far smaller than a full mask per proposition)."""
        from sgplan.scene.labels import raster_from_cells

        mission.check_scene(self.building)
        reach = self.radii(reach_radius_m=reach_radius_m).reach_m
        return raster_from_cells(
            (self.building.num_floors, *self.building.grid_shape),
            [self.proposition_cells(prop, reach, reach_model) for prop in mission.ordered_propositions],
        )

    def proposition_cells(self, prop: Proposition, reach_radius_m: float,
                          reach_model: str = DEFAULT_REACH_MODEL) -> np.ndarray:
        """Flat indices of the cells where ``prop`` holds at this reach radius (metres) and reach model, as
        :func:`sgplan.scene.labels.proposition_cells`; built once per proposition, radius and model. The
        label rasters and the explanations of this session's plans read them from here."""
        from sgplan.scene.labels import proposition_cells

        key = (prop, reach_radius_m, reach_model)
        if key not in self._cells:
            self._cells[key] = proposition_cells(self.building, prop, reach_radius_m, reach_model)
            self.builds["label_mask"] += 1
        return self._cells[key]

    def plan(
        self,
        mission: Mission,
        start: StartSpec = None,
        *,
        options: PlanOptions | None = None,
        guide: MissionGuide | None = None,
        callback: IterationCallback | None = None,
        explanation: Explanation | None = None,
        termination: Termination | None = None,
        start_state: int | None = None,
        **option_values: Any,
    ) -> PlanResult:
        """Plan ``mission`` from ``start`` with AMRA*; see :func:`sgplan.plan`."""
        chosen = PlanOptions.from_keywords(options, **option_values)
        try:
            return self._plan(mission, start, chosen, guide=guide, callback=callback, explanation=explanation,
                              termination=termination, start_state=start_state)
        finally:
            self.parts.trim()

    def _plan(
        self,
        mission: Mission,
        start: StartSpec,
        options: PlanOptions,
        *,
        guide: MissionGuide | None,
        callback: IterationCallback | None,
        explanation: Explanation | None,
        termination: Termination | None,
        start_state: int | None,
    ) -> PlanResult:
        from sgplan.planning.amra import plan as amra_plan
        from sgplan.planning.termination import any_of
        from sgplan.runtime.jit import announce_compile

        announce_compile()  # before staging, whose scene checks run kernels too
        t0 = time.perf_counter()
        staged = self._stage(mission, start, options, guide, start_state)
        prepare_s = time.perf_counter() - t0
        # Without kept parts the problem's maps are this plan's alone: freed once the search stops
        # reading them.
        stop_when = any_of(options.termination(), termination)
        try:
            found = amra_plan(staged.problem, options.setup, termination=stop_when, callback=callback,
                              prebuild_actions=options.prebuild_actions, release_maps=not self.parts.keeps)
        except PlanningError as error:
            raise _with_cause(error, staged.mission, self.building, staged.problem) from None
        explained = explain_for_result(staged.mission, self.building, explanation, self.proposition_cells,
                                       reach_radius_m=staged.radii.reach_m,
                                       reach_model=str(staged.problem.reach_model))
        return finish_plan(found, staged, options, explained, started=t0, prepare_s=prepare_s)

    def _stage(self, mission: Mission, start: StartSpec, options: PlanOptions,
               guide: MissionGuide | None, start_state: int | None = None) -> StagedPlan:
        """Everything before the search: the guidance a setup needs, the radii, grid, start cell and the
        planning problem, checked against the scene (an error found there is raised)."""
        from sgplan.planning.setups import get_setup
        from sgplan.starts import start_cell

        guidance = "mission" if mission.guidance is not None else None
        if get_setup(options.setup).uses_llm:
            mission, guidance = add_guidance(mission, self.building, guide)
        radii = self.radii(options.robot_radius_m, options.reach_radius_m)
        grid = self.grid(radii.robot_m)
        start_at, start_from = start_cell(self.building, grid, start)
        labels = self.labels(mission, radii.reach_m, options.effective_reach_model)
        prepared = make_problem(self.building, mission, start_at, options, grid=grid, labels=labels,
                                shared=self.parts, start_state=start_state)
        scene_check = _check_in_scene(mission, self.building, prepared.problem)
        log.info(
            "scene %s: start %s (%s), robot radius %g m (%s), reach %g m (%s, %s model), profile %s, %d "
            "automaton states",
            self.building.name, start_at, start_from, radii.robot_m, radii.robot_from, radii.reach_m,
            radii.reach_from, prepared.problem.reach_model, options.profile, mission.automaton.num_states,
        )
        return StagedPlan(mission, guidance, prepared.problem, radii, start_from, scene_check)


@dataclass(frozen=True)
class StagedPlan:
    """A plan's inputs once staged (:meth:`Session._stage`, or a run's plan from its position): the
    mission (with the guidance added, if any), where its guidance came from, the problem, the radii, how the
    start was chosen, the scene check's findings."""

    mission: Mission
    guidance: str | None
    problem: PlanningProblem
    radii: Radii
    start_from: str
    scene_check: list[dict[str, Any]]


def finish_plan(found: SearchResult, staged: StagedPlan, options: PlanOptions, explained: Explained, *,
                started: float, prepare_s: float) -> PlanResult:
    """The public result of a search over ``staged``'s problem: the path checked (``options.verify``), its
    waypoints and events, the timings since ``started`` (a ``time.perf_counter()``)."""
    result = _result(found, staged, options, staged.problem.building, explained)
    if found.path is not None:
        _add_outputs(result, options.verify, staged.problem.start_state)
    result.timings = {
        "prepare_s": prepare_s, "precompute_s": found.precompute_s, "search_s": found.search_s,
        "wall_s": time.perf_counter() - started,
    }
    return result


def _result(found: SearchResult, staged: StagedPlan, options: PlanOptions, building: Building,
            explained: Explained) -> PlanResult:
    """The public result of a search (without the outputs :func:`_add_outputs` adds)."""
    from sgplan.result import PlanResult

    mission, problem = staged.mission, staged.problem
    bound = 1.0 if found.status == "optimal" else found.iterations[-1].bound if found.iterations else None
    return PlanResult(
        scene=building.name, status=found.status, setup=found.setup, profile=options.profile,
        reach_model=str(problem.reach_model),
        cost_m=found.cost_m, bound=bound, path=found.path, start=problem.start, start_from=staged.start_from,
        radii=staged.radii, queues=found.queues, iterations=found.iterations, mission_text=mission.text,
        grounded_text=mission.grounded_text, formula=_formula_text(mission),
        propositions=mission.descriptions, guidance=staged.guidance, notes=list(mission.notes),
        building=building, grid=problem.grid, labels=problem.labels, mission=mission,
        scene_check=staged.scene_check, **explained,
    )


def _check_in_scene(mission: Mission, building: Building, problem: PlanningProblem) -> list[dict[str, Any]]:
    """The scene-aware checks of the problem about to be searched
    (:func:`sgplan.explain.checks.check_mission_in_scene`): warnings and notes are logged, the first error
    is raised (unsatisfiable in this scene, from this start, or only through forbidden rooms); the findings
    as records."""
    from sgplan.explain.checks import check_mission_in_scene

    profile = problem.profile
    if problem.start_state is not None:  # check what is left from the start state, its label read
        a = mission.automaton
        mission = replace(mission, automaton=type(a)(a.aps, a.table, problem.start_state, a.accepting),
                          formula=None)
        profile = "authors"
    check = check_mission_in_scene(mission, building, problem.start, grid=problem.grid, labels=problem.labels,
                                   profile=profile, reach_model=problem.reach_model)
    check.report()
    return check.to_dict()


def _with_cause(error: PlanningError, mission: Mission, building: Building,
                problem: PlanningProblem) -> PlanningError:
    """The planner's ``infeasible`` error said with its cause when a place the mission needs cannot be
    reached from the start (:func:`sgplan.explain.checks.unreachable_finding`: no door, too narrow for this
    robot); any other error as it is."""
    if error.status != "infeasible":
        return error
    from sgplan.explain.checks import unreachable_finding

    finding = unreachable_finding(mission, building, problem.grid, problem.labels, problem.start)
    return error if finding is None else PlanningError(finding.message, status="infeasible")


def _formula_text(mission: Mission) -> str | None:
    from sgplan.logic import to_infix

    return to_infix(mission.formula) if mission.formula is not None else None


def _add_outputs(result: PlanResult, verify: bool, start_state: int | None) -> None:
    """Check the path (when asked) and add the waypoints and events; ``start_state``: the automaton state
    at the path's first cell when it resumes a mission (:class:`~sgplan.planning.PlanningProblem`)."""
    from sgplan.outputs.events import path_events
    from sgplan.outputs.waypoints import leg_costs, path_waypoints
    from sgplan.planning.checker import check_path

    assert result.path is not None and result.grid is not None and result.labels is not None
    assert result.mission is not None and result.building is not None
    automaton = result.mission.automaton
    if verify:
        check = check_path(result.path, result.grid, result.labels, automaton, result.profile, start_state)
        if not check.valid:
            raise PlanningError("the path failed the independent check (a bug, please report it): "
                                + "; ".join(check.problems))
        if abs(check.cost_m - result.cost_m) > 1e-6:
            raise PlanningError(f"the checker recomputes cost {check.cost_m:.6f} m, the planner said "
                                f"{result.cost_m:.6f} m (a bug, please report it)")
        result.verified = True
    result.waypoints = path_waypoints(result.path, result.grid, result.building)
    result.simplify_waypoints()
    costs = np.concatenate([[0.0], np.cumsum(leg_costs(result.path, result.grid))])
    result.events = path_events(result.path, costs, result.labels, automaton, result.building,
                                result.mission.descriptions, start_state=start_state)


def plan(
    building: Building,
    mission: Mission,
    start: StartSpec = None,
    *,
    options: PlanOptions | None = None,
    guide: MissionGuide | None = None,
    callback: IterationCallback | None = None,
    session: Session | None = None,
    explanation: Explanation | None = None,
    termination: Termination | None = None,
    start_state: int | None = None,
    **option_values: Any,
) -> PlanResult:
    """Plan an optimal path for ``mission`` over ``building`` with AMRA* and check it.

    Parameters
    ----------
    start:
        ``None`` (the scene's first initial position), an initial position index, a cell
        ``(row, col, floor)``, a metric :class:`~sgplan.starts.Point` ``(x_m, y_m, floor)`` (or a triple with
        float x/y), or a room (``"kitchen"``, ``"room_5"``); see :mod:`sgplan.starts`.
    options, **option_values:
        the planning options (:class:`sgplan.PlanOptions`, which states and checks them), as a value, as
        keywords (``setup="NO-LLM"``), or both (the keywords replace the value's fields). A
        setup using LLM guidance on a mission without guidance gets it from ``guide`` (default: the
        offline symbolic guide, which is not an LLM); ``PlanResult.guidance`` says which. When a budget
        runs out the result has status ``"timeout"`` with the best path so far (its ``bound``) or none:
        no exception, the caller decides.
    callback:
        called with each AMRA* iteration record as it finishes.
    session:
        plan within this :class:`Session` (its grids, labels, action maps and distance fields are
        reused); default a new one that keeps no planner parts.
    explanation:
        the mission's explanation over this building (:func:`sgplan.explain.explain_mission` with the
        plan's reach radius and model) when the caller already made it, e.g. to say it back before
        planning: the result carries it instead of making it again (a few tens of ms); default: made here.
    termination:
        a further condition that stops the search (:mod:`sgplan.planning.termination`), e.g. a
        :class:`~sgplan.planning.termination.CancelFlag` that another thread sets (status
        ``"cancelled"``, with the best path so far) or a wall-clock
        :class:`~sgplan.planning.termination.Deadline`; checked with the options' budgets.
    start_state:
        plan the rest of a mission already under way: the automaton state at ``start``, its label already
        read (e.g. ``PlanResult.path[k, 3]`` at the path's cell ``k``, or a monitor's state there); the
        path's rows then carry the states from it on. ``None``: from the automaton's initial state.

    Raises
    ------
    TypeError
        a keyword that is no planning option (the message names the options).
    PlanningError
        ``status="invalid-start"`` / ``"infeasible"`` with the reason, or ``"error"`` (a bad option value).
    SceneError, MissionError
        the mission names entities the building lacks.
    """
    if session is None:  # a one-off session keeps nothing: no copy of what this plan holds anyway
        session = Session(building, max_shared_bytes=0)
    elif session.building is not building:
        raise PlanningError("the session plans on another building than the one given")
    return session.plan(mission, start, options=options, guide=guide, callback=callback,
                        explanation=explanation, termination=termination, start_state=start_state,
                        **option_values)
