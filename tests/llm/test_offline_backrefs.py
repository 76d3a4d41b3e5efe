"""Back-references in the offline translator (own sentences over the four scenes): a demonstrative (*that
X*, *this X*, *those X*, *the same X*) names again the phrase it points back to, never a fresh description;
*it*, *there*, *up there*, *its*, *next to it* pointing back to a choice are refused (which one depends on
the choice the robot makes); what cannot be resolved is refused, naming it."""

from __future__ import annotations

import pytest

from tests.llm.offline_reading import means, refused
from tests.shared_data import scene_building

# Allensville: room_2 bathroom (o16 sink, o20 vase, o33 toilet), room_4 bathroom (o18 sink, o34 toilet),
# room_6 bedroom (o24 vase, o45 bed), room_10 dining room (o36, o37 chairs), room_11 kitchen, room_12
# living room, room_13 lobby (o25-o28 vases). Benevolence: room_7 bedroom (o30 book, o34 vase, o54 bed),
# room_8 bedroom (o35 teddy bear, o59 tv), room_6 bathroom next to it, room_15 kitchen (o31, o32
# bottles), room_16 living room. Collierville: room_2 bathroom floor 1 (o25, o26 sinks), room_4
# bathroom floor 2 (o36, o37 toilets; o38 toilet in room_2), room_7 bedroom with the plant, room_14
# office (o59-o61 tvs), room_15 kitchen, room_16 living room (o35 vase). demo: room_5 / room_14
# bathrooms (o41 sink in room_14), room_4 kitchen, room_6 living room, room_12 office.


building = scene_building


@pytest.mark.parametrize(
    ("scene", "text", "gold"),
    [
        # 'that X' across sentences: the X named last, not any X
        ("Collierville", "Go to the bathroom on the top floor. Then use one of the toilets in that bathroom.",
         "F(r4 & F((o36 & r4) | (o37 & r4)))"),
        ("Collierville", "You may enter the bathroom on the top floor only once you have been to the bedroom "
                         "with the plant. Flush one of the toilets in that bathroom.",
         "(!r4 U r7) & F(o36 | o37)"),
        ("Collierville", "Go into the bathroom on floor 1, then touch a sink in this bathroom.",
         "F(r2 & F((o25 & r2) | (o26 & r2)))"),
        ("Collierville",
         "Visit the bathroom on the top floor, then the kitchen, then go back to that bathroom.",
         "F(r4 & F(r15 & F(!r4 & F r4)))"),
        # 'that room' after a phrase with a nested one: the phrase's head, not the nested room
        ("Benevolence", "Check the bed in the bedroom with the vase, then the book in that room.",
         "F(o54 & r7 & F(o30 & r7))"),
        ("Benevolence",
         "Go to the bedroom with the teddy bear. Then go to the bathroom next to that bedroom.",
         "F(r8 & F r6)"),
        ("Benevolence", "Go to the kitchen, then the living room. Then go to that kitchen again.",
         "F(r15 & F(r16 & F(!r15 & F r15)))"),
        ("Benevolence", "If you go into the kitchen, grab a bottle in that kitchen.",
         "F r15 -> F((o31 & r15) | (o32 & r15))"),
        # the same X, this X, those Xs
        ("Allensville", "Go to the bathroom with the vase, then the lobby, then back to the same bathroom.",
         "F(r2 & F(r13 & F(!r2 & F r2)))"),
        ("Allensville", "Go to the dining room. Check one of the chairs in this room.",
         "F r10 & F((o36 & r10) | (o37 & r10))"),
        ("Collierville", "Check the TVs in the office. Then go to the kitchen and come back to those TVs.",
         "F(o59 & r14 & F(r15 & F(o59 & r14) & F(o60 & r14) & F(o61 & r14)))"
         " & F(o60 & r14 & F(r15 & F(o59 & r14) & F(o60 & r14) & F(o61 & r14)))"
         " & F(o61 & r14 & F(r15 & F(o59 & r14) & F(o60 & r14) & F(o61 & r14)))"),
        ("demo", "Visit both bathrooms, then the kitchen, then those bathrooms again.",
         "F(r5 & F(r4 & F(!r5 & F r5) & F(!r14 & F r14)))"
         " & F(r14 & F(r4 & F(!r5 & F r5) & F(!r14 & F r14)))"),
        ("Collierville", "Go to the bathroom on the top floor. Then use a toilet in that top floor bathroom.",
         "F(r4 & F((o36 & r4) | (o37 & r4)))"),
        ("Benevolence", "Visit both bedrooms. Then the kitchen. Then one of those bedrooms again.",
         "F(r7 & F(r15 & F(!(r7 | r8) & F(r7 | r8)))) & F(r8 & F(r15 & F(!(r7 | r8) & F(r7 | r8))))"),
        ("demo", "Go to the bathroom upstairs, then wash at the sink in that bathroom.",
         "F(r14 & F(o41 & r14))"),
    ],
)
def test_back_references_read(scene, text, gold):
    b = building(scene)
    means(text, gold, b)


@pytest.mark.parametrize(
    ("scene", "text", "fragment"),
    [
        # nothing named before that fits
        ("Collierville", "Look at the sink in that bathroom.", "'that bathroom' does not refer back"),
        ("Allensville", "Go to this room.", "'this room' does not refer back"),
        ("Allensville", "Go to the living room. Never enter that kitchen.",
         "'that kitchen' does not refer back"),
        ("Allensville", "Go to the lobby. Look at those vases.", "'those vases' does not refer back"),
        # what the phrase adds must agree with what it refers to
        ("Collierville", "Go to the bathroom on floor 1, then to that bathroom on the top floor.",
         "which does not fit"),
        # singular after a group
        ("demo", "Visit both bathrooms, then go back to that bathroom.", "which is several"),
        # pointing back to a choice: which one depends on the choice
        ("Allensville", "Look at a vase in the lobby, then look at that vase again.", "a choice"),
        ("Allensville", "Look at a vase in the lobby, then look at it again.", "a choice"),
        ("Allensville", "Go to the kitchen or the living room and clean it.", "one alternative of a choice"),
        ("Collierville", "Go to the kitchen or the living room, then look at the vase in that room.",
         "one alternative of a choice"),
        ("Collierville", "Go to the kitchen or the living room, then look at the vase there.", "a choice"),
        ("Allensville", "Go to a bathroom and flush the toilet there.",
         "'there' refers back to 'a bathroom'"),
        ("Allensville", "Go to a bathroom, then wash at the sink in there.", "a choice"),
        ("Allensville", "Look at a vase in the lobby, but don't touch it.", "a choice"),
        ("Allensville", "Go to a bathroom, then the sink in the same room.", "'the same room' refers back"),
        ("Allensville", "Go to a bathroom, then use its sink.", "'its' refers back"),
        ("Benevolence", "Visit any bathroom, then go to the bedroom up there.", "'up there' refers back"),
        # 'that room' / 'the same room' as a place to go after several rooms: which one?
        ("demo", "Go to the kitchen, then the office, then back to that room.", "'that room': which one?"),
        # a quantifier before the demonstrative chooses among what it points back to, never among all
        ("Benevolence", "Go to the bedroom with the vase and the kitchen. Then go to one of those bedrooms.",
         "which is one (room_7), not several"),
        ("Benevolence", "Visit the bathroom on floor 0 and the kitchen. Then check all of those sinks.",
         "does not refer back"),
        # 'there' after several places, and 'back there' (the place named last is where the robot just was)
        ("Benevolence", "Look at the kitchen and both bedrooms. Then get there.", "several places"),
        ("Allensville", "Visit the bedroom with the vase, then the kitchen, then go back there.",
         "'back there'"),
        ("demo", "Go to the kitchen. Then the office, and return there.", "'back there'"),
        # the guard: a demonstrative is never read as a fresh description, whatever stands before the noun
        ("Collierville", "Go to the bathroom on floor 1. Then go to that top floor bathroom.",
         "does not fit"),
        ("demo", "Go to the kitchen, then that other bathroom.", "'other'"),
        ("Allensville", "Go to the kitchen. Then check those.", "'those"),
        # the former / the latter
        ("Allensville", "Visit the lobby and the kitchen. Then go back to the former.", "'the former'"),
        ("Allensville", "Visit the lobby and the kitchen. Then go back to the latter.", "'the latter'"),
        ("Allensville", "Go to the kitchen, then that one.", "'one'"),
    ],
)
def test_unresolvable_back_references_refused(scene, text, fragment):
    refused(text, fragment, building(scene))


@pytest.mark.parametrize(
    ("scene", "text", "gold"),
    [
        # a pronoun after a choice is fine where it only carries the object
        ("Allensville", "Grab a bowl and bring it to the dining room.", "F((o29 | o30) & F r10)"),
        ("Benevolence", "Grab a bottle in the kitchen. Bring it to the living room.",
         "F((o31 & r15) | (o32 & r15)) & F r16"),
        # and after a single thing it is that thing
        ("Allensville", "Take the bowl in the kitchen and put it in the living room.",
         "F(o29 & r11 & F r12)"),
    ],
)
def test_pronouns_still_read(scene, text, gold):
    b = building(scene)
    means(text, gold, b)


@pytest.mark.parametrize(
    ("scene", "start", "text", "gold"),
    [
        # a floor move before an action is where the action is done, not a goal of its own
        ("Benevolence", None, "go up to the top floor and check a bathroom there", "F(r4 | r6)"),
        ("Benevolence", None, "Go up to the top floor and use a bathroom.", "F(r4 | r6)"),
        ("Benevolence", None, "Go to the top floor, then check a bathroom.", "F(r4 | r6)"),
        ("Benevolence", None, "Go down to the ground floor and use the bathroom down there.", "F r2"),
        ("Benevolence", None, "Go to the top floor. Check a bathroom there.", "F(r4 | r6)"),
        ("Benevolence", None, "Go up to the top floor and check every bathroom there.", "F r4 & F r6"),
        ("Collierville", None, "Go up to the top floor and use a toilet there.",
         "F((o36 & r4) | (o37 & r4))"),
        ("Collierville", None, "Go to floor 1 and check a bathroom on that floor.", "F r2"),
        ("Collierville", None, "Go to the middle floor, then check the bathroom.", "F r2"),
        # 'go upstairs and ...' with the start floor known: every goal of that action upstairs / downstairs
        ("Benevolence", 0, "Go upstairs, then check a bathroom there.", "F(r4 | r6)"),
        ("Collierville", 2, "Head downstairs and check the bathroom and the kitchen.", "F r2 & F r15"),
    ],
)
def test_floor_back_references_read(scene, start, text, gold):
    b = building(scene)
    means(text, gold, b, start)


@pytest.mark.parametrize(
    ("scene", "start", "text", "fragment"),
    [
        # 'a <room> there' after a room: rooms are not inside rooms (it was silently dropped before)
        ("Benevolence", None, "Go to the bedroom with the teddy bear and check a bathroom there.",
         "not a floor"),
        # 'there' could be the floor or a place named after it
        ("Collierville", None,
         "Go to the top floor. Then the bedroom with the plant, and use the toilet there.",
         "could refer back to 'the top floor' or to 'the bedroom with the plant'"),
        ("Benevolence", None, "Go to the top floor. Go to the kitchen, then a bathroom up there.",
         "could refer back to 'the top floor' or to 'the kitchen'"),
        ("Benevolence", None, "Go to the top floor. Go to the kitchen, then a bathroom on the same floor.",
         "could refer back to 'the top floor' or to 'the kitchen'"),
        # upstairs with the start unknown in a three-floor building
        ("Benevolence", None, "Go upstairs and use the bathroom.", "depends on where the robot starts"),
    ],
)
def test_floor_back_references_refused(scene, start, text, fragment):
    refused(text, fragment, building(scene), start)
