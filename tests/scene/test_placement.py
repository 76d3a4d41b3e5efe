"""Greedy label placement: free spots first, never over a taken box when there is room, soft points
avoided."""

from __future__ import annotations

import numpy as np

from sgplan.scene.placement import LabelPlacer


def _overlap(a: tuple[float, ...], b: tuple[float, ...]) -> float:
    return max(0.0, min(a[2], b[2]) - max(a[0], b[0])) * max(0.0, min(a[3], b[3]) - max(a[1], b[1]))


def test_free_anchor_keeps_the_label_centred() -> None:
    placer = LabelPlacer((0, 0, 200, 100))
    assert placer.place((100, 50), (40, 10)) == (80, 45, 120, 55)
    assert placer.boxes == [(80, 45, 120, 55)]


def test_labels_avoid_markers_and_each_other_and_stay_inside() -> None:
    placer = LabelPlacer((0, 0, 200, 100), gap=2)
    marker = (95, 45, 105, 55)
    placer.block(marker)
    boxes = [placer.place((100, 50), (40, 12)) for _ in range(6)]  # six labels all wanting the marker's spot
    for k, box in enumerate(boxes):
        assert _overlap(box, marker) == 0
        assert box[0] >= 0 and box[2] <= 200 and box[1] >= 0 and box[3] <= 100
        assert all(_overlap(box, other) == 0 for other in boxes[:k])
    # The first one sits next to the marker (in the first rings around it), not far away.
    centre = ((boxes[0][0] + boxes[0][2]) / 2, (boxes[0][1] + boxes[0][3]) / 2)
    assert abs(centre[0] - 100) <= 1.5 * (20 + 2) + 1e-9 and abs(centre[1] - 50) <= 1.5 * (6 + 2) + 1e-9


def test_near_the_border_the_label_moves_inside() -> None:
    placer = LabelPlacer((0, 0, 200, 100))
    box = placer.place((2, 2), (40, 10))
    assert box[0] >= 0 and box[1] >= 0


def test_no_room_left_takes_the_least_overlap() -> None:
    placer = LabelPlacer((0, 0, 50, 20))
    placer.block((0, 0, 50, 10))  # the top half is taken
    box = placer.place((25, 5), (30, 8))
    assert _overlap(box, (0, 0, 50, 10)) == 0  # the bottom half still fits
    crowded = LabelPlacer((0, 0, 50, 20))
    crowded.block((0, 0, 50, 20))
    box = crowded.place((25, 10), (30, 8))
    assert box[2] - box[0] == 30  # still a label of the right size, overlap unavoidable


def test_soft_points_are_avoided_when_cheap() -> None:
    points = np.column_stack([np.linspace(60, 140, 40), np.full(40, 50.0)])  # a path through the anchor
    placer = LabelPlacer((0, 0, 200, 100), soft_points=points)
    box = placer.place((100, 50), (40, 10))
    assert not (
        (points[:, 0] >= box[0])
        & (points[:, 0] <= box[2])
        & (points[:, 1] >= box[1])
        & (points[:, 1] <= box[3])
    ).any()
