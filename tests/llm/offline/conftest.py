"""The offline translator's tests: the demo building, shared by every test of this folder (other scenes
come from :func:`tests.shared_data.scene_building`, which skips without the Gibson data)."""

from __future__ import annotations

import pytest

from sgplan.scene.model import Building
from tests.shared_data import scene_building

# demo building (2 floors): floor 0: room_2 corridor, room_4 kitchen (object_15 refrigerator, object_16 oven,
# object_17 sink, object_18 microwave, object_19 bowl), room_5 bathroom (object_20 toilet, object_21 sink),
# room_6 living room (object_22 couch, object_23 tv, object_24 potted plant, object_25 vase, object_26
# clock), room_7 dining room (object_27 dining table, object_28/29 chairs, object_30 vase), room_8 staircase;
# floor 1: room_9 corridor, room_11 bedroom (object_31 bed, object_32 teddy bear, object_33 clock), room_12
# home office (object_34 chair, object_35 laptop, object_36 potted plant), room_13 bedroom (object_37 bed,
# object_38 chair, object_39 book), room_14 bathroom (object_40 toilet, object_41 sink, object_42 bottle).


@pytest.fixture(scope="session")
def demo() -> Building:
    """The embedded demo building."""
    return scene_building("demo")
