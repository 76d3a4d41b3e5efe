"""The clauses and the order of steps as people write them (branch `steps`): a closing *when you're
done*, *once you've done that / both*, *after all that* opening a sentence, learners' order words.

Each sentence of ``corpus/steps.jsonl`` must mean its gold formula or be refused with its fragment."""

from __future__ import annotations

from sgplan.llm.offline import PatternTranslator
from sgplan.scene.demo import demo_building
from tests.llm.offline.corpus import corpus_test

test_steps_read_or_refused = corpus_test("steps")


def test_a_clause_that_says_nothing_is_needed_is_said_back_as_set_aside() -> None:
    t = PatternTranslator().translate("Go to the kitchen. Don't bother tidying up.", demo_building())
    assert t.set_aside == ("Don't bother tidying up",)


def test_a_heading_that_names_the_work_is_said_back_as_set_aside() -> None:
    t = PatternTranslator().translate("Bathroom duty: go to the bathroom upstairs and check the sink.",
                                      demo_building())
    assert t.set_aside == ("Bathroom duty",)
