"""Grounding replies: ID extraction, strict parsing, invented IDs, problem reports and their messages."""

from __future__ import annotations

import json

import pytest

from sgplan.llm.grounding import (
    ReferenceProblem,
    ReplyError,
    building_ids,
    describe_id,
    extract_ids,
    parse_grounding_reply,
    rephrase_message,
)
from sgplan.scene.demo import demo_building


@pytest.fixture(scope="module")
def demo():
    return demo_building()


@pytest.fixture(scope="module")
def known(demo):
    return building_ids(demo)


def test_extract_ids_in_order_without_duplicates_or_partial_words() -> None:
    text = "Reach object_21 in room_5, then room_7; not myroom_3 nor room_5x. Again object_21."
    assert extract_ids(text) == ("object_21", "room_5", "room_7")


def test_reply_with_fences_and_prose_is_read(known) -> None:
    reply = 'Sure!\n```json\n{"grounded": "Visit room_5.", "problems": []}\n```'
    assert parse_grounding_reply(reply, known) == ("Visit room_5.", [])


@pytest.mark.parametrize(
    ("reply", "fragment"),
    [
        ("Visit room_5.", "no JSON object"),
        ('{"grounded": "Visit room_5.", "problems": [}', "not valid JSON"),
        ('{"grounded": "", "problems": []}', "non-empty string"),
        ('{"grounded": "Visit room_5."}', None),  # problems default to []
        ('{"grounded": "Visit room_99 and object_5.", "problems": []}', "room_99, object_5 are not an ID"),
        ('{"grounded": "x room_5", "problems": [{"kind": "ambiguous"}]}', "phrase"),
        ('{"grounded": "x room_5", "problems": [{"phrase": "p", "kind": "odd"}]}', "kind"),
    ],
)
def test_bad_replies_name_the_defect(reply: str, fragment: str | None, known) -> None:
    if fragment is None:
        assert parse_grounding_reply(reply, known) == ("Visit room_5.", [])
        return
    with pytest.raises(ReplyError, match=fragment):
        parse_grounding_reply(reply, known)


def test_problem_candidates_keep_only_real_ids(known) -> None:
    reply = json.dumps({"grounded": "Go to the bathroom.", "problems": [
        {"phrase": "the bathroom", "kind": "ambiguous", "candidates": ["room_5", "room_14", "room_77"]}]})
    _, problems = parse_grounding_reply(reply, known)
    assert problems == [ReferenceProblem("the bathroom", "ambiguous", ("room_5", "room_14"))]


def test_rephrase_message_names_phrases_and_candidates(demo) -> None:
    message = rephrase_message("Go to the bathroom, then the garage.", [
        ReferenceProblem("the bathroom", "ambiguous", ("room_5", "room_14")),
        ReferenceProblem("the garage", "unresolved", ()),
    ], demo)
    assert "'the bathroom' could be any of room_5 (bathroom, floor 0), room_14 (bathroom, floor 1)" in message
    assert "'the garage' matches no room or object" in message and "Rephrase" in message


def test_describe_id_of_an_object_names_its_room_and_floor(demo) -> None:
    assert describe_id(demo, "object_41") == "object_41 (sink in room_14, floor 1)"
