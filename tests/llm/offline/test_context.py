"""The offline translator on what surrounds the instructions: statements of any wording, exclamations,
apologies and tag questions set aside and said back, and a statement naming a place followed by *so* and
an order about it (``corpus/context.jsonl``, our own phrasings)."""

from __future__ import annotations

from sgplan.explain import explain_mission
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.translation import mission_of
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_context = corpus_test("context")


def test_statements_and_remarks_set_aside_are_said_back(demo: Building) -> None:
    text = ("Oh gosh, check the oven. Laundry's done, so let's get cracking. "
            "The bathroom downstairs is being painted, so keep out of it.")
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("Oh gosh", "Laundry's done, so let's get cracking",
                                     "The bathroom downstairs is being painted")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert "Not part of the mission: 'Laundry's done, so let's get cracking'" in said


def test_the_pronoun_after_a_statement_is_the_place_it_names(demo: Building) -> None:
    text = "Check the oven. The bathroom downstairs is being painted, so keep out of it."
    translation = PatternTranslator().translate(text, demo)
    avoided = [r for r in translation.references if r.role == "avoid"]
    assert [(r.phrase, r.keys) for r in avoided] == [("The bathroom downstairs", ("room_5",))]


def test_praise_times_guesses_and_purposes_set_aside_are_said_back(demo: Building) -> None:
    text = ("I lost my glasses, most likely somewhere upstairs. This evening stay on the ground floor: "
            "check the oven, you know, to switch it off. Lovely, thank you.")
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("I lost my glasses, most likely somewhere upstairs", "This evening",
                                     "you know, to switch it off", "Lovely, thank you")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert "Not part of the mission: 'This evening'" in said
    assert "Not part of the mission: 'Lovely, thank you'" in said


def test_remarks_after_a_joiner_are_said_back(demo: Building) -> None:
    text = "Check the oven, as usual. Sit on the couch, as discussed."
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("as usual", "as discussed")


def test_fragments_wishes_needs_and_durations_set_aside_are_said_back(demo: Building) -> None:
    text = ("Time for the evening round. Hope you're charged up! The plants need watering. "
            "Water the plant in the office, if that's okay with you. Sit on the couch for a bit.")
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("Time for the evening round", "Hope you're charged up",
                                     "The plants need watering", "if that's okay with you", "for a bit")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert "Not part of the mission: 'Time for the evening round'" in said
    assert "Not part of the mission: 'The plants need watering'" in said


def test_asides_events_and_remarks_of_this_round_are_said_back(demo: Building) -> None:
    text = ("Before you start: pretty sure we're out of milk. Avoid the living room - the carpet's wet - and "
            "check the vase in the dining room, my mum gave it to me, so be gentle. "
            "Before the plumber turns up, check the potted plant in the office. It's a fussy plant lol.")
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("Before you start", "pretty sure we're out of milk", "the carpet's wet",
                                     "my mum gave it to me, so be gentle", "Before the plumber turns up",
                                     "It's a fussy plant lol")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert "Not part of the mission: 'the carpet's wet'" in said
    assert "Not part of the mission: 'It's a fussy plant lol'" in said


def test_results_reasons_after_times_and_hedged_headings_are_said_back(demo: Building) -> None:
    text = ("Two things when you can: check the fridge before lunch so I know what to cook, then look at the "
            "bedroom with the book so it's tidy. For now just keep out of the living room.")
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("when you can", "before lunch", "so I know what to cook", "so it's tidy",
                                     "For now")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert "Not part of the mission: 'so it's tidy'" in said


def test_a_remark_between_two_orders_is_said_back(demo: Building) -> None:
    text = "Check the couch, bear with me, then the oven, no rush."
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("bear with me", "no rush")


def test_headings_times_and_cautions_set_aside_are_said_back(demo: Building) -> None:
    text = ("Heads up: the office is a mess after last night. Quick tidy. Careful, the kitchen is off "
            "limits. After the game tonight, sit on the couch to see if anyone left anything.")
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("Heads up", "the office is a mess after last night",
                                     "Quick tidy", "Careful", "After the game tonight",
                                     "to see if anyone left anything")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert "Not part of the mission: 'After the game tonight'" in said
    assert "Not part of the mission: 'Careful'" in said


def test_a_chore_name_before_a_colon_is_said_back(demo: Building) -> None:
    text = "Dishes: look at the sink in the kitchen, then the couch."
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("Dishes",)
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert "Not part of the mission: 'Dishes'" in said
