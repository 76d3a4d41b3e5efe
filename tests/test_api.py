"""The public API: `import sgplan` is cheap and flat; scenes, missions, starts, plans, sessions."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy import ndimage

import sgplan
from sgplan.cli import main
from sgplan.errors import PlanningError, SceneError

README = Path(__file__).resolve().parents[1] / "README.md"
KITCHEN_THEN_BEDROOM = 'F("enter(room_4)" & F "enter(room_11)")'


@pytest.fixture(scope="module")
def demo() -> sgplan.api.Building:
    return sgplan.load_scene("demo")


def test_the_readme_example_is_at_most_five_lines_and_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    text = README.read_text(encoding="utf-8")
    block = re.search(r"From Python.*?```python\n(.*?)```", text, re.DOTALL)
    assert block is not None
    lines = block[1].strip().splitlines()
    assert len(lines) <= 5 and lines[0] == "import sgplan"
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {}
    exec(block[1], namespace)
    result = namespace["result"]
    assert isinstance(result, sgplan.PlanResult) and result.status == "optimal" and result.verified
    assert hasattr(result, "explanation") and str(result) in capsys.readouterr().out
    assert {"plan.json", "plan_floor_0.png", "plan_floor_1.png", "automaton.svg"} <= {
        p.name for p in (tmp_path / "out/quick").iterdir()}
    assert json.loads((tmp_path / "out/quick/plan.json").read_text())["cost_m"] == pytest.approx(
        result.cost_m
    )


def test_import_sgplan_is_cheap_and_names_load_on_first_use() -> None:
    code = (
        "import sys, sgplan; print(sorted(m for m in ('numpy', 'numba', 'scipy') if m in sys.modules)); "
        "sgplan.plan"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
    assert {"load_scene", "mission_from_text", "plan", "Session", "PlanResult", "Point"} <= set(dir(sgplan))
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        sgplan.nope  # noqa: B018


def test_load_scene_accepts_names_in_any_case_paths_and_buildings(demo, tmp_path: Path) -> None:
    assert sgplan.load_scene("DEMO").name == demo.name and sgplan.load_scene(demo) is demo
    from sgplan.scene.native import write_native_scene

    assert sgplan.load_scene(write_native_scene(demo, tmp_path / "d")).name == demo.name
    with pytest.raises(SceneError, match="neither an existing path") as error:
        sgplan.load_scene("no-such-scene")
    assert "did you mean" not in str(error.value)
    for typo, meant in (("Benevolance", "Benevolence"), ("colliervile", "Collierville"), ("demoo", "demo")):
        with pytest.raises(SceneError, match=f"; did you mean '{meant}'\\?$"):
            sgplan.load_scene(typo)


def test_gibson_scene_names_in_any_case(gibson_root: Path) -> None:
    assert sgplan.load_scene("collierville", data=gibson_root).name.lower() == "collierville"


def test_starts_by_cell_point_room_and_index(demo) -> None:
    session = sgplan.Session(demo)
    mission = sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo)
    grid = session.grid()
    by_room = session.plan(mission, "bathroom on floor 0", setup="NO-LLM")
    row, col, floor = by_room.start
    assert grid.traversable[floor, row, col] and grid.room_map[floor, row, col] == demo.room(uuid=5).id
    assert (
        by_room.start_from == "room bathroom room_5"
        and session.plan(mission, "room_5", setup="NO-LLM").start == by_room.start
    )
    x, y = demo.floors[0].cell_to_xy((row, col))
    by_point = session.plan(mission, sgplan.Point(x + 0.01, y - 0.01, 0), setup="NO-LLM")
    assert by_point.start == by_room.start and by_point.cost_m == pytest.approx(by_room.cost_m)
    assert session.plan(mission, (row, col, floor), setup="NO-LLM").start_from == "cell"
    assert session.plan(mission, 2, setup="NO-LLM").start == demo.initial_cells[2]
    blocked = np.argwhere(~grid.traversable[0] & (grid.room_map[0] > 0))  # inflated-obstacle cells in rooms
    depth = ndimage.distance_transform_edt(~grid.traversable[0])
    snap = next(c for c in blocked if 0 < depth[tuple(c)] * 0.05 <= 0.3)
    snapped = session.plan(mission, (*demo.floors[0].cell_to_xy(tuple(snap)), 0), setup="NO-LLM")
    assert "moved" in snapped.start_from and grid.traversable[0, snapped.start[0], snapped.start[1]]
    with pytest.raises(PlanningError, match=r"names 2 rooms; .*room_5.*room_14") as error:
        session.plan(mission, "bathroom")
    assert error.value.status == "invalid-start"
    with pytest.raises(PlanningError, match=r"no free cell lies within 0.5 m"):
        session.plan(mission, sgplan.Point(*demo.floors[0].cell_to_xy((0, 0)), 0))
    with pytest.raises(PlanningError, match=r"lies off floor 0's grid \(x -5.25..5.25 m, y -5.15..5.15 m\)"):
        session.plan(mission, sgplan.Point(20.0, 2.0, 0))
    with pytest.raises(PlanningError, match=r"floors 0..1"):
        session.plan(mission, sgplan.Point(0.0, 0.0, 5))
    with pytest.raises(PlanningError, match="no room called 'garage'"):
        session.plan(mission, "garage")
    with pytest.raises(PlanningError, match="is none of"):
        session.plan(mission, {"x": 1})  # type: ignore[arg-type]


def test_a_session_keeps_grids_and_labels_and_plans_like_fresh_calls(demo) -> None:
    session = sgplan.Session(demo)
    first = sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo)
    second = sgplan.mission_from_formula('F("reach(object_28)") & G !"enter(room_4)"', demo)
    results = [session.plan(m, 0, setup="NO-LLM") for m in (first, second, first)]
    assert results[0].grid is results[1].grid is session.grid() and len(session._grids) == 1
    for mission in (first, second):
        assert np.array_equal(session.labels(mission), mission.labels(demo, demo.reach_radius_m))
    fresh = [sgplan.plan(demo, m, 0, setup="NO-LLM") for m in (first, second)]
    assert [r.cost_m for r in results] == pytest.approx([fresh[0].cost_m, fresh[1].cost_m, fresh[0].cost_m])
    assert session.grid(0.2) is not session.grid() and len(session._grids) == 2
    with pytest.raises(PlanningError, match="another building"):
        sgplan.plan(sgplan.load_scene("demo"), first, session=session)


def _maps_built(session: sgplan.Session) -> np.ndarray:
    """The one action-map store of a session (one grid, radius and component), as built flags (none when
    only the A* setup, which builds no composite actions, has planned)."""
    stores = list(session.parts.kept("action_maps").values())
    if not stores:
        return np.zeros(0, dtype=bool)
    (store,) = stores
    return store.built.astype(bool)


@pytest.mark.parametrize("prebuild", [False, True])
@pytest.mark.parametrize("setup", ["ALL", "NO-LLM", "A*"])
def test_a_second_mission_on_a_session_builds_only_what_depends_on_it(
    demo, setup: str, prebuild: bool
) -> None:
    """Work counted, not timed: the grid, the cell graph, the masks of propositions already seen, the
    action tables, every action map, every h_LTL distance field and the label runs and label boundary of
    each labelling are built once per session (the A* setup builds no action tables, maps or label runs at
    all); the plans are those of fresh calls (same cost and path)."""
    actions = setup != "A*"
    action_parts = {"action_tables": 1, "action_maps": 1, "label_runs": 1} if actions else {}
    session = sgplan.Session(demo)
    first = sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo)
    second = sgplan.mission_from_formula('F("reach(object_28)" & F "enter(room_5)")', demo)
    a = session.plan(first, 0, setup=setup, prebuild_actions=prebuild)
    fields = set(session.parts.kept("distance_field"))
    built = (dict(session.builds), dict(session.parts.builds))
    assert built == ({"grid": 1, "label_mask": len(first.ordered_propositions)},
                     {"cell_graph": 1, **action_parts, "label_boundary": 1, "distance_field": len(fields)})
    maps_a = _maps_built(session).copy()
    b = session.plan(second, 0, setup=setup, prebuild_actions=prebuild)
    new_props = set(second.ordered_propositions) - set(first.ordered_propositions)
    assert session.builds == {"grid": 1, "label_mask": built[0]["label_mask"] + len(new_props)}
    new_fields = set(session.parts.kept("distance_field")) - fields
    runs = {"label_runs": 2} if actions else {}
    assert session.parts.builds == {"cell_graph": 1, **action_parts, **runs, "label_boundary": 2,
                                    "distance_field": len(fields) + len(new_fields)}
    fresh_maps = []
    for kept, mission in ((a, first), (b, second)):
        alone = sgplan.Session(demo)
        fresh = alone.plan(mission, 0, setup=setup, prebuild_actions=prebuild)
        assert kept.status == fresh.status == "optimal"
        assert kept.cost_m == pytest.approx(fresh.cost_m, abs=1e-9)
        assert np.array_equal(np.asarray(kept.path), np.asarray(fresh.path))
        fresh_maps.append(_maps_built(alone))
    # The second mission built exactly the maps it needs that the first had not: what the session holds
    # is the union of what each mission builds alone (none for A*, every map when prebuilt).
    assert np.array_equal(_maps_built(session), fresh_maps[0] | fresh_maps[1])
    assert np.array_equal(maps_a, fresh_maps[0])
    assert actions == maps_a.any()
    again = session.plan(first, 0, setup=setup, prebuild_actions=prebuild)  # nothing new at all
    assert session.parts.builds["distance_field"] == len(fields) + len(new_fields)
    assert sum(session.parts.builds.values()) == (7 if actions else 3) + len(fields) + len(new_fields)
    assert again.cost_m == a.cost_m and np.array_equal(np.asarray(again.path), np.asarray(a.path))
    session.plan(first, 0, setup="NO-LLM", robot_radius_m=0.2)  # another grid: its own cell graph and maps
    assert session.builds["grid"] == 2
    maps_built = session.parts.builds["action_maps"]
    assert (session.parts.builds["cell_graph"], maps_built) == (2, 2 if actions else 1)


def test_session_parts_are_bounded_by_bytes_least_recently_used_first(demo) -> None:
    """A session over its byte cap drops the parts used longest ago after a plan, and rebuilds them
    when needed again, with the same result."""
    mission = sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo)
    session = sgplan.Session(demo, max_shared_bytes=0)  # keeps nothing
    first = session.plan(mission, 0, setup="NO-LLM", prebuild_actions=True)
    again = session.plan(mission, 0, setup="NO-LLM", prebuild_actions=True)
    assert len(session.parts) == 0 and session.parts.builds["action_maps"] == 2
    assert again.cost_m == first.cost_m and np.array_equal(again.path, first.path)
    roomy = sgplan.Session(demo)
    roomy.plan(mission, 0, setup="NO-LLM", prebuild_actions=True)
    held = roomy.parts.nbytes()
    (store,) = roomy.parts.kept("action_maps").values()
    assert held >= store.nbytes() > 0
    roomy.parts.max_bytes = held - 1  # one byte short: the oldest part (the cell graph) goes
    assert roomy.parts.trim() < held and roomy.parts.evictions == {"cell_graph": 1}
    assert roomy.parts.kept("action_maps")
    again = roomy.plan(mission, 0, setup="NO-LLM", prebuild_actions=True)  # the graph rebuilt, maps kept
    assert roomy.parts.builds["cell_graph"] == 2 and roomy.parts.builds["action_maps"] == 1
    assert again.cost_m == first.cost_m and np.array_equal(again.path, first.path)


@pytest.mark.parametrize("setup", ["ALL", "NO-LLM"])
def test_action_maps_built_on_demand_or_before_give_the_same_optimum(demo, setup: str) -> None:
    mission = sgplan.mission_from_formula('F("reach(object_28)" & F "enter(room_5)")', demo)
    lazy = sgplan.plan(demo, mission, 0, setup=setup)
    built = sgplan.plan(demo, mission, 0, setup=setup, prebuild_actions=True)
    assert lazy.status == built.status == "optimal" and lazy.verified and built.verified
    assert lazy.cost_m == pytest.approx(built.cost_m, abs=1e-9)


def test_guidance_provenance_and_timeouts_as_results(demo) -> None:
    mission = sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo)
    assert sgplan.plan(demo, mission, setup="no-llm").guidance is None
    guided = sgplan.plan(demo, mission, setup="ALL")
    assert (
        guided.guidance == "offline-symbolic" and mission.guidance is None
    )  # the caller's mission is unchanged
    assert guided.mission is not None and guided.mission.guidance is not None
    cut = sgplan.plan(demo, mission, setup="NO-LLM", max_expansions=1)
    assert cut.status == "timeout" and cut.path is None and cut.to_dict()["cost_m"] is None
    text = guided.to_json()
    record = json.loads(text)
    assert (
        record["mission"]["formula"]
        and "room_" in record["explanation"]["text"]
        and record["verified"] is True
    )
    # The layout plan --json writes: a line per path row, not a line per number.
    lines = text.splitlines()
    first = lines.index(' "path": [') + 1
    assert lines[first:first + len(record["path"])] == [
        f"  {json.dumps(row, separators=(', ', ': '))}," for row in record["path"][:-1]
    ] + [f"  {json.dumps(record['path'][-1], separators=(', ', ': '))}"]


def test_mission_from_text_offline_and_saved(demo, tmp_path: Path) -> None:
    mission = sgplan.mission_from_text("Go to the kitchen.", demo, save_to=tmp_path / "m")
    assert mission.grounded_text == "Go to room_4." and (tmp_path / "m" / "automaton.aut").is_file()
    assert sgplan.load_mission(tmp_path / "m").automaton.num_states == mission.automaton.num_states


def test_a_plan_finds_where_each_proposition_holds_once_for_its_explanation_and_labels(
    demo, monkeypatch: pytest.MonkeyPatch
) -> None:
    import sgplan.explain.scene_labels
    import sgplan.scene.labels as labels

    built: list[str] = []
    real = labels.proposition_cells

    def counted(building: sgplan.api.Building, prop: labels.Proposition, reach_radius_m: float | None = None,
                reach_model: str = "visible") -> np.ndarray:
        built.append(prop.name)
        return real(building, prop, reach_radius_m, reach_model)

    for module in (labels, sgplan.explain.scene_labels):
        monkeypatch.setattr(module, "proposition_cells", counted)
    result = sgplan.plan(demo, sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo), 0, setup="NO-LLM")
    assert result.status == "optimal" and result.explanation_method == "patterns"
    assert sorted(built) == ["enter(room_11)", "enter(room_4)"]


def test_reprs_are_short_and_say_what_they_hold(demo) -> None:
    session = sgplan.Session(demo)
    assert repr(session).startswith("<Session 'demo-house': grids for robot radii none yet, 0 propositions")
    result = session.plan(sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo), start="kitchen")
    text = repr(result)  # was 50,051 characters (every path row and waypoint)
    assert len(text) < 250 and f"cost {result.cost_m:.4f} m over {len(result.path)} cells" in text
    assert "'demo-house'" in text and "room kitchen room_4" in text and "setup ALL" in text
    assert repr(demo) == ("<Building 'demo-house': 2 floors, 11 rooms, 28 objects, grid 210 x 206 cells of "
                          "0.05 m>")  # was 18,308 characters
    assert repr(demo.floors[1]) == "<Floor 1 (B): 5 rooms, grid 210 x 206 cells of 0.05 m>"
    kitchen = "<Room room_4 kitchen (id 2, floor 0): 5 objects, connected to room_2, room_5>"
    assert repr(demo.room(uuid=4)) == kitchen
    assert "grids for robot radii 0.15 m, 2 propositions located" in repr(session)


def test_dir_of_sgplan_is_its_public_api() -> None:
    assert dir(sgplan) == sorted(sgplan.__all__)
    assert not {"Any", "TYPE_CHECKING", "importlib", "annotations", "api"} & set(dir(sgplan))


def test_result_draw_writes_what_plan_draw_writes(demo, tmp_path: Path) -> None:
    result = sgplan.plan(demo, sgplan.mission_from_formula(KITCHEN_THEN_BEDROOM, demo), start="kitchen")
    names = {p.name for p in result.draw(tmp_path / "api")}
    assert main(["plan", "--scene", "demo", "--formula", KITCHEN_THEN_BEDROOM, "--start-room", "kitchen",
                 "--draw", str(tmp_path / "cli"), "-q"]) == 0
    assert names == {p.name for p in (tmp_path / "cli").iterdir()} >= {"plan_floor_0.png", "plan_floor_0.svg"}


@pytest.mark.parametrize(("scene", "name"), [("demo", "bathroom"), ("Allensville", "corridor")])
def test_each_start_suggested_for_an_ambiguous_room_is_accepted(scene: str, name: str) -> None:
    """Allensville's three corridors are all on floor 0: "corridor on floor N" cannot tell them apart."""
    from sgplan.scene.grid import build_occupancy_grid
    from sgplan.starts import start_cell
    from tests import shared_data

    building = shared_data.scene_building(scene)
    grid = build_occupancy_grid(building, building.robot_radius_m or 0.0)
    with pytest.raises(PlanningError) as error:
        start_cell(building, grid, name)
    suggested = re.findall(r"'([^']+)' \(", str(error.value).split("with one of:")[1])
    assert len(suggested) == len(building.rooms_named(name)) >= 2
    rooms = [start_cell(building, grid, spec)[1] for spec in suggested]  # each one is accepted ...
    assert len(set(rooms)) == len(rooms) and all(name in r for r in rooms)  # ... and names its own room
