"""Order read by the offline translator: then, first, before that, last, after / before X, once done, on the
way, via, comma lists, order remarks, only after.

Each sentence of ``corpus/order.jsonl`` must mean its gold formula or be refused with
its fragment."""

from __future__ import annotations

import pytest

from sgplan.errors import MissionError
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.meaning.compose import Clause, Task, check_text_order, moved
from sgplan.logic import parse_infix
from sgplan.logic.formula import Atom
from sgplan.scene.model import Building
from tests.llm.offline.corpus import corpus_test

test_order_read_or_refused = corpus_test("order")


def said(start: int, end: int) -> str:
    """The text between two offsets, as the guard quotes it: here, the offset itself."""
    return f"goal at {start}"


def test_the_order_guard_refuses_a_goal_read_after_one_the_text_states_after_it() -> None:
    kitchen = Task("all", [Atom("enter(room_4)")], said_at=0)  # "Go to the kitchen, (then?) the office"
    office = Task("all", [Atom("enter(room_12)")], said_at=20)
    with pytest.raises(MissionError, match="'goal at 0' is said before 'goal at 20' but would be done after"):
        check_text_order(Clause(steps=[[office], [kitchen]]), said)
    check_text_order(Clause(steps=[[kitchen], [office]]), said)  # in the text's order
    check_text_order(Clause(steps=[[kitchen, office]]), said)  # in any order


def test_the_order_guard_lets_an_explicit_word_reorder() -> None:
    office = Task("all", [Atom("enter(room_12)")], said_at=0)  # "Go to the office, but first the kitchen"
    kitchen = Task("all", [Atom("enter(room_4)")], said_at=30)
    check_text_order(Clause(steps=[*moved([[kitchen]]), [office]]), said)
    assert kitchen.moved and not office.moved


def test_explicit_words_may_read_goals_out_of_the_text_order(demo: Building) -> None:
    for text in ("Go to the office, but first go to the kitchen.", "Go to the office after the kitchen.",
                 "Before going to the office, visit the kitchen.", "Go to the office via the kitchen.",
                 "Go to the office. Before that, go to the kitchen."):
        assert PatternTranslator().translate(text, demo).formula == parse_infix(
            'F("enter(room_4)" & F "enter(room_12)")'), text
