"""Issue 11's misreadings of the offline translator: each is now read as people mean it, or refused with a
reason naming the phrase (never a formula that silently means something else)."""

from __future__ import annotations

import pytest

from sgplan.scene.demo import demo_building
from sgplan.scene.model import Building
from tests.llm.offline_reading import means, refused

# demo building (2 floors): room_2 corridor, room_4 kitchen (object_15 refrigerator, object_17 sink,
# object_19 bowl), room_5 bathroom floor 0 (object_21 sink), room_6 living room (object_22 couch,
# object_26 clock), room_7 dining room, room_11 bedroom with the teddy bear (object_33 clock), room_12
# home office, room_13 bedroom with the book, room_14 bathroom floor 1.


@pytest.fixture(scope="module")
def demo() -> Building:
    return demo_building()


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Go to the kitchen, but first go to the bathroom on floor 1.", "F(r14 & F r4)"),
        ("Go to the kitchen, then the dining room, but first visit the home office.",
         "F(r12 & F(r4 & F r7))"),
        ("Firstly go to the home office. Secondly go to the kitchen.", "F(r12 & F r4)"),
        ("First, go to the home office. Second, go to the kitchen. Lastly, go to the dining room.",
         "F(r12 & F(r4 & F r7))"),
        ("Go to the kitchen. Before that, go to the home office.", "F(r12 & F r4)"),
        ("Go to the kitchen. First, go to the home office.", "F(r12 & F r4)"),
        ("Go to the living room, but go to the kitchen first.", "F(r4 & F r6)"),
        ("Go to the kitchen first, then the living room.", "F(r4 & F r6)"),
        ("Go to the living room and before that go to the kitchen.", "F(r4 & F r6)"),
    ],
)
def test_order_words_keep_their_order(demo, text, gold):
    means(text, gold, demo)


def test_ambiguous_before_that_is_refused(demo):
    refused("Go to the kitchen, then the dining room. Before that, visit the home office.",
            "not clear which of the earlier goals", demo)
    refused("Go to the kitchen. Go to the dining room. First, visit the home office.",
            "not clear which of the earlier goals", demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Go to the bedroom with the teddy bear while avoiding the kitchen.", "F r11 & G !r4"),
        ("Go to the bedroom with the teddy bear and avoid the kitchen.", "F r11 & G !r4"),
        ("Go to the bedroom with the teddy bear but avoid the kitchen.", "F r11 & G !r4"),
        ("Go to the bedroom with the teddy bear without entering the kitchen.", "F r11 & G !r4"),
        ("Go to the dining room, then the bedroom with the book, and avoid the kitchen.",
         "F(r7 & F r13) & G !r4"),
        # an object elsewhere: the local reading would say nothing, so it holds for the whole mission
        ("Go to the kitchen and avoid the couch.", "F r4 & G !o22"),
        # an object of the room the step is in keeps the authors' local reading
        ("Visit the bathroom on floor 0 and avoid the sink.", "F(r5 & !o21)"),
        ("Go to the kitchen without touching the bowl.", "F(r4 & !o19)"),
    ],
)
def test_trailing_avoidance_of_a_room_holds_for_the_whole_mission(demo, text, gold):
    means(text, gold, demo)


def test_an_object_is_not_taken_from_another_room(demo):
    message = refused("Go to the kitchen and sit on the couch.", "'the couch' is not in room_4 (kitchen)",
                      demo)
    assert "object_22 (couch in room_6, floor 0)" in message
    refused("In the kitchen, sit on the couch.", "'the couch' is not in room_4 (kitchen)", demo)
    refused("Sit on the couch in the kitchen.", "this scene has: object_22 (couch in room_6, floor 0)", demo)
    refused("Sit on the kitchen couch.", "this scene has: object_22 (couch in room_6, floor 0)", demo)
    # with 'then' the two are separate steps, and the couch is the living room's
    means("Go to the kitchen, then sit on the couch.", "F(r4 & F o22)", demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Open the refrigerator or the kitchen sink, then go to the living room.", "F((o15 | o17) & F r6)"),
        ("Go to the fridge or the bathroom on floor 1, then the dining room.", "F((o15 | r14) & F r7)"),
        ("Wash the kitchen sink.", "F o17"),
    ],
)
def test_a_choice_followed_by_then_stays_a_choice(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Never ever enter the kitchen and visit the living room.", "G !r4 & F r6"),
        ("Visit the living room and don't ever enter the kitchen.", "F r6 & G !r4"),
    ],
)
def test_ever_after_a_negation(demo, text, gold):
    means(text, gold, demo)


def test_upstairs_and_downstairs(demo):
    # a two-floor building: upstairs is floor 1, downstairs floor 0, whatever the start
    means("Go to the bathroom upstairs.", "F r14", demo)
    means("Go upstairs to the bathroom, then downstairs to the kitchen.", "F(r14 & F r4)", demo)
    means("Clean the upstairs bathroom.", "F r14", demo)
    refused("Go upstairs.", "expected a room or object after 'upstairs'", demo)
    # with a known start floor it is relative to it
    means("Go to the bathroom downstairs.", "F r5", demo, 1)
    refused("Go to the bathroom upstairs.", "the robot starts on floor 1", demo,
            1)


@pytest.mark.gibson
def test_upstairs_without_a_start_in_a_taller_building_is_refused(gibson_root):
    from sgplan.scene.authors import load_authors_scene

    building = load_authors_scene(gibson_root / "Benevolence")
    refused("Go to the corridor upstairs.", "the building 'Benevolence' has floors 0 to 2", building)
    means("Go to the bedroom with the tv upstairs.", "F r8", building, 1)


def test_the_other(demo):
    means("Go to the bedroom with the book, then the other bedroom.", "F(r13 & F r11)", demo)
    means("Touch the sink in the kitchen, then the other sinks.", "F(o17 & F o21 & F o41)", demo)
    refused("Go to the other bedroom.", "no bedroom was named before it", demo)
    means("Visit the bedroom with the book and then the other one.", "F(r13 & F r11)", demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Go to the living room only after you have been in the kitchen.", "F r6 & (!r6 U r4)"),
        ("Only after you have been in the kitchen, go to the living room.", "F r6 & (!r6 U r4)"),
        ("Only once you have visited the kitchen, go to the living room.", "F r6 & (!r6 U r4)"),
    ],
)
def test_only_after(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Whenever you enter the kitchen, open the fridge.", "G(r4 -> F o15)"),
        ("Open the fridge whenever you enter the kitchen.", "G(r4 -> F o15)"),
        ("Every time you visit the living room, go to the dining room afterwards. Visit the kitchen.",
         "G(r6 -> F r7) & F r4"),
        ("Whenever you enter a bathroom, visit the kitchen.", "G((r5 | r14) -> F r4)"),
    ],
)
def test_whenever_is_a_response(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Water the plant in the office. If you ever walk into the dining room, check the sink "
         "upstairs later.",
         "F o36 & G(r7 -> F o41)"),
        ("If you enter the living room at some point, sit on the couch afterwards.", "G(r6 -> F o22)"),
        ("If you pass through the kitchen, go to the bedroom with the book after that.", "G(r4 -> F r13)"),
        ("Open the fridge afterwards if you ever end up in the dining room.", "G(r7 -> F o15)"),
        ("Visit the bathroom on floor 1 if you visit the kitchen at any time.", "G(r4 -> F r14)"),
        # without those words the condition is one event: "if X happens (at all), Y"
        ("If you visit the kitchen, then take the bowl.", "F r4 -> F o19"),
    ],
)
def test_a_condition_about_every_visit_is_a_response(demo, text, gold):
    means(text, gold, demo)


def test_a_response_to_several_places_is_refused(demo):
    refused("If you ever go to the kitchen and the bedroom with the book, visit the office afterwards.",
            "with one room or object", demo)
    means("If at some point you go into the office, touch the teddy bear.", "G(r12 -> F o32)", demo)


@pytest.mark.parametrize(
    "text",
    ["If you enter the office after the kitchen, sit on the couch.",
     "If you go to the dining room and sit on a chair, wash the bowl afterwards."],
)
def test_a_condition_of_more_than_one_action_is_refused(demo, text):
    refused(text, "a condition is one action", demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Visit the kitchen twice.", "F(r4 & F(!r4 & F r4))"),
        ("Visit the kitchen two times.", "F(r4 & F(!r4 & F r4))"),
        ("Go to the kitchen, then go to the kitchen again.", "F(r4 & F(!r4 & F r4))"),
        ("Go to the kitchen, then the living room, then the kitchen again.", "F(r4 & F(r6 & F r4))"),
        ("Go to the kitchen, then the living room, then go back to the kitchen.", "F(r4 & F(r6 & F r4))"),
        ("Take the bowl, then go to the dining room, then return to the bowl.", "F(o19 & F(r7 & F o19))"),
    ],
)
def test_again_and_twice_are_new_visits(demo, text, gold):
    means(text, gold, demo)


def test_again_without_an_ordered_first_visit_is_refused(demo):
    refused("Visit the kitchen again.", "'the kitchen again': it was not a goal before", demo)
    refused("Visit the kitchen. Visit it again.", "needs the first visit earlier in the same sequence", demo)
    refused("Visit the kitchen nine times.", "at most 5 repeated visits", demo)


def test_this_floor_is_the_start_floor(demo):
    means("Go to the bathroom on this floor.", "F r5", demo, 0)
    refused("Go to the bathroom on this floor.", "'this floor' depends on where the robot starts", demo)


# ---- more everyday constructs, read as people mean them (or refused with the phrase named)

@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Take the bowl in the kitchen to the dining room.", "F(o19 & F r7)"),
        ("Bring the bowl to the dining table.", "F(o19 & F o27)"),
        ("Sit on one of the dining room chairs.", "F(o28 | o29)"),
        ("Read my book.", "F o39"),
        ("Go to the bedroom that doesn't have a book.", "F r11"),
        ("Go to the bedroom with no teddy bear.", "F r13"),
        ("Go to the ground floor bathroom.", "F r5"),
        ("Visit the top floor.", "F(r9 | r11 | r12 | r13 | r14)"),
        ("Never go up to the top floor. Visit the kitchen.", "G(!r9 & !r11 & !r12 & !r13 & !r14) & F r4"),
        ("Go to the bathroom on floor 0 and avoid the sink the whole time.", "F r5 & G !o21"),
        ("Only after you have opened the fridge may you go into the living room.", "F r6 & (!r6 U o15)"),
        ("I do want you to visit the kitchen.", "F r4"),
        ("Go to the living room, but not before you have been in the kitchen.", "F r6 & (!r6 U r4)"),
        ("Get something from the fridge.", "F o15"),
        ("Walk from the kitchen to the living room.", "F(r4 & F r6)"),
        ("Go to the kitchen for the bowl.", "F o19"),
        ("Whenever you enter the kitchen, go to the dining room after.", "G(r4 -> F r7)"),
        ("Go to the living room, and stay out of the kitchen until you get there.", "F r6 & (!r4 U r6)"),
        ("Go to the living room and look at the tv there.", "F o23"),
        ("Go to the living room, but stop by the kitchen before that.", "F(r4 & F r6)"),
        ("Go upstairs and check the sink.", "F o41"),
        ("Visit the kitchen or the dining room, I don't care which.", "F(r4 | r7)"),
        ("Visit the kitchen and the living room, any order.", "F r4 & F r6"),
        ("Open the fridge and the oven in either order, then go to the couch.",
         "F(o15 & F o22) & F(o16 & F o22)"),
        ("Use the toilet in the bathroom attached to the kitchen.", "F o20"),
    ],
)
def test_everyday_constructs(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("Wash your hands in the kitchen.", "no room or object of this scene is called 'hands'"),
        ("Go to the bathroom on the middle floor.", "has 2 floors (0 to 1), so no middle one"),
        ("Go to the bedroom that doesn't have a bed.",
         "'the bedroom that doesn't have a bed' matches no room"),
        ("Go to the dining room but not the kitchen.", "'the kitchen' is not one of 'the dining room'"),
    ],
)
def test_everyday_constructs_refused(demo, text, fragment):
    refused(text, fragment, demo)


@pytest.mark.gibson
def test_everyday_constructs_in_gibson_scenes(gibson_root):
    from sgplan.scene.authors import load_authors_scene

    allensville = load_authors_scene(gibson_root / "Allensville")
    means("Go to the bedroom that only has a bed in it.", "F r5", allensville)
    # issue 11: "the couch in the lobby" where the lobby has no couch never picks another room's couch
    for text in ("Sit on the couch in the lobby.", "Go to the lobby and sit on the couch."):
        assert "object_40 (couch in room_12, floor 0)" in refused(text, "couch", allensville)
    benevolence = load_authors_scene(gibson_root / "Benevolence")
    means("Go to the bedroom with the two beds.", "F r8", benevolence)
    # to avoid, "the stairs" is every staircase when the mission stays on some floors (the others are
    # forbidden anyway); otherwise all of them or those of the floors used differ, so which is asked
    refused("Go to the fridge while avoiding the stairs.", "'the stairs' matches 2 rooms", benevolence)
    means("Keep to the top floor and off the stairs, and visit each bathroom there.",
          "F r4 & F r6 & G !(r2 | r9 | r14 | r17 | r18 | r10 | r13 | r15 | r16 | r19)", benevolence)
    means("Use the fridge and keep off the stairs on floor 1.", "F o28 & G !r19", benevolence)
    refused("Go to the stairs while avoiding the kitchen.", "'the stairs' matches 2 rooms", benevolence)
    means("Go downstairs to the lobby.", "F r17", benevolence, 2)
    collierville = load_authors_scene(gibson_root / "Collierville")
    means("Use the toilet on the middle floor.", "F o38", collierville)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Once you have been to the office, sit on the couch.", "F(r12 & F o22)"),
        ("Sit on the couch once you have been to the office.", "F(r12 & F o22)"),
        ("Open the fridge, and once you are done, wash the bowl.", "F(o15 & F o19)"),
        ("Touch the teddy bear. When you have finished with that, go to the dining room.", "F(o32 & F r7)"),
        ("When done with the office, head to the bathroom on floor 0.", "F(r12 & F r5)"),
        ("Go to the dining room after you are done with the living room.", "F(r6 & F r7)"),
        ("Sit on the couch. Stay out of the kitchen until you have done that.", "F o22 & (!r4 U o22)"),
    ],
)
def test_once_and_done_are_sequences(demo, text, gold):
    means(text, gold, demo)


def test_when_without_a_clear_reading_is_refused(demo):
    refused("When you reach the kitchen, open the fridge.", "say which", demo)
    refused("Never enter the office until you have done that.", "'done that' does not refer", demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Sit on the couch first and wash the bowl.", "F(o22 & F o19)"),
        ("Visit the dining room and the office, the office first.", "F(r12 & F r7)"),
    ],
)
def test_a_trailing_first_orders_what_follows(demo, text, gold):
    means(text, gold, demo)


def test_unclear_first_and_repeated_phrases_are_refused(demo):
    refused("Go to the office. Go to the kitchen first.", "trailing 'first'", demo)
    refused("Visit the kitchen, the office and the kitchen.", "named twice", demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Head to a bathroom, either one works.", "F(r5 | r14)"),
        ("Sit on one of the chairs in the dining room, whichever you like, then watch the TV.",
         "F((o28 | o29) & r7 & F o23)"),
        ("Wash the bowl, then go to a bedroom, any one, then the office.", "F(o19 & F((r11 | r13) & F r12))"),
        ("Could you sit on the couch and open the fridge? The order doesn't matter.", "F o22 & F o15"),
        ("I need you to wash the bowl. Make sure that you never enter the dining room.", "F o19 & G !r7"),
        ("Open the fridge, wash the bowl (in any order), then go to the office.",
         "F(o15 & F r12) & F(o19 & F r12)"),
        ("Touch the sink in the bathroom on floor 1, then the one in the bathroom on floor 0.",
         "F(o41 & r14 & F(o21 & r5))"),
        ("Sit on the couch. Don't ever go upstairs.", "F o22 & G(!r9 & !r11 & !r12 & !r13 & !r14)"),
        ("Open the fridge, and stay out of the dining room on the way.", "F o15 & G !r7"),
    ],
)
def test_everyday_wrappers_choices_and_asides(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("Visit the bedrooms, either one.", "which means each of them"),
        ("Go to the kitchen and maybe the office.", "'maybe'"),
        ("Open the fridge and try to sit on the couch.", "'try'"),
    ],
)
def test_choices_of_all_and_optional_goals_are_refused(demo, text, fragment):
    refused(text, fragment, demo)


def test_never_upstairs_from_the_start_floor(demo):
    means("Touch the teddy bear and never go downstairs.",
          "F o32 & G(!r2 & !r4 & !r5 & !r6 & !r7 & !r8)", demo,
          1)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("On your way to the office, wash the bowl and then sit on the couch.", "F(o19 & F(o22 & F r12))"),
        ("Wash the bowl, and on your way back up touch the teddy bear.", "F(o19 & F o32)"),
        ("Sit on the chairs in the dining room, both of them, then watch the TV.",
         "F(o28 & r7 & F o23) & F(o29 & r7 & F o23)"),
        ("Touch the sink in the ground-floor bathroom, then the toilet on the top floor.",
         "F(o21 & r5 & F o40)"),
        ("Visit the office, the kitchen and the dining room, in that order please.", "F(r12 & F(r4 & F r7))"),
    ],
)
def test_way_group_and_order_remarks(demo, text, gold):
    means(text, gold, demo)


def test_a_group_of_the_wrong_size_is_refused(demo):
    refused("Sit on the chairs in the dining room, all three of them.", "is 2, not 3", demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Head to the bedroom with the book via the office.", "F(r12 & F r13)"),
        ("Walk through the dining room to the living room, then open the fridge.", "F(r7 & F(r6 & F o15))"),
        ("Wash the bowl, then go to the office, passing through the bathroom on floor 1.",
         "F(o19 & F(r14 & F r12))"),
    ],
)
def test_waypoints_come_before_their_goal(demo, text, gold):
    means(text, gold, demo)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("Sit on the couch and the teddy bear via the kitchen.", "which of the goals"),
        ("Stay away from the kitchen after you sit on the couch.", "for part of the mission"),
        ("Open the fridge, then wash the bowl. The order doesn't matter.", "given in order"),
        ("Go to the office. Touch the teddy bear first.", "trailing 'first'"),
    ],
)
def test_partial_prohibitions_and_contradictory_order_are_refused(demo, text, fragment):
    refused(text, fragment, demo)


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Go to the bathroom on floor 0 and touch the sink in there.", "F r5 & F(o21 & r5)"),
        ("Watch the TV, then sit on the couch in there.", "F(o23 & F(o22 & r6))"),
        ("Dust the chairs in the dining room. Keep out of the office until both of them are done.",
         "F(o28 & r7) & F(o29 & r7) & (!r12 U (o28 & r7)) & (!r12 U (o29 & r7))"),
        ("Never enter the office until the kitchen and the dining room have been visited.",
         "(!r12 U r4) & (!r12 U r7)"),
    ],
)
def test_there_and_until_done(demo, text, gold):
    means(text, gold, demo)


def test_a_condition_may_open_with_and_or_but(demo):
    means("Touch the teddy bear. And every time you enter the kitchen, wash the bowl afterwards.",
          "F o32 & G(r4 -> F o19)", demo)
    means("Open the fridge. But if you ever go into the office, visit the dining room afterwards.",
          "F o15 & G(r12 -> F r7)", demo)


def test_up_there_is_the_floor_of_the_last_goal(demo):
    means("Touch the book and the teddy bear, then use the sink up there.", "F(o39 & F o41) & F(o32 & F o41)",
          demo)
    refused("Use the sink up there.", "'up there' does not refer", demo)


def test_on_your_way_there(demo):
    # before the one goal named last; after several goals it is not clear on the way to which
    means("Go to the office. On your way there, touch the teddy bear.", "F(o32 & F r12)", demo)
    refused("Go to the office and the kitchen. On your way there, touch the teddy bear.",
            "on the way to which", demo)


@pytest.mark.gibson
def test_new_constructs_in_gibson_scenes(gibson_root):
    from sgplan.scene.authors import load_authors_scene

    # Allensville: room_10 dining room, room_11 kitchen (object_15 oven, object_31/32 apples),
    # room_12 living room, room_13 lobby
    allensville = load_authors_scene(gibson_root / "Allensville")
    means("If you ever walk through the kitchen, touch the oven afterwards. Visit the lobby.",
          "G(r11 -> F o15) & F r13", allensville)
    means("On your way to the lobby, look at the oven.", "F(o15 & F r13)", allensville)
    means("Grab an apple, any one, then head to the dining room via the living room.",
          "F((o31 | o32) & F(r12 & F r10))", allensville)
    # Collierville from floor 1: downstairs is floor 0 (room_8, 13, 14, 17); object_27 fridge,
    # object_20 microwave; object_19 keyboard in the office room_14, object_31 cup
    collierville = load_authors_scene(gibson_root / "Collierville")
    means("Never go downstairs. Could you check the fridge and the microwave (in any order)?",
          "G(!r8 & !r13 & !r14 & !r17) & F o27 & F o20", collierville, 1)
    means("Check the keyboard in the office, and once you're done, look at the cup.",
          "F(o19 & r14 & F o31)", collierville)
    # Benevolence: object_35 teddy bear in the bedroom room_8, object_36 in the living room room_16
    benevolence = load_authors_scene(gibson_root / "Benevolence")
    means("Touch the teddy bear in the bedroom, then the one in the living room.",
          "F(o35 & r8 & F(o36 & r16))", benevolence)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("Wash the bowl and keep away from the office afterwards.", "for part of the mission"),
        ("Sit on the couch, then never go back there.", "never go back"),
        ("Never set foot in the dining room again.", "for part of the mission"),
        ("Begin in the office and finish in the kitchen.", "where the path starts or ends"),
        ("Touch the teddy bear and end up in the living room.", "where the path starts or ends"),
    ],
)
def test_prohibitions_after_a_visit_and_path_ends_are_refused(demo, text, fragment):
    refused(text, fragment, demo)


def test_start_by_and_end_up_in_a_condition_are_read(demo):
    means("Start by opening the fridge, then sit on the couch.", "F(o15 & F o22)", demo)
    means("Whenever you end up in the dining room, wash the bowl.", "G(r7 -> F o19)", demo)


def test_a_member_of_a_group_first_and_do_it_again(demo):
    means("Touch the clocks, the one in the bedroom first.", "F(o33 & r11 & F o26)", demo)
    refused("Touch the clocks and the one in the bedroom.", "named twice", demo)
    refused("Go to the office, then the kitchen. Do it twice.", "refers to what was done", demo)
    means("Do the kitchen first, then the office.", "F(r4 & F r12)", demo)


@pytest.mark.parametrize(
    "text",
    [
        "Sit on the couch in the living room, but only after you have been in the kitchen.",
        "Only after visiting the kitchen, go to the couch in the living room.",
        "Go to the kitchen, and only then to the couch in the living room.",
        "Check the TV. Only after that, go to the couch in the living room.",
    ],
)
def test_only_after_on_an_object_named_by_its_room_offers_both_readings(demo, text):
    """Not entering the living room before the kitchen, or not reaching the couch before it: they differ."""
    message = refused(text, "it can mean not entering the living room before that", demo)
    assert "'only enter the living room after ...'" in message
    assert "'reach the couch only after ...'" in message


@pytest.mark.parametrize(
    ("text", "gold"),
    [
        ("Only enter the living room after you have been in the kitchen.", "F r6 & (!r6 U r4)"),
        ("Only go to the couch once you have visited the kitchen.", "F o22 & (!o22 U r4)"),
        ("Reach the couch only after you have been in the kitchen.", "F o22 & (!o22 U r4)"),
        ("Go to the living room and the couch, but only after you have been in the kitchen.",
         "F r6 & F o22 & (!r6 U r4)"),
    ],
)
def test_only_after_said_of_one_thing(demo, text, gold):
    means(text, gold, demo)
