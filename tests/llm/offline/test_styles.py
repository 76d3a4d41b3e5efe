"""The offline translator on the styles people write to robots in, each a corpus of our own phrasings
(``corpus/style_<style>.jsonl``): every sentence means its gold formula or gets its refusal."""

from __future__ import annotations

from sgplan.explain import explain_mission
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.translation import mission_of
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_shorthand = corpus_test("style_shorthand")
test_errands = corpus_test("style_errands")
test_polite = corpus_test("style_polite")
test_times_and_places = corpus_test("style_timeplace")
test_voice = corpus_test("style_voice")
test_dictation = corpus_test("style_dictation")
test_lists = corpus_test("style_lists")
test_constraints = corpus_test("style_constraints")
test_nonnative = corpus_test("style_nonnative")


def test_context_is_set_aside_and_said_back(demo: Building) -> None:
    text = ("We're hosting dinner tonight. Water the plant in the office, then check the couch. The guests "
            "arrive at seven, so no rush.")
    translation = PatternTranslator().translate(text, demo)
    assert translation.set_aside == ("We're hosting dinner tonight", "The guests arrive at seven, so no rush")
    said = explain_mission(mission_of(translation), demo).text.splitlines()
    assert said[-2:] == ["Not part of the mission: 'We're hosting dinner tonight'",
                         "Not part of the mission: 'The guests arrive at seven, so no rush'"]


def test_a_list_heading_that_says_more_than_a_label_is_said_back(demo: Building) -> None:
    translation = PatternTranslator().translate("Shopping run:\n- the fridge\n- the bowl", demo)
    assert translation.set_aside == ("Shopping run",)
    assert PatternTranslator().translate("Tasks:\n1. the fridge\n2. the bowl", demo).set_aside == ()
