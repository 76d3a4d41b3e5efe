"""Missions: the authors' folders, formula missions, round trips and bad input."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.errors import MissionError
from sgplan.logic import equivalent, ltlf_to_dfa
from sgplan.mission import compile_mission, load_mission_folder, parse_formula, save_mission_folder
from sgplan.scene.demo import demo_building
from sgplan.scene.labels import Proposition

MISSIONS = [(scene, k) for scene in ("Allensville", "Benevolence", "Collierville") for k in range(1, 6)]


@pytest.mark.gibson
@pytest.mark.parametrize(("scene", "number"), MISSIONS)
def test_shipped_missions_load_and_match_their_formula(gibson_root: Path, scene: str, number: int) -> None:
    mission = load_mission_folder(gibson_root / scene / "missions" / str(number))
    assert mission.text and mission.grounded_text and mission.guidance
    # GPT_LTL_formula.txt (read through ap_dict.txt) means what automaton.aut means, read as a complete DFA
    # (Spot simplified Allensville 3's p3 away: the languages are compared over the union of APs)
    assert equivalent(mission.formula, mission.automaton)
    assert {p.kind for p in mission.propositions.values()} <= {"enter", "reach"}


@pytest.mark.gibson
def test_profiles_change_missing_edges(gibson_root: Path) -> None:
    folder = gibson_root / "Benevolence" / "missions" / "1"  # incomplete automaton: 192 missing pairs
    strict, stay = load_mission_folder(folder, "ltlf"), load_mission_folder(folder, "authors")
    assert strict.automaton.num_states == stay.automaton.num_states + 1  # the rejecting sink
    assert not equivalent(strict.automaton, stay.automaton)


def test_formula_mission_round_trips_through_a_folder(tmp_path: Path) -> None:
    building = demo_building()
    room, other = list(building.rooms())[:2]
    obj = next(building.objects())
    tokens = ["AND", "EVENTUALLY", "AND", f"enter({room.key})", f"reach({obj.key})",
              "ALWAYS", "NOT", f"enter({other.key})"]
    mission = compile_mission(tokens, text="go", grounded_text="go uuid",
                                   guidance={room.uuid: {0: [f"reach({room.uuid}, {obj.uuid})"]}})
    mission.check_scene(building)
    assert mission.labels(building).shape == (building.num_floors, *building.grid_shape)
    folder = save_mission_folder(mission, tmp_path / "m", hierarchy_text="Building description: x")
    back = load_mission_folder(folder)
    assert back.automaton.aps == ("p1", "p2", "p3")
    assert [p.name for p in back.ordered_propositions] == [p.name for p in mission.ordered_propositions]
    renamed = ltlf_to_dfa(back.formula, aps=back.automaton.aps)
    assert equivalent(renamed, back.automaton)
    assert back.text == "go" and back.grounded_text == "go uuid"
    assert back.guidance == {room.uuid: {0: [f"reach({room.uuid}, {obj.uuid})"]}}


def test_parse_formula_accepts_three_syntaxes() -> None:
    a, b = "enter(room_2)", "reach(object_3)"
    infix = parse_formula(f'F("{a}" & F "{b}")')
    prefix = parse_formula(f'F & "{a}" F "{b}"')
    tokens = parse_formula(str(["EVENTUALLY", "AND", a, "EVENTUALLY", b]))
    assert equivalent(ltlf_to_dfa(infix), ltlf_to_dfa(prefix))
    assert equivalent(ltlf_to_dfa(infix), ltlf_to_dfa(tokens))


def test_unknown_proposition_names_need_a_meaning() -> None:
    with pytest.raises(MissionError, match="'kitchen' is neither"):
        compile_mission("F kitchen")
    mission = compile_mission("F kitchen", {"kitchen": Proposition("enter", 2)})
    assert mission.propositions["kitchen"].uuid == 2


def test_mission_naming_absent_entities_is_refused() -> None:
    mission = compile_mission('F "enter(room_999)"')
    with pytest.raises(MissionError, match=r"does not have: enter\(room_999\) \(its rooms: room_2, room_4, .*"
                                           r"room_14; `sgplan inspect` lists them with their objects\)"):
        mission.check_scene(demo_building())


def test_bad_folders(tmp_path: Path) -> None:
    with pytest.raises(MissionError, match="does not exist"):
        load_mission_folder(tmp_path / "nope")
    folder = save_mission_folder(compile_mission('F "enter(room_2)"'), tmp_path / "m")
    (folder / "ap_desc.yaml").write_text("p1: {type: kTeleport, uuid: 2}\n")
    with pytest.raises(MissionError, match="unknown type 'kTeleport'"):
        load_mission_folder(folder)
    (folder / "ap_desc.yaml").write_text("p7: {type: kEnterRoom, uuid: 2}\n")
    with pytest.raises(MissionError, match=r"uses p1, which ap_desc.yaml does not define"):
        load_mission_folder(folder)
    (folder / "ap_desc.yaml").write_text("p1: [unclosed\n")
    with pytest.raises(MissionError, match="invalid YAML"):
        load_mission_folder(folder)
    (folder / "ap_desc.yaml").unlink()
    with pytest.raises(MissionError, match=r"missing ap_desc.yaml"):
        load_mission_folder(folder)
