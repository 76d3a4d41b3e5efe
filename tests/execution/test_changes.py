"""The typed scene changes and their YAML / JSON form: every kind reads back what it writes, and bad
changes are refused naming the change, the field and what it must be."""

from __future__ import annotations

import pytest

from sgplan.errors import SceneError
from sgplan.execution.changes import (
    AddObject,
    Area,
    Block,
    CloseDoor,
    MoveObject,
    NewSceneGraph,
    OpenDoor,
    RemoveObject,
    ScheduledChange,
    Trigger,
    Unblock,
    change_from_dict,
    changes_document,
    changes_from_document,
    read_changes,
)

EVERY_KIND = [
    CloseDoor(("kitchen", "corridor on floor 0")),
    OpenDoor(("room_4", "room_2")),
    Block(Area(0, box_m=(1.0, 2.0, 1.5, 2.5)), "trolley"),
    Block(Area(1, polygon_m=((0.0, 0.0), (1.0, 0.0), (0.5, 1.0)))),
    Unblock(name="trolley"),
    Unblock(area=Area(0, box_m=(0.0, 0.0, 4.0, 4.0))),
    MoveObject("object_19", (3.0, 3.0)),
    MoveObject("chair in the dining room", (3.0, 3.0), floor=1),
    AddObject("trolley", (2.0, 4.0), 0, (0.5, 0.8), 1.2),
    RemoveObject("oven"),
    NewSceneGraph("later/export", 0.1),
]


@pytest.mark.parametrize("change", EVERY_KIND, ids=lambda c: c.kind)
def test_every_kind_reads_back_what_it_writes(change):
    assert change_from_dict(change.to_dict()) == change


def test_a_changes_document_round_trips_with_its_triggers():
    scheduled = [ScheduledChange(EVERY_KIND[0], Trigger(after_m=4.0)),
                 ScheduledChange(EVERY_KIND[2], Trigger(enter="kitchen")),
                 ScheduledChange(EVERY_KIND[6], Trigger(waypoint=3)), ScheduledChange(EVERY_KIND[9])]
    assert changes_from_document(changes_document(scheduled)) == scheduled


def test_a_yaml_file_is_read(tmp_path):
    path = tmp_path / "changes.yaml"
    path.write_text("version: 1\nchanges:\n  - kind: close_door\n    rooms: [kitchen, corridor]\n"
                    "    when: {after_m: 2}\n  - {kind: remove_object, object: object_19}\n")
    assert read_changes(path) == [ScheduledChange(CloseDoor(("kitchen", "corridor")), Trigger(after_m=2.0)),
                                  ScheduledChange(RemoveObject("object_19"))]


@pytest.mark.parametrize(("data", "message"), [
    ({"kind": "paint_wall"}, "change 1: unknown kind 'paint_wall'; use one of close_door"),
    ({"kind": "close_door", "rooms": ["kitchen"]},
     "change 1 (close_door): field 'rooms' must name two rooms"),
    ({"kind": "close_door", "rooms": ["kitchen", "kitchen"]}, "names the same room twice"),
    ({"kind": "close_door", "rooms": ["a", "b"], "colour": "red"},
     "unknown field(s) colour; a close_door takes rooms"),
    ({"kind": "block", "floor": 0, "box_m": [2, 0, 1, 1]},
     "field 'box_m' must be [x0, y0, x1, y1] with x0 < x1"),
    ({"kind": "block", "floor": 0, "box_m": [0, 0, 1, "x"]},
     "field 'box_m' must be a list of 4 finite numbers"),
    ({"kind": "block", "floor": 0}, "give the area as box_m"),
    ({"kind": "block", "floor": -1, "box_m": [0, 0, 1, 1]}, "field 'floor' must be a floor index >= 0"),
    ({"kind": "block", "floor": 0, "polygon_m": [[0, 0], [1, 1]]}, "at least 3 [x, y] vertices"),
    ({"kind": "unblock"}, "give the blocks to clear as name: or as an area"),
    ({"kind": "move_object", "object": "object_1", "to_xy_m": [1.0]}, "field 'to_xy_m' must be a list of 2"),
    ({"kind": "move_object", "object": " ", "to_xy_m": [1, 2]}, "field 'object' must not be empty"),
    ({"kind": "add_object", "category": "box", "at_xy_m": [1, 2], "floor": 0, "size_m": [0, 1]},
     "field 'size_m' must be two positive lengths"),
    ({"kind": "scene_graph", "scene": "x", "tolerance_m": -1}, "field 'tolerance_m' must be >= 0"),
    ({"kind": "remove_object", "object": "x", "when": {"after_m": -2}}, "field 'after_m' must be >= 0"),
    ({"kind": "remove_object", "object": "x", "when": {"after_m": 1, "waypoint": 2}}, "exactly one of"),
    ({"kind": "remove_object", "object": "x", "when": {"waypoint": 1.5}},
     "field 'waypoint' must be a waypoint"),
])
def test_bad_changes_are_refused_naming_what_is_wrong(data, message):
    with pytest.raises(SceneError) as error:
        changes_from_document({"version": 1, "changes": [data]})
    assert message in str(error.value)


def test_a_bad_document_is_refused(tmp_path):
    with pytest.raises(SceneError, match="version 2 is not supported"):
        changes_from_document({"version": 2, "changes": []})
    with pytest.raises(SceneError, match="field 'changes' must be a list"):
        changes_from_document({"changes": "close the door"})
    with pytest.raises(SceneError, match="unknown field"):
        changes_from_document({"changes": [], "extra": 1})
    path = tmp_path / "bad.yaml"
    path.write_text("changes: [\n")
    with pytest.raises(SceneError, match=r"bad.yaml: invalid YAML"):
        read_changes(path)


def test_the_json_schema_in_docs_lists_the_kinds_and_fields_the_reader_takes():
    import json
    from pathlib import Path

    from sgplan.execution.changes import _FIELDS, CHANGE_KINDS

    schema = json.loads((Path(__file__).parents[2] / "docs" / "changes.schema.json").read_text())
    variants = schema["$defs"]["change"]["oneOf"]
    kinds = {v["properties"]["kind"]["const"]: set(v["properties"]) - {"kind", "when"} for v in variants}
    assert set(kinds) == set(CHANGE_KINDS)
    assert kinds == _FIELDS
