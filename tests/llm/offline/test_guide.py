"""The symbolic guide: only valid calls, and following them finishes the mission."""

from __future__ import annotations

import ast

import pytest
import yaml

from sgplan.llm.offline import SYMBOLIC_BACKEND, PatternTranslator, SymbolicGuide
from sgplan.logic import atoms, ltlf_to_dfa, parse_infix, read_hoa
from sgplan.logic.automaton import Automaton
from sgplan.scene.authors import load_authors_scene
from sgplan.scene.model import Building

MISSIONS = [
    "Go to the kitchen, then visit the living room. Always avoid the bathroom on floor 0.",
    "Water the plant in the home office and never enter the living room.",
    "Touch the sink in the bathroom on floor 0 without touching the toilet, then sit on a chair.",
    "Don't enter the kitchen until you have visited the dining room. Then open the fridge.",
    "Visit the bedroom with the teddy bear, the bedroom with the book and the kitchen in that order.",
    "If you go to the kitchen, then wash the bowl. Visit the home office.",
]


def follow(building: Building, automaton: Automaton, room_uuid: int, state: int, calls: list[str],
           ap_actions: dict[str, str]) -> int:
    """Run the calls from (room, state), asserting each is valid; the automaton state at the end."""
    action_bit = {ap_actions.get(ap, ap): 1 << i for i, ap in enumerate(automaton.aps)}
    sinks = automaton.sink_states()
    current = room_uuid
    for call in calls:
        kind, args = call.split("(", 1)
        a, b = (int(x) for x in args.rstrip(")").split(","))
        assert a == current, f"{call} does not start in the current room {current}"
        if kind == "move":
            assert b in building.room(uuid=a).connected_room_uuids, f"{call}: rooms are not connected"
            current = b
            label = action_bit.get(f"enter(room_{b})", 0)
        else:
            assert kind == "reach"
            assert building.object(uuid=b).room_uuid == a, f"{call}: object {b} is not in room {a}"
            label = action_bit.get(f"enter(room_{a})", 0) | action_bit.get(f"reach(object_{b})", 0)
        state = automaton.step(state, label)
        assert not sinks[state], f"{call} leads to a dead automaton state"
    return state


def check_guidance(building: Building, automaton: Automaton, ap_actions: dict[str, str] | None = None) -> int:
    """Every entry is valid and leads to acceptance; returns how many entries are empty."""
    ap_actions = ap_actions or {}
    guidance = SymbolicGuide().guide(building, automaton, ap_actions)
    non_accepting = {q for q in range(automaton.num_states) if not automaton.accepting[q]}
    assert set(guidance) == {r.uuid for r in building.rooms()}
    empty = 0
    for room_uuid, per_state in guidance.items():
        assert set(per_state) == non_accepting
        for q, calls in per_state.items():
            end = follow(building, automaton, room_uuid, q, calls, ap_actions)
            if calls:
                why = f"room {room_uuid}, state {q}: {calls} do not finish the mission"
                assert automaton.accepting[end], why
            else:
                empty += 1
    return empty


def demo_automaton(demo: Building, text: str) -> Automaton:
    formula = PatternTranslator().translate(text, demo).formula
    aps = atoms(formula)
    return ltlf_to_dfa(formula, exclusive=[[p for p in aps if p.startswith("enter(")]])


@pytest.mark.parametrize("text", MISSIONS)
def test_guidance_is_valid_and_finishes_the_mission(demo, text):
    automaton = demo_automaton(demo, text)
    check_guidance(demo, automaton)
    # The demo building is connected, so every live non-accepting state gets calls in every room.
    guidance = SymbolicGuide().guide(demo, automaton)
    live = automaton.live_states()
    for per_state in guidance.values():
        for q, calls in per_state.items():
            assert bool(calls) == bool(live[q])


def test_guidance_is_shortest_and_deterministic(demo):
    automaton = demo_automaton(demo, "Visit the kitchen.")
    guidance = SymbolicGuide().guide(demo, automaton)
    assert SymbolicGuide().name == SYMBOLIC_BACKEND == "offline-symbolic"
    assert guidance == SymbolicGuide().guide(demo, automaton)
    kitchen = demo.rooms_named("kitchen")[0]
    corridor = demo.rooms_named("corridor", floor=0)[0]
    bedroom = demo.rooms_named("bedroom")[0]
    q0 = automaton.initial
    assert guidance[corridor.uuid][q0] == [f"move({corridor.uuid}, {kitchen.uuid})"]
    # From upstairs: down the staircase, through the corridor, into the kitchen.
    path = guidance[bedroom.uuid][q0]
    assert path[-1] == f"move({corridor.uuid}, {kitchen.uuid})"
    assert any(demo.room(uuid=int(c.split("(")[1].split(",")[0])).is_staircase for c in path)


def test_guidance_respects_always_avoid(demo):
    # "Visit the dining room. Never enter the corridor on floor 0.": the translator refuses it (no way in),
    # the guide is still asked and must keep out of the corridor
    formula = parse_infix('F "enter(room_7)" & G !"enter(room_2)"')
    automaton = ltlf_to_dfa(formula, exclusive=[["enter(room_7)", "enter(room_2)"]])
    guidance = SymbolicGuide().guide(demo, automaton)
    corridor = demo.rooms_named("corridor", floor=0)[0]
    for per_state in guidance.values():
        for calls in per_state.values():
            assert not any(c.endswith(f", {corridor.uuid})") and c.startswith("move") for c in calls)
    # The dining room is reached only through that corridor, so no room outside it gets calls.
    kitchen = demo.rooms_named("kitchen")[0]
    assert guidance[kitchen.uuid][automaton.initial] == []


@pytest.mark.gibson
@pytest.mark.parametrize("scene", ["Allensville", "Benevolence", "Collierville"])
def test_guidance_on_the_shipped_automata(gibson_root, scene):
    building = load_authors_scene(gibson_root / scene)
    empty_total = 0
    for mission in sorted((gibson_root / scene / "missions").iterdir()):
        automaton = read_hoa(mission / "automaton.aut")
        ap_dict = ast.literal_eval((mission / "ap_dict.txt").read_text())
        ap_actions = {name: token for token, name in ap_dict.items()}
        empty_total += check_guidance(building, automaton, ap_actions)
        guidance = SymbolicGuide().guide(building, automaton, ap_actions)
        yaml.safe_load(yaml.safe_dump(guidance))  # the llm_heuristic.yaml format round-trips
    assert empty_total >= 0
