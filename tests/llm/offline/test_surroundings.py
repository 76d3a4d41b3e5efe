"""The offline translator on what people put around and between the instructions (sign-offs, greetings,
contractions, headings, context, self-corrections, shorthand): ``corpus/surroundings.jsonl`` holds our own
phrasings, each read to its gold formula or refused with its reason."""

from __future__ import annotations

from sgplan.explain import explain_mission
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.translation import mission_of
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_surroundings = corpus_test("surroundings")


def test_times_and_labels_set_aside_are_said_back(demo: Building) -> None:
    text = "Route for this afternoon: the oven, then the couch. Stay out of the office all evening."
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("Route for this afternoon", "all evening")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert said[-2:] == ["Not part of the mission: 'Route for this afternoon'",
                         "Not part of the mission: 'all evening'"]
