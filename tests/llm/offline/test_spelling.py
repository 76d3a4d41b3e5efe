"""Unknown words and the known words they look like: a refusal names every one at once (*did you mean*),
and a misspelt room or object in the verb slot is refused, never taken for a verb."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.names import SceneVocabulary
from sgplan.llm.offline.spelling import Spelling
from sgplan.scene.model import Building


def test_a_refusal_names_every_unknown_word_at_once(demo: Building) -> None:
    with pytest.raises(MissionError) as refused:
        PatternTranslator().translate("Go to the kitchn, then the livng room and the bathrom upstairs.", demo)
    assert "did you mean 'kitchen' for 'kitchn', 'living' for 'livng', 'bathroom' for 'bathrom'?" in str(
        refused.value)


def test_a_misspelt_noun_in_the_verb_slot_is_refused_not_read_as_a_verb(demo: Building) -> None:
    # read as a verb, "bathrom" would be dropped and the sink of any room would do
    with pytest.raises(MissionError, match=r"cannot understand 'bathrom'.*did you mean 'bathroom'"):
        PatternTranslator().translate("Go to the kitchen, then bathrom sink.", demo)


def test_a_word_without_a_vowel_is_no_verb(demo: Building) -> None:
    with pytest.raises(MissionError, match="cannot understand 'bthrmx'"):
        PatternTranslator().translate("Go to the kitchen, then bthrmx sink.", demo)


def test_a_negated_typo_gets_its_verb_suggested(demo: Building) -> None:
    with pytest.raises(MissionError, match="'tuch' is neither; did you mean 'touch' for 'tuch'"):
        PatternTranslator().translate("Go to the kitchen and don't tuch the oven.", demo)


def test_words_of_english_with_an_ending_are_not_corrected(demo: Building) -> None:
    spelling = Spelling(SceneVocabulary(demo).nouns)
    assert spelling.suggestion("seen") is None  # see + n
    assert spelling.suggestion("pets") is None  # pet + s
    assert spelling.suggestion("kitchn") == "kitchen"
    said = spelling.did_you_mean(["go", "to", "the", "kitchn", "kitchn"])
    assert said == "did you mean 'kitchen' for 'kitchn'?"
    assert spelling.did_you_mean(["go", "to", "the", "kitchen"]) == ""


@pytest.mark.parametrize(("word", "misspelt"), [("dripping", False), ("leaking", False), ("dinning", True),
                                                 ("kitchn", True), ("bedrooom", True), ("livng", True)])
def test_a_shared_ending_is_no_misspelling(demo: Building, word: str, misspelt: bool) -> None:
    """*dripping* shares *-ing* with *dining*, but *dripp* is far from *din*: an English word to set aside."""
    assert Spelling(SceneVocabulary(demo).nouns).may_be_a_misspelt_name(word) is misspelt
