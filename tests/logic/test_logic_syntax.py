"""Formula syntaxes: infix, LBT prefix, LLM token lists; printers, round trips and precise errors."""

from __future__ import annotations

import pytest
from hypothesis import given, settings

from sgplan.errors import FormulaError
from sgplan.logic import (
    Always,
    And,
    Atom,
    Eventually,
    Implies,
    Next,
    Not,
    Or,
    Release,
    Until,
    WeakNext,
    atoms,
    equivalent,
    number_aps,
    parse_infix,
    parse_prefix,
    parse_tokens,
    to_infix,
    to_prefix,
    to_tokens,
)
from sgplan.logic.formula import Const, walk
from tests.logic.oracle import formulas

p1, p2, p3 = Atom("p1"), Atom("p2"), Atom("p3")


def test_infix_examples():
    assert parse_infix("F(p1 & F p2) & G !p3") == And(
        (Eventually(And((p1, Eventually(p2)))), Always(Not(p3)))
    )
    assert parse_infix("p1 -> p2 -> p3") == Implies(p1, Implies(p2, p3))
    assert parse_infix("p1 U p2 & p3") == And((Until(p1, p2), p3))  # U binds tighter, as in Spot
    assert parse_infix("GFp1") == Always(Eventually(p1))
    assert parse_infix("true R false") == Release(Const(True), Const(False))
    assert parse_infix('"enter(room_2)" | [] <> x') == Or(
        (Atom("enter(room_2)"), Always(Eventually(Atom("x"))))
    )


def test_next_dialects():
    assert parse_infix("X p1") == Next(p1)
    assert parse_infix("X[!] p1") == Next(p1)
    assert parse_infix("X p1", dialect="spot") == WeakNext(p1)
    assert to_infix(Next(p1), dialect="spot") == "X[!] p1"
    assert to_infix(WeakNext(p1)) == "!X !p1"


def test_prefix_examples():
    f = parse_prefix("& & F & p1 ! p2 F & p3 p4 G & ! p5 ! p6")
    assert atoms(f) == ("p1", "p2", "p3", "p4", "p5", "p6")
    assert to_prefix(f) == "& & F & p1 ! p2 F & p3 p4 G & ! p5 ! p6"
    assert parse_prefix("i p1 e p2 t") == Implies(p1, parse_infix("p2 <-> true"))
    assert equivalent(parse_prefix("W p1 p2"), parse_infix("(p1 U p2) | G p1"))
    assert equivalent(parse_prefix("M p1 p2"), parse_infix("(p1 R p2) & F p1"))


@settings(max_examples=150, deadline=None)
@given(formulas(("p1", "q", "enter(room_2)"), max_leaves=10))
def test_printers_round_trip(formula):
    # The sgplan dialect writes weak next as !X!, which reads back as an equivalent formula.
    if any(isinstance(n, WeakNext) for n in walk(formula)):
        assert equivalent(parse_infix(to_infix(formula)), formula)
    else:
        assert parse_infix(to_infix(formula)) == formula
    assert parse_infix(to_infix(formula, "spot"), "spot") == formula
    # LBT has no weak next; it is written !X! and reads back as an equivalent formula.
    assert equivalent(parse_prefix(to_prefix(formula)), formula)


@settings(max_examples=100, deadline=None)
@given(formulas(("enter(room_2)", "reach(object_7)", "enter(room_10)"), max_leaves=10))
def test_tokens_round_trip(formula):
    if any(isinstance(n, Const) for n in walk(formula)):
        with pytest.raises(FormulaError, match="no constant"):
            to_tokens(formula)
        return
    tokens = to_tokens(formula)
    assert equivalent(parse_tokens(tokens), formula)
    assert equivalent(parse_tokens(repr(tokens)), formula)


def test_tokens_vocabulary_and_ap_names():
    tokens = [
        "AND", "EVENTUALLY", "AND", "enter(room_2)", "NEGATION", "reach(object_27)", "ALWAYS", "IMPLY",
        "NEXT", "enter( room_3 )", "UNTIL", "not", "enter(room_2)", "reach(object_27)",
    ]
    f = parse_tokens(tokens)
    assert atoms(f) == ("enter(room_2)", "reach(object_27)", "enter(room_3)")
    names = number_aps(tokens)
    assert names == {"enter(room_2)": "p1", "reach(object_27)": "p2", "enter(room_3)": "p3"}
    g = parse_tokens(tokens, ap_names=names)
    assert atoms(g) == ("p1", "p2", "p3")
    back = to_tokens(g, ap_tokens={v: k for k, v in names.items()})
    assert parse_tokens(back) == parse_tokens(
        [
            "AND", "EVENTUALLY", "AND", "enter(room_2)", "NOT", "reach(object_27)", "ALWAYS", "IMPLY", "NEXT",
            "enter(room_3)", "UNTIL", "NOT", "enter(room_2)", "reach(object_27)",
        ]
    )
    assert to_tokens(parse_infix("a R b"), {"a": "enter(room_1)", "b": "enter(room_2)"}) == [
        "NOT", "UNTIL", "NOT", "enter(room_1)", "NOT", "enter(room_2)"]


@pytest.mark.parametrize(
    ("tokens", "message", "position"),
    [
        ([], "the list is empty", None),
        ("[]", "the list is empty", None),
        (["AND", "enter(room_2)"], "token 0 'AND' needs 2 operands but the list ends after 1", 0),
        (
            ["AND", "enter(room_2)", "EVENTUALLY"],
            "token 2 'EVENTUALLY' needs 1 operand but the list ends after 0", 2,
        ),
        (["THEN", "enter(room_2)"], "token 0 'THEN' is not an operator (NOT, NEGATION,", 0),
        (
            ["EVENTUALLY", "reach(object_99)"],
            "token 1 'reach(object_99)' names object_99, which is not a known", 1,
        ),
        (
            ["EVENTUALLY", "enter(object_27)"],
            "token 1 'enter(object_27)' is malformed: enter takes a room_<id>", 1,
        ),
        (
            ["enter(room_2)", "enter(room_2)", "ALWAYS"],
            "the formula is complete at token 0 but 2 more tokens follow, starting with token 1 "
            "'enter(room_2)'",
            1,
        ),
        (["NOT", 5], "token 1 is 5 (an int), not a string", 1),
        ("['AND', 'enter(room_2)'", "the formula is not a Python list of quoted tokens", None),
        ("{'AND': 1}", "the formula must be a list of tokens, got a dict", None),
    ],
)
def test_token_errors_are_precise(tokens, message, position):
    with pytest.raises(FormulaError) as info:
        parse_tokens(tokens, known={"room_2", "object_27"})
    assert str(info.value).startswith(message)
    assert info.value.position == position


def test_ap_mapping_must_cover_every_action():
    with pytest.raises(FormulaError, match="token 1 'enter\\(room_3\\)' has no proposition name"):
        parse_tokens(["EVENTUALLY", "enter(room_3)"], ap_names={"enter(room_2)": "p1"})


@pytest.mark.parametrize(
    ("text", "message", "position"),
    [
        ("", "the formula is empty", None),
        ("F(p1 & p2", "the parenthesis opened at character 1 is not closed: found the end of the formula", 9),
        ("p1 &", "the formula ends at character 4 where an operand is expected", 4),
        ("p1 p2", "unexpected 'p2' at character 3 after a complete formula", 3),
        ("F enter(room_5)", "unexpected '(' at character 7 after a complete formula; a proposition with "
         'parentheses goes in double quotes, e.g. "enter(...)"', 7),
        ("p1 & )", "unexpected ')' at character 5 where an operand is expected", 5),
        ("a $ b", "unexpected character '$' at character 2", 2),
        ('"abc', "the quoted proposition at character 0 is never closed", 0),
    ],
)
def test_infix_errors_are_precise(text, message, position):
    with pytest.raises(FormulaError) as info:
        parse_infix(text)
    assert str(info.value).startswith(message)
    assert info.value.position == position


@pytest.mark.parametrize(
    ("text", "message", "position"),
    [
        ("  ", "the formula is empty", None),
        ("& p1", "token 0 '&' (character 0) needs 2 operands but the formula ends after 1", 0),
        (
            "F p1 p2",
            "the formula is complete at token 1 but 1 more token follows, starting with token 2 'p2'", 5,
        ),
        ("& p1 ( p2", "token 2 '(' (character 5) is neither an operator", 5),
    ],
)
def test_prefix_errors_are_precise(text, message, position):
    with pytest.raises(FormulaError) as info:
        parse_prefix(text)
    assert str(info.value).startswith(message)
    assert info.value.position == position


def test_deep_inputs_do_not_overflow():
    deep = ["NOT"] * 5000 + ["enter(room_2)"]
    assert isinstance(parse_tokens(deep), Not)
    with pytest.raises(FormulaError, match="nests too deeply"):
        parse_infix("(" * 5000 + "p" + ")" * 5000)
