"""Floor drawings: colours, the planner's path as it is, labels clear of markers and of each other,
legend / title / ticks / scale bar, direction arrows, reach regions, PNG and SVG, errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from matplotlib.quiver import Quiver
from PIL import Image

from sgplan.errors import SceneError
from sgplan.scene.demo import demo_building
from sgplan.scene.draw import MissionView, draw_building, draw_floor, floor_image, room_colour
from sgplan.scene.draw_path import arrow_marks, path_cells
from sgplan.scene.grid import build_occupancy_grid
from sgplan.scene.labels import label_raster
from sgplan.scene.model import CatCode
from tests.plans import REACH_M, TEXT, demo_plan


def _view() -> MissionView:
    d = demo_plan()
    return MissionView(
        text=TEXT,
        explanation="one line of explanation",
        cost_m=d.result.cost_m,
        propositions=d.mission.ordered_propositions,
        reach_radius_m=REACH_M,
    )


def test_floor_image_colours() -> None:
    building = demo_building()
    grid = build_occupancy_grid(building, building.robot_radius_m)
    floor = building.floors[0]
    image = floor_image(building, 0)
    assert image.shape == (*floor.shape, 3) and image.min() >= 0 and image.max() <= 1
    walls = image[floor.cat_map == CatCode.WALL]
    assert (walls.max(axis=1) < 0.3).all()  # dark
    outside = image[floor.cat_map == CatCode.OUTSIDE]
    assert (outside.min(axis=1) > 0.9).all()  # light
    kitchen = building.rooms_named("kitchen")[0]
    ground = (floor.room_map == kitchen.id) & (floor.cat_map == CatCode.GROUND)
    np.testing.assert_allclose(image[ground], np.broadcast_to(room_colour(kitchen.id), image[ground].shape))
    objects = image[floor.cat_map > 0]
    assert len(objects) and np.ptp(objects, axis=0).max() == 0  # one object colour
    shaded = floor_image(building, 0, grid)
    blocked = ground & ~grid.traversable[0]
    assert blocked.any() and (shaded[blocked].sum(axis=1) < image[blocked].sum(axis=1)).all()


def test_path_cells_accepts_rows_and_planner_arrays() -> None:
    d = demo_plan()
    cells = path_cells(d.result.path)  # (n, 4) with the automaton state
    assert cells.shape == (len(d.result.path), 3) and cells.dtype == np.int64
    np.testing.assert_array_equal(path_cells([tuple(c) for c in cells.tolist()]), cells)
    assert path_cells([]).shape == (0, 3)
    for bad in ([(1, 2)], np.zeros((3, 3)), [(1, 2, 3), (1, 2)]):
        with pytest.raises(SceneError, match="a path must be rows"):
            path_cells(bad)  # type: ignore[arg-type]


def test_draw_building_with_the_planner_path_png_and_svg(tmp_path: Path) -> None:
    d = demo_plan()
    written = draw_building(
        d.building,
        tmp_path / "out",
        grid=d.grid,
        path=d.result.path,
        mission=_view(),
        stem="plan",
        formats=("png", "svg"),
    )
    assert [p.name for p in written] == ["plan_0.png", "plan_0.svg", "plan_1.png", "plan_1.svg"]
    pictures = []
    for png in written[::2]:
        with Image.open(png) as image:
            assert image.format == "PNG" and image.width > 800 and image.height > 800
            pictures.append(np.asarray(image.convert("RGB")).astype(int))
    blue = [((p[..., 2] > 150) & (p[..., 0] < 60) & (p[..., 1] < 100)).sum() for p in pictures]
    red = [((p[..., 0] > 180) & (p[..., 1] < 60) & (p[..., 2] < 60)).sum() for p in pictures]
    # The path starts (blue) on floor 0 and ends (red, with the red end marker) on floor 1.
    assert blue[0] > 50 and red[1] > 50 and blue[0] > blue[1] and red[1] > red[0]
    svg = written[1].read_text(encoding="utf-8")
    assert "<svg" in svg and "stairs up" in svg and "corridor" in svg  # text kept as text


def _label_boxes(fig, ax) -> list[tuple[str, tuple[float, float, float, float]]]:
    renderer = fig.canvas.get_renderer()
    out = []
    for text in ax.texts:
        if text.get_bbox_patch() is None or " m (" in text.get_text():
            continue
        extent = text.get_window_extent(renderer)
        out.append((text.get_text(), (extent.x0, extent.y0, extent.x1, extent.y1)))
    return out


@pytest.mark.parametrize("floor", [0, 1])
def test_labels_clear_markers_and_each_other(floor: int) -> None:
    d = demo_plan()
    fig = draw_floor(d.building, floor, grid=d.grid, path=d.result.path, mission=_view())
    ax = fig.axes[0]
    boxes = _label_boxes(fig, ax)
    assert len(boxes) >= 10 and any("corridor" in t for t, _ in boxes)
    cells = path_cells(d.result.path)
    f = d.building.floors[floor]
    markers = [tuple(c[:2]) for c in (cells[0], cells[-1]) if c[2] == floor]
    markers += [end.portal for end in (f.up_stairs, f.down_stairs) if end is not None]
    assert markers
    x0, y0, x1, y1 = ax.bbox.extents
    for k, (text, (a0, b0, a1, b1)) in enumerate(boxes):
        assert x0 - 1 <= a0 and a1 <= x1 + 1 and y0 - 1 <= b0 and b1 <= y1 + 1, f"{text!r} leaves the map"
        for r, c in markers:
            mx, my = ax.transData.transform((r, c))  # drawing coordinates: x = row, y = column
            assert not (a0 - 4 < mx < a1 + 4 and b0 - 4 < my < b1 + 4), (
                f"{text!r} covers the marker at {(r, c)}"
            )
        for other, (o0, p0, o1, p1) in boxes[:k]:
            overlap = max(0, min(a1, o1) - max(a0, o0)) * max(0, min(b1, p1) - max(b0, p0))
            assert overlap < 1.0, f"{text!r} overlaps {other!r}"


def test_legend_title_ticks_and_scale_bar() -> None:
    d = demo_plan()
    fig = draw_floor(d.building, 0, grid=d.grid, path=d.result.path, mission=_view())
    ax = fig.axes[0]
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    for entry in ("start", "stairs portal", "reach region (mission)", "mission room"):
        assert entry in legend
    assert "end" not in legend  # the path ends upstairs
    assert any(t.startswith("path") for t in legend)
    title = " ".join(t.get_text() for t in fig.texts)
    assert f"cost {d.result.cost_m:.2f} m" in title and "one line of explanation" in title
    assert "mission: Visit the bathroom" in title
    assert len(ax.get_xticks()) >= 3 and len(ax.get_yticks()) >= 3
    assert ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "y (m)"
    assert any(t.get_text() == "2 m (40 cells)" for t in ax.texts)  # 0.05 m cells: 2 m = 40 rows
    arrows = [c for c in ax.collections if isinstance(c, Quiver)]
    assert len(arrows) == 1 and arrows[0].N >= 5


@pytest.mark.parametrize("axes", ["metres", "cells"])
def test_ticks_say_metres_in_the_map_frame_or_cells(axes: str) -> None:
    building = demo_building()
    f = building.floors[0]
    ax = draw_floor(building, 0, axes=axes).axes[0]
    rows, cols = f.shape
    assert ax.get_xlim() == (-0.5, rows - 0.5) and ax.get_ylim() == (-0.5, cols - 0.5)  # y grows upwards
    for ticks, axis in ((ax.get_xticks(), 0), (ax.get_yticks(), 1)):
        labels = [t.get_text() for t in (ax.get_xticklabels() if axis == 0 else ax.get_yticklabels())]
        assert len(ticks) >= 3
        for position, label in zip(ticks, labels, strict=True):
            label = label.replace("\N{MINUS SIGN}", "-")
            if axes == "metres":  # the metric coordinate of that place: origin + (index + 0.5) * resolution
                metres = f.origin_m[axis] + (position + 0.5) * f.resolution_m[axis]
                assert float(label) == pytest.approx(metres)
            else:
                assert float(label) == position
    titles = ("x (m)", "y (m)") if axes == "metres" else ("row", "column")
    assert (ax.get_xlabel(), ax.get_ylabel()) == titles
    with pytest.raises(SceneError, match="unknown drawing axes 'feet'"):
        draw_floor(building, 0, axes="feet")


def test_a_ros_map_is_drawn_as_its_image_shows_it(tmp_path: Path) -> None:
    """x to the right, y upwards, like the map image and RViz: a block in the image's top-left corner is in
    the picture's top-left corner (it was in the top-right, the map turned by 90 degrees)."""
    from sgplan.importers.assemble import Settings
    from sgplan.importers.ros import import_ros_map

    image = np.full((60, 100), 254, np.uint8)  # 5 m (x, columns of the image) by 3 m (y, rows), 5 cm pixels
    image[:20, :30] = 0  # the top-left corner: x < 1.5 m, y > 2 m
    Image.fromarray(image).save(tmp_path / "map.pgm")
    (tmp_path / "map.yaml").write_text("image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n")
    (tmp_path / "rooms.yaml").write_text("rooms:\n- name: hall\n  polygon: [[0, 0], [5, 0], [5, 3], [0, 3]]")
    imported = import_ros_map(tmp_path / "map.yaml", tmp_path / "rooms.yaml", Settings(robot_radius_m=0.0))
    building = imported.building
    fig = draw_floor(building, 0)
    fig.canvas.draw()
    pixels = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)  # type: ignore[attr-defined]
    ax = fig.axes[0]
    f = building.floors[0]

    def shade(x_m: float, y_m: float) -> int:
        px, py = ax.transData.transform(f.xy_to_cell(x_m, y_m))  # the cell's (row, col) are (x, y) here
        return int(pixels[fig.canvas.get_width_height()[1] - int(py), int(px)].sum())

    box = ax.get_window_extent()
    top_left = shade(0.5, 2.5)
    assert top_left < 300 and shade(4.5, 2.5) > 600 and shade(0.5, 0.5) > 600  # dark wall, light hall
    px, py = ax.transData.transform(f.xy_to_cell(0.5, 2.5))
    assert px < box.x0 + box.width / 2 and py > box.y0 + box.height / 2  # it is in the top-left quarter


def test_long_missions_and_explanations_are_wrapped_never_cut() -> None:
    d = demo_plan()
    explanation = " ".join(["1. Go to the bathroom (room_5, floor 0) while not within reach of the sink."] * 6
                           + ["2. Never enter the living room (room_6, floor 0) or the kitchen (room_4)."])
    view = MissionView(text=TEXT * 3, explanation=explanation, cost_m=d.result.cost_m)
    for floor in (0, 1):
        fig = draw_floor(d.building, floor, grid=d.grid, path=d.result.path, mission=view)
        renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
        width, height = fig.canvas.get_width_height()
        for text in fig.texts:
            box = text.get_window_extent(renderer)
            assert box.x0 >= 0 and box.x1 <= width and box.y0 >= 0 and box.y1 <= height, text.get_text()
        said = " ".join(t.get_text() for t in fig.texts)
        assert " ".join(explanation.split()) in said and " ".join(("mission: " + TEXT * 3).split()) in said
        boxes = sorted((t.get_window_extent(renderer) for t in fig.texts), key=lambda b: -b.y1)
        legend = fig.axes[0].get_legend().get_window_extent(renderer)
        assert all(not (b.y0 < legend.y1 and b.y1 > legend.y0) for b in boxes)  # no text over the legend


def test_arrows_of_an_out_and_back_path_lie_on_both_sides() -> None:
    out = [(10, c) for c in range(41)]
    xy = np.array([(c, r) for r, c in out + out[::-1]], dtype=float)  # east along row 10, then back west
    centres, vectors, index = arrow_marks(xy, np.ones(len(xy), bool), spacing=10, length=3, lane=1)
    east, west = vectors[:, 0] > 0, vectors[:, 0] < 0
    assert east.sum() >= 3 and west.sum() >= 3 and (east | west).all()
    np.testing.assert_allclose(centres[east, 1], 11.0)  # right of eastward travel, rows growing down: below
    np.testing.assert_allclose(centres[west, 1], 9.0)
    np.testing.assert_allclose(np.hypot(*vectors.T), 3.0)
    assert (np.diff(index) > 0).all() and index[west].min() > index[east].max()
    up, _, _ = arrow_marks(xy, np.ones(len(xy), bool), spacing=10, length=3, lane=1, y_up=True)
    np.testing.assert_allclose(up[east, 1], 9.0)  # where y grows upwards, right of eastward travel is below


def test_reach_regions_are_shaded_exactly() -> None:
    d = demo_plan()
    view = _view()
    # The raster is drawn transposed (x = row, y = column: sgplan.scene.draw_axes).
    figures = (draw_floor(d.building, 0, mission=m) for m in (None, view))
    plain, shaded = (np.swapaxes(np.asarray(fig.axes[0].images[0].get_array()), 0, 1) for fig in figures)
    reach = [p for p in view.propositions if p.kind == "reach"]
    expected = label_raster(d.building, reach, REACH_M)[0] > 0
    assert expected.any()
    np.testing.assert_array_equal((plain != shaded).any(axis=2), expected)


def test_draw_errors(tmp_path: Path) -> None:
    building = demo_building()
    with pytest.raises(SceneError, match="no floor 5"):
        draw_floor(building, 5)
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(SceneError, match="cannot create"):
        draw_building(building, blocker / "sub")
    with pytest.raises(SceneError, match="cannot draw format"):
        draw_building(building, tmp_path, formats=("jpg",))
    with pytest.raises(SceneError, match="a path must be rows"):
        draw_building(building, tmp_path, path=[(1.5, 2.0, 0.0)])


@pytest.mark.gibson
def test_draw_benevolence(gibson_root: Path, tmp_path: Path) -> None:
    from sgplan.scene.authors import load_authors_scene

    building = load_authors_scene(gibson_root / "Benevolence")
    written = draw_building(building, tmp_path, grid=build_occupancy_grid(building, building.robot_radius_m))
    assert len(written) == 6 and all(p.stat().st_size > 20_000 for p in written)  # a PNG and an SVG a floor


def test_legend_lists_what_the_floor_shows() -> None:
    d = demo_plan()
    cells = path_cells(d.result.path)
    upstairs_only = cells[cells[:, 2] == 1]  # a path that never visits floor 0
    fig = draw_floor(d.building, 0, path=upstairs_only, mission=_view())
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "start" not in legend and "end" not in legend and not any(t.startswith("path") for t in legend)
    assert "reach region (mission)" in legend  # the sink and the chairs are on floor 0
    assert "the path does not come to this floor" in " ".join(t.get_text() for t in fig.texts)
    fig = draw_floor(d.building, 1, path=upstairs_only, mission=_view())
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert {"start", "end"} <= set(legend) and "reach region (mission)" not in legend


@pytest.mark.parametrize(("flag", "titles"), [([], ("x (m)", "y (m)")),
                                              (["--axes", "cells"], ("row", "column"))])
def test_inspect_draws_png_and_svg_with_the_chosen_axes(tmp_path: Path, flag: list[str],
                                                        titles: tuple[str, str]) -> None:
    from sgplan.cli import main

    assert main(["inspect", "demo", "--draw", str(tmp_path), "-q", *flag]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["floor_0.png", "floor_0.svg", "floor_1.png", "floor_1.svg"]
    svg = (tmp_path / "floor_0.svg").read_text(encoding="utf-8")
    assert all(f">{title}<" in svg for title in titles)
