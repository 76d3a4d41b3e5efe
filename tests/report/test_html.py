"""The HTML report: self-contained, right content, and working in a real headless browser."""

from __future__ import annotations

import base64
import io
import json
import re
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from PIL import Image

from sgplan.errors import OutputError
from sgplan.outputs.events import Event
from sgplan.report.html import report_html, write_html_report
from sgplan.scene.draw_path import path_cells
from tests.browser import browser as _browser
from tests.browser import launch, watch
from tests.plans import REACH_M, DemoPlan

EXPLANATION = (
    "First the bathroom, keeping away from its sink; then a dining chair; then the bedroom upstairs."
)


@pytest.fixture(scope="module")
def report(demo_plan: DemoPlan, tmp_path_factory: pytest.TempPathFactory) -> Path:
    d = demo_plan
    return write_html_report(
        tmp_path_factory.mktemp("report") / "plan.html",
        d.building,
        d.grid,
        d.result,
        d.mission,
        explanation=EXPLANATION,
        reach_radius_m=REACH_M,
        engine="matplotlib",
    )


def _data_uri_image(uri: str) -> np.ndarray:
    assert uri.startswith("data:image/png;base64,")
    with Image.open(io.BytesIO(base64.b64decode(uri.split(",", 1)[1]))) as image:
        return np.asarray(image.convert("RGBA"))


def test_report_is_self_contained_and_complete(report: Path, demo_plan: DemoPlan) -> None:
    page = report.read_text(encoding="utf-8")
    # Nothing is fetched: no external scripts, styles, images or links (SVG namespaces are names only).
    assert not re.search(r'(src|href)="(?!data:|#)', page)
    assert '<link rel="stylesheet"' not in page and "@import" not in page
    assert len(re.findall(r'class="floor-tab"', page)) == demo_plan.building.num_floors == 2
    assert EXPLANATION in page and "never enter the living room" in page
    assert 'id="cost-chart"' in page and 'id="transitions"' in page and "<svg" in page
    # The path is drawn on both floors (it takes the stairs), start on floor 0, end on floor 1.
    layers = re.findall(r'<div class="floor" data-floor="(\d)".*?</svg>', page, flags=re.DOTALL)
    assert layers == ["0", "1"]
    floor0, floor1 = page.split('<div class="floor" data-floor="1"')
    assert 'class="start"' in floor0 and 'class="end"' not in floor0.split('id="floors"')[1]
    assert 'class="end"' in floor1 and floor0.count('class="path"') and floor1.count('class="path"')
    # One chart point per iteration with a path.
    chart = page.split('id="cost-chart"')[1].split("</svg>")[0]
    assert chart.count('class="point"') == len(demo_plan.result.iterations)


def test_id_rasters_round_trip(report: Path, demo_plan: DemoPlan) -> None:
    """The hover lookup reads room and object ids back from PNGs: they must hold the exact ids."""
    page = report.read_text(encoding="utf-8")
    for floor in demo_plan.building.floors:
        layer = page.split(f'<div class="floor" data-floor="{floor.index}"')[1]
        rooms_uri = re.search(r'class="ids rooms" hidden alt="" src="([^"]+)"', layer).group(1)  # type: ignore[union-attr]
        objects_uri = re.search(r'class="ids objects" hidden alt="" src="([^"]+)"', layer).group(1)  # type: ignore[union-attr]
        for uri, expected in (
            (rooms_uri, np.maximum(floor.room_map, 0)),
            (objects_uri, np.maximum(floor.cat_map, 0)),
        ):
            rgba = _data_uri_image(uri).astype(np.int64)
            ids = rgba[..., 0] | rgba[..., 1] << 8 | rgba[..., 2] << 16
            assert (rgba[..., 3] == 255).all()
            # Shown in the map frame: pixel (down, across) is cell (row = across, col = cols - 1 - down).
            np.testing.assert_array_equal(ids, np.flipud(expected.T))
    entities = json.loads(page.split('id="sgplan-entities">')[1].split("</script>")[0])
    teddy = demo_plan.building.objects_named("teddy bear")[0]
    assert entities["objects"][str(teddy.id)] == {
        "name": "teddy bear",
        "key": teddy.key,
        "uuid": teddy.uuid,
        "floor": 1,
        "room": demo_plan.building.room(id=teddy.room_id).key,
    }


def test_report_without_path_and_write_errors(demo_plan: DemoPlan, tmp_path: Path) -> None:
    d = demo_plan
    failed = replace(d.result, path=None, cost_m=float("inf"), iterations=[], status="timeout")
    page = report_html(d.building, d.grid, failed, d.mission, engine="matplotlib")
    assert "no path" in page and "No iteration finished" in page and 'class="start"' not in page
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(OutputError, match="cannot write the HTML report"):
        write_html_report(blocker / "plan.html", d.building, d.grid, d.result, d.mission, engine="matplotlib")


def test_report_in_headless_chromium(report: Path, demo_plan: DemoPlan) -> None:
    sync_playwright, executable = _browser()
    building = demo_plan.building
    teddy = building.objects_named("teddy bear")[0]
    floor1 = building.floors[1]
    cells = np.argwhere(floor1.cat_map == teddy.id)
    row, col = (int(v) for v in cells[len(cells) // 2])
    with sync_playwright() as p:  # type: ignore[operator]
        browser = launch(p, executable)
        try:
            page = browser.new_page(viewport={"width": 1200, "height": 900})
            problems = watch(page)
            page.goto(report.as_uri())
            page.wait_for_selector(
                '#floors .floor[data-floor="1"][data-ready="true"]', state="attached", timeout=20_000
            )

            tabs = page.locator(".floor-tab")
            assert tabs.count() == 2
            assert page.locator("#explanation").inner_text() == EXPLANATION
            assert page.locator('.floor[data-floor="0"]').is_visible()
            assert not page.locator('.floor[data-floor="1"]').is_visible()
            assert page.locator('.floor[data-floor="0"] polyline.path').first.is_visible()
            assert page.locator('.floor[data-floor="0"] circle.start').is_visible()
            assert (
                page.locator("#cost-chart").is_visible() and page.locator(".automaton-svg svg").is_visible()
            )

            tabs.nth(1).click()
            assert page.locator('.floor[data-floor="1"]').is_visible()
            assert not page.locator('.floor[data-floor="0"]').is_visible()
            assert page.locator('.floor[data-floor="1"] rect.end').is_visible()
            assert tabs.nth(1).get_attribute("aria-selected") == "true"

            stage = page.locator('.floor[data-floor="1"] .stage')
            stage.scroll_into_view_if_needed()
            box = stage.bounding_box()
            assert box is not None
            rows, cols = floor1.shape
            assert box["width"] / box["height"] == pytest.approx(rows / cols, rel=0.01)  # x across, y up
            across, down = (row + 0.5) / rows, (cols - col - 0.5) / cols
            page.mouse.move(box["x"] + across * box["width"], box["y"] + down * box["height"])
            tooltip = page.locator("#tooltip")
            assert tooltip.is_visible()
            text = tooltip.inner_text()
            room = building.room(id=teddy.room_id)
            x_m, y_m = floor1.cell_to_xy((row, col))
            assert f"teddy bear ({teddy.key}, id {teddy.id}, floor 1)" in text
            assert f"room: {room.name} ({room.key}" in text
            assert f"x {x_m:.2f} m, y {y_m:.2f} m (row {row}, column {col}), floor 1" in text
            ticks = page.locator('.floor[data-floor="1"] svg.axes text.tick')
            assert ticks.count() >= 6 and ticks.first.is_visible()

            reach = page.locator('.floor[data-floor="0"] img.reach')
            assert reach.count() == 1 and reach.evaluate("e => getComputedStyle(e).display") != "none"
            page.locator("#show-reach").uncheck()
            assert reach.evaluate("e => getComputedStyle(e).display") == "none"
        finally:
            browser.close()
    assert problems == []


def test_events_are_listed_and_marked_on_their_floor(demo_plan: DemoPlan) -> None:
    d = demo_plan
    path = d.result.path
    assert path is not None
    first_up = int(np.flatnonzero(path[:, 2] == 1)[0])
    events = [
        Event(
            5,
            "proposition",
            1.0,
            int(path[5, 2]),
            int(path[5, 0]),
            int(path[5, 1]),
            "p1",
            "enter(room_2)",
            "corridor",
        ),
        Event(
            first_up,
            "state",
            9.0,
            1,
            int(path[first_up, 0]),
            int(path[first_up, 1]),
            from_state=1,
            to_state=2,
        ),
    ]
    with_events = SimpleNamespace(
        path=path,
        cost_m=d.result.cost_m,
        status=d.result.status,
        setup=d.result.setup,
        iterations=d.result.iterations,
        events=events,
    )
    page = report_html(d.building, d.grid, with_events, d.mission, engine="matplotlib")
    listed = page.split('<section id="events">')[1].split("</section>")[0]
    assert listed.count("<li>") == 2 and "enter(room_2) (corridor) became true" in listed
    floor0, floor1 = page.split('<div class="floor" data-floor="1"')
    assert floor0.count('class="event"') == 1 and floor1.count('class="event"') == 1
    assert "mission state 1 -&gt; 2" in floor1


def test_room_names_keep_off_the_start_and_end(report: Path, demo_plan: DemoPlan) -> None:
    page = report.read_text(encoding="utf-8")
    cells = path_cells(demo_plan.result.path)
    for cell in (cells[0], cells[-1]):
        cols = demo_plan.building.floors[int(cell[2])].shape[1]
        x_cell, y_cell = cell[0], cols - 1 - cell[1]  # the map frame: x = row, y = cols - 1 - col
        layer = page.split(f'<div class="floor" data-floor="{cell[2]}"')[1].split("</svg>")[0]
        names = re.findall(
            r'class="room-label" x="([\d.]+)" y="([\d.]+)" font-size="([\d.]+)"[^>]*>([^<]+)<', layer
        )
        assert len(names) >= 5
        for x, y, font, name in names:
            half_w, half_h = 0.31 * float(font) * len(name), 0.65 * float(font)
            assert abs(float(x) - x_cell) > half_w or abs(float(y) - y_cell) > half_h, (
                f"{name} covers {cell}"
            )
